// mujoco_probe: measures the MuJoCo world against exact solutions. Standalone (not in any CMake
// file); build by hand, for example (from the repository root, in a folder of your own):
//
//   g++ -std=c++20 -O2 -I. -Isrc -o /tmp/mujoco_probe engines/mujoco/mujoco_probe.cc
//       engines/mujoco/mujoco_world.cc engines/common/{engine_input,monitor,placement}.cc
//       src/scene/*.cc reference/*.cc -lmujoco
//
// (one command line; or link the built static libraries of the scene and the reference instead
// of their sources). Run it from the repository root (stack_scene= is a relative path).
//
// Runs
//   housner  Housner's single block (0.4 m x 1.2 m, 100 kg) released from theta1 = alpha / 2 at
//            rest, no base motion, g = 9.81, for 2.5 s, against its exact solution (integrated
//            here with RK4 at 1e-5 s and bisection of every impact to 1e-15 s; between impacts
//            I_O theta'' = -m g R sin(alpha sign(theta) - theta), at an impact the rate is
//            multiplied by e = 1 - 1.5 sin^2(alpha)) and against the reference model;
//   stack    the thesis's stack (scenes/thesis_free_rocking.toml) for 3 s against the reference
//            model,
// at each time step and contact model, through the Monitor as the harness does, and prints the
// largest angle errors over all steps, the first impacts and their rate ratios, what the monitor
// measured (penetration, slip, uplift, energy) and the wall time per simulated second.
//
// Arguments (key=value, all optional):
//   scenes=housner,stack  dts=1e-3,1e-4,1e-5  contacts=stiff,mujoco_default
//   stack_scene=scenes/thesis_free_rocking.toml
//   solimp=d0,d1,w,mid,pow  timeconst_steps=2  dampratio=1  friction=10  noslip=0
//   solver=newton|cg|pgs  iterations=100  tolerance=1e-10  integrator=euler|rk4|implicit
//   cone=pyramidal|elliptic  impratio=1  impacts=4 (impacts printed)  xml=1 (print the MJCF)
//   trace=0 (print theta1 and omega1 against the reference every this many s; 0: never)
//   window=1 (also the largest errors up to this time, s: before late small-amplitude rocking,
//   where an impact's timing error is a large angle error)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/mujoco/mujoco_settings.h"
#include "engines/mujoco/mujoco_world.h"
#include "reference/simulate.h"
#include "scene/ground_motion.h"
#include "scene/scene.h"

namespace rm = rockbench::mujoco;
using rockbench::EngineInput;

namespace {

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Housner's block, exact: RK4 at a fine step with every impact located by bisection.
struct Impact {
  double t_s = 0.0, omega_before = 0.0, omega_after = 0.0;
};

class ExactHousner {
 public:
  ExactHousner(double b, double h, double g, double theta0, double omega0, double step)
      : alpha_(std::atan(b / h)), step_(step), theta_(theta0), omega_(omega0) {
    const double r = std::hypot(b, h);
    p2_ = 3.0 * g / (4.0 * r);  // m g R / I_O with I_O = 4/3 m R^2
    e_ = 1.0 - 1.5 * std::sin(alpha_) * std::sin(alpha_);
    side_ = theta0 > 0.0 ? 1 : (theta0 < 0.0 ? -1 : (omega0 > 0.0 ? 1 : -1));
  }
  double e() const { return e_; }
  double alpha() const { return alpha_; }
  const std::vector<Impact>& impacts() const { return impacts_; }

  // State at t_target (>= the current time): theta, omega.
  void AdvanceTo(double t_target, double* theta, double* omega) {
    while (t_ < t_target) {
      const double h = std::min(step_, t_target - t_);
      double th = theta_, om = omega_;
      Rk4(side_, h, &th, &om);
      if (side_ * th < 0.0) {
        // Crossing inside the step: bisect the step length.
        double lo = 0.0, hi = h;
        for (int k = 0; k < 200 && hi - lo > 1e-16; ++k) {
          const double mid = 0.5 * (lo + hi);
          double a = theta_, w = omega_;
          Rk4(side_, mid, &a, &w);
          (side_ * a > 0.0 ? lo : hi) = mid;
        }
        double a = theta_, w = omega_;
        Rk4(side_, hi, &a, &w);
        const double tc = t_ + hi;
        impacts_.push_back({tc, w, e_ * w});
        theta_ = 0.0;
        omega_ = e_ * w;
        side_ = -side_;
        t_ = tc;
        continue;
      }
      theta_ = th;
      omega_ = om;
      t_ += h;
    }
    *theta = theta_;
    *omega = omega_;
  }

 private:
  void Rhs(int side, double th, double om, double* dth, double* dom) const {
    *dth = om;
    *dom = -p2_ * std::sin(side * alpha_ - th);
  }
  void Rk4(int side, double h, double* th, double* om) const {
    double k1t, k1o, k2t, k2o, k3t, k3o, k4t, k4o;
    Rhs(side, *th, *om, &k1t, &k1o);
    Rhs(side, *th + 0.5 * h * k1t, *om + 0.5 * h * k1o, &k2t, &k2o);
    Rhs(side, *th + 0.5 * h * k2t, *om + 0.5 * h * k2o, &k3t, &k3o);
    Rhs(side, *th + h * k3t, *om + h * k3o, &k4t, &k4o);
    *th += h / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    *om += h / 6.0 * (k1o + 2 * k2o + 2 * k3o + k4o);
  }

  double alpha_, step_, p2_ = 0.0, e_ = 0.0;
  double t_ = 0.0, theta_, omega_;
  int side_ = 1;
  std::vector<Impact> impacts_;
};

// ---------------------------------------------------------------------------------------------

struct Args {
  std::vector<std::string> scenes = {"housner", "stack"};
  std::vector<double> dts = {1e-3, 1e-4, 1e-5};
  std::vector<rm::ContactModel> contacts = {rm::ContactModel::kStiff,
                                            rm::ContactModel::kMujocoDefault};
  std::string stack_scene = "scenes/thesis_free_rocking.toml";
  rm::MujocoSettings base;
  int impacts = 4;
  double window_s = 1.0;
  double trace_s = 0.0;
  bool xml = false;
};

Args ParseArgs(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto eq = arg.find('=');
    if (eq == std::string::npos) {
      std::fprintf(stderr, "expected key=value: %s\n", arg.c_str());
      std::exit(2);
    }
    const std::string k = arg.substr(0, eq), v = arg.substr(eq + 1);
    auto bad = [&] {
      std::fprintf(stderr, "bad value: %s\n", arg.c_str());
      std::exit(2);
    };
    if (k == "scenes") {
      a.scenes = Split(v);
    } else if (k == "dts") {
      a.dts.clear();
      for (const auto& s : Split(v)) a.dts.push_back(std::stod(s));
    } else if (k == "contacts") {
      a.contacts.clear();
      for (const auto& s : Split(v)) {
        auto c = rm::ParseContactModel(s);
        if (!c) bad();
        a.contacts.push_back(*c);
      }
    } else if (k == "stack_scene") {
      a.stack_scene = v;
    } else if (k == "solimp") {
      const auto p = Split(v);
      if (p.size() != 5) bad();
      for (int j = 0; j < 5; ++j) a.base.stiff_solimp[j] = std::stod(p[j]);
    } else if (k == "timeconst_steps") {
      a.base.stiff_timeconst_steps = std::stod(v);
    } else if (k == "dampratio") {
      a.base.stiff_dampratio = std::stod(v);
    } else if (k == "friction") {
      a.base.friction = std::stod(v);
    } else if (k == "noslip") {
      a.base.noslip_iterations = std::stoi(v);
    } else if (k == "solver") {
      auto s = rm::ParseSolver(v);
      if (!s) bad();
      a.base.solver = *s;
    } else if (k == "iterations") {
      a.base.iterations = std::stoi(v);
    } else if (k == "tolerance") {
      a.base.tolerance = std::stod(v);
    } else if (k == "integrator") {
      auto s = rm::ParseIntegrator(v);
      if (!s) bad();
      a.base.integrator = *s;
    } else if (k == "cone") {
      auto s = rm::ParseCone(v);
      if (!s) bad();
      a.base.cone = *s;
    } else if (k == "impratio") {
      a.base.impratio = std::stod(v);
    } else if (k == "impacts") {
      a.impacts = std::stoi(v);
    } else if (k == "trace") {
      a.trace_s = std::stod(v);
    } else if (k == "window") {
      a.window_s = std::stod(v);
    } else if (k == "xml") {
      a.xml = v == "1";
    } else {
      std::fprintf(stderr, "unknown key: %s\n", k.c_str());
      std::exit(2);
    }
  }
  return a;
}

rockbench::Scene HousnerScene() {
  rockbench::Scene sc;
  sc.title = "Housner's block";
  sc.block1.width_m = 0.4;
  sc.block1.height_m = 1.2;
  sc.block1.depth_m = 1.0;
  sc.block1.mass_kg = 100.0;
  sc.initial.theta1_rad = 0.5 * std::atan(0.4 / 1.2);
  sc.run.duration_s = 2.5;
  sc.run.output_interval_s = 0.005;
  sc.run.gravity_mps2 = 9.81;
  rockbench::ValidateScene(sc);
  return sc;
}

struct RunResult {
  double err1 = 0.0, err2 = 0.0, err1_t = 0.0, err2_t = 0.0;  // max |theta error| and when
  double err1_exact = 0.0;                    // Housner only: against the RK4 exact solution
  double err1_early = 0.0, err2_early = 0.0;  // max |theta error| for t <= Args::window_s
  double wall_per_sim_s = 0.0;
  nlohmann::json summary, diagnostics;
  std::vector<rockbench::Event> events;
};

void Run(const Args& a, const std::string& name, const rockbench::Scene& scene,
         const rockbench::reference::Result& ref, rm::ContactModel contact, double dt) {
  const rockbench::GroundMotion motion = rockbench::GroundMotion::FromScene(scene);
  const EngineInput in =
      rockbench::MakeEngineInput(scene, motion, "mujoco", dt, rockbench::DriveKind::kInertial, 0.0);
  rm::MujocoSettings s = a.base;
  s.time_step_s = dt;
  s.contact = contact;
  const bool housner = name == "housner";
  std::unique_ptr<ExactHousner> exact;
  if (housner) {
    exact = std::make_unique<ExactHousner>(0.5 * scene.block1.width_m, 0.5 * scene.block1.height_m,
                                           scene.run.gravity_mps2, scene.initial.theta1_rad,
                                           scene.initial.omega1_radps, 1e-5);
  }
  RunResult r;
  rm::MujocoWorld world(in, s);
  if (a.xml && dt == a.dts.front()) std::printf("%s", world.xml().c_str());
  rockbench::Monitor monitor(in);
  monitor.Start(world.Read(0));
  double phi1 = 0.0, phi2 = 0.0;
  std::int64_t n = 0;
  for (; n < in.steps; ++n) {
    world.ApplyDrive(n);
    world.Step();
    const rockbench::StepReadout rd = world.Read(n + 1);
    // Angle errors at every step (unwrapped CCW angles; theta = -phi).
    phi1 += std::remainder(std::atan2(rd.block1.sin_phi, rd.block1.cos_phi) - phi1,
                           2.0 * std::numbers::pi);
    const double t = rd.t_s;
    const rockbench::Sample rs = ref.trajectory.At(t);
    const double e1 = std::abs(-phi1 - rs.theta1_rad);
    if (e1 > r.err1) r.err1 = e1, r.err1_t = t;
    if (t <= a.window_s) r.err1_early = std::max(r.err1_early, e1);
    if (in.two_blocks()) {
      phi2 += std::remainder(std::atan2(rd.block2.sin_phi, rd.block2.cos_phi) - phi2,
                             2.0 * std::numbers::pi);
      const double e2 = std::abs(-phi2 - rs.theta2_rad);
      if (e2 > r.err2) r.err2 = e2, r.err2_t = t;
      if (t <= a.window_s) r.err2_early = std::max(r.err2_early, e2);
    }
    if (a.trace_s > 0.0 && std::fmod(t + 0.5 * dt, a.trace_s) < dt) {
      std::printf("      trace t %.5f theta1 %+.8f ref %+.8f err %+.3e omega1 %+.6f ref %+.6f\n", t,
                  -phi1, rs.theta1_rad, -phi1 - rs.theta1_rad, -rd.block1.w_radps, rs.omega1_radps);
    }
    if (exact) {
      double th, om;
      exact->AdvanceTo(t, &th, &om);
      r.err1_exact = std::max(r.err1_exact, std::abs(-phi1 - th));
    }
    if (!monitor.Step(n + 1, rd)) {
      ++n;
      break;
    }
  }
  monitor.Finish();
  const double sim = static_cast<double>(n) * dt;
  {
    // Wall time of the run alone (world and monitor, as the harness's loop), without the error
    // bookkeeping above: a second, identical run.
    const auto t0 = std::chrono::steady_clock::now();
    rm::MujocoWorld w2(in, s);
    rockbench::Monitor m2(in);
    m2.Start(w2.Read(0));
    for (std::int64_t k = 0; k < n; ++k) {
      w2.ApplyDrive(k);
      w2.Step();
      if (!m2.Step(k + 1, w2.Read(k + 1))) break;
    }
    m2.Finish();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.wall_per_sim_s = sim > 0.0 ? wall / sim : 0.0;
  }
  r.summary = monitor.Summary();
  r.diagnostics = world.Diagnostics();
  r.events = monitor.history().events;

  const auto& v = r.summary["violations"];
  std::printf("%-7s %-14s dt %-6g | max|dth1| %.3e at %.4f s", name.c_str(),
              std::string(rm::ContactModelName(contact)).c_str(), dt, r.err1, r.err1_t);
  if (exact) std::printf(" (exact RK4: %.3e)", r.err1_exact);
  if (in.two_blocks()) std::printf(" | max|dth2| %.3e at %.4f s", r.err2, r.err2_t);
  std::printf(" | to %.2f s: %.3e", a.window_s, r.err1_early);
  if (in.two_blocks()) std::printf(", %.3e", r.err2_early);
  std::printf(" | %s, impacts %d (ref %d+%d)\n", r.summary["status"].get<std::string>().c_str(),
              r.summary["impacts"]["total"].get<int>(), ref.summary.impacts_ground,
              ref.summary.impacts_interface);
  std::printf("    penetration ground %.2e m", v["penetration_ground_max_m"].get<double>());
  if (in.two_blocks()) {
    std::printf(", interface %.2e m", v["penetration_interface_max_m"].get<double>());
  }
  std::printf(" | slip ground %.2e m (drift %.2e)", v["slip_ground_m"].get<double>(),
              v["drift_ground_max_m"].get<double>());
  if (in.two_blocks()) {
    std::printf(", interface %.2e m (drift %.2e)", v["slip_interface_m"].get<double>(),
                v["drift_interface_max_m"].get<double>());
  }
  std::printf(" | uplift ground %.2e m", v["uplift_ground_max_m"].get<double>());
  if (in.two_blocks()) std::printf(", interface %.2e m", v["uplift_interface_max_m"].get<double>());
  std::printf(" | energy gain %.2e rel\n", v["energy_gain_rel"].get<double>());
  std::printf("    wall %.3f s per simulated s | max contacts %d, max solver iterations %d",
              r.wall_per_sim_s, r.diagnostics["max_contacts"].get<int>(),
              r.diagnostics["max_solver_iterations"].get<int>());
  if (r.diagnostics["contact_buffer_full"].get<int>() ||
      r.diagnostics["constraint_buffer_full"].get<int>() || r.diagnostics["blown_up"].get<bool>()) {
    std::printf(" | DIAGNOSTICS %s", r.diagnostics.dump().c_str());
  }
  std::printf("\n");

  // First impacts: engine against the reference (and the exact ratio for Housner's block).
  int shown = 0;
  std::vector<const rockbench::Event*> ref_impacts;
  for (const auto& e : ref.history.events) {
    if (e.kind == "ground_impact" || e.kind == "interface_impact") ref_impacts.push_back(&e);
  }
  size_t ri = 0;
  for (const auto& e : r.events) {
    if (e.kind != "ground_impact" && e.kind != "interface_impact") continue;
    if (shown >= a.impacts) break;
    std::printf("    %-16s t %.5f", e.kind.c_str(), e.t_s);
    auto ratio = [](double after, double before) {
      return before != 0.0 ? after / before : std::nan("");
    };
    if (in.two_blocks()) {
      std::printf("  w1 %+.4f -> %+.4f, w2 %+.4f -> %+.4f", e.omega1_before, e.omega1_after,
                  e.omega2_before, e.omega2_after);
    } else {
      std::printf("  w1 %+.4f -> %+.4f ratio %.5f", e.omega1_before, e.omega1_after,
                  ratio(e.omega1_after, e.omega1_before));
    }
    if (ri < ref_impacts.size()) {
      const auto* f = ref_impacts[ri++];
      std::printf("   | ref %-16s t %.5f", f->kind.c_str(), f->t_s);
      if (in.two_blocks()) {
        std::printf("  w1 %+.4f -> %+.4f, w2 %+.4f -> %+.4f", f->omega1_before, f->omega1_after,
                    f->omega2_before, f->omega2_after);
      } else {
        std::printf("  w1 %+.4f -> %+.4f ratio %.5f", f->omega1_before, f->omega1_after,
                    ratio(f->omega1_after, f->omega1_before));
      }
    }
    std::printf("\n");
    ++shown;
  }
  if (exact && !exact->impacts().empty()) {
    std::printf("    exact (RK4) impacts:");
    for (size_t k = 0; k < exact->impacts().size() && k < static_cast<size_t>(a.impacts); ++k) {
      std::printf(" %.5f", exact->impacts()[k].t_s);
    }
    std::printf("  (%zu by %.1f s), ratio e = %.5f\n", exact->impacts().size(), sim, exact->e());
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = ParseArgs(argc, argv);
  const rm::MujocoSettings& b = a.base;
  std::printf(
      "MuJoCo probe: solver %s, iterations %d, tolerance %g, integrator %s, cone %s, "
      "friction %g, noslip %d, impratio %g; stiff: timeconst %g dt, dampratio %g, "
      "solimp (%g, %g, %g, %g, %g)\n",
      std::string(rm::SolverName(b.solver)).c_str(), b.iterations, b.tolerance,
      std::string(rm::IntegratorName(b.integrator)).c_str(),
      std::string(rm::ConeName(b.cone)).c_str(), b.friction, b.noslip_iterations, b.impratio,
      b.stiff_timeconst_steps, b.stiff_dampratio, b.stiff_solimp[0], b.stiff_solimp[1],
      b.stiff_solimp[2], b.stiff_solimp[3], b.stiff_solimp[4]);
  for (const auto& name : a.scenes) {
    rockbench::Scene scene;
    if (name == "housner") {
      scene = HousnerScene();
    } else if (name == "stack") {
      scene = rockbench::LoadScene(a.stack_scene, {"run.duration=3"});
    } else {
      std::fprintf(stderr, "unknown scene %s\n", name.c_str());
      return 2;
    }
    const rockbench::GroundMotion motion = rockbench::GroundMotion::FromScene(scene);
    const rockbench::reference::Result ref = rockbench::reference::Simulate(scene, motion);
    std::printf(
        "== %s: reference %s, %d ground + %d interface impacts, peak |theta1| %.5f, "
        "friction required ground %.3f, interface %.3f\n",
        name.c_str(), ref.summary.status.c_str(), ref.summary.impacts_ground,
        ref.summary.impacts_interface, ref.summary.peak_theta1_rad,
        ref.summary.friction_required_ground, ref.summary.friction_required_interface);
    for (auto contact : a.contacts) {
      for (double dt : a.dts) Run(a, name, scene, ref, contact, dt);
    }
  }
  return 0;
}
