// Standalone probe of the DART adapter (not built by CMake): runs Housner's single block and the
// thesis's free-rocking stack with DartWorld + Monitor and prints the angle errors against
//   - an exact solution of Housner's block (RK4 at 1e-6 s with bisection of the impacts), and
//   - the project's reference model (reference::Simulate), for both scenes.
//
// Build (by hand; the rockbench libraries compiled from the same tree):
//   g++ -std=c++20 -O2 -I. -Isrc -I/usr/include/eigen3 engines/dart/dart_probe.cc
//       engines/dart/dart_world.cc <rockbench scene, reference, engines/common objects>
//       -ldart -ldart-external-odelcpsolver -lfcl -lccd -lassimp -loctomap -lboost_filesystem
//       -ltomlplusplus
//
// Usage: dart_probe [single|stack|all|threads|--drives SCENE] [dt ...] [--collision dart|fcl]
// [--lcp dantzig|pgs]
//        [--erp X] [--erv X] [--cfm X] [--allowance X] [--friction X] [--stack-duration S]
//        [--csv FILE] (writes t, theta1 of the last single-block run for plotting)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/dart/dart_world.h"
#include "reference/simulate.h"
#include "scene/ground_motion.h"
#include "scene/scene.h"

using namespace rockbench;
using rockbench::dart_engine::DartSettings;
using rockbench::dart_engine::DartWorld;

namespace {

// ----- Exact Housner block: theta'' = -p^2 sin(alpha sgn(theta) - theta), e at each impact -----
struct Housner {
  double b, h, g;
  double R() const { return std::hypot(b, h); }
  double alpha() const { return std::atan(b / h); }
  double p2() const { return 3.0 * g / (4.0 * R()); }  // m g R / I_O, I_O = 4/3 m R^2
  double e() const {
    const double s = std::sin(alpha());
    return 1.0 - 1.5 * s * s;
  }
};

struct ExactSolution {
  std::vector<double> t, theta, omega;  // on a fine grid
  std::vector<double> impact_t, impact_w_before, impact_w_after;
  double dt = 0.0;
  double At(double time) const {  // linear interpolation on the fine grid (1e-6 s: < 1e-11 rad)
    if (time <= 0.0) return theta.front();
    const size_t i = static_cast<size_t>(time / dt);
    if (i + 1 >= t.size()) return theta.back();
    const double f = (time - t[i]) / dt;
    // An impact inside the interval: the angle is continuous, linear interpolation holds.
    return theta[i] + f * (theta[i + 1] - theta[i]);
  }
};

ExactSolution SolveHousner(const Housner& hb, double theta0, double duration, double dt) {
  const double p2 = hb.p2(), alpha = hb.alpha(), e = hb.e();
  int side = theta0 > 0 ? 1 : -1;
  auto acc = [&](double th) { return -p2 * std::sin(alpha * side - th); };
  auto rk4 = [&](double th, double w, double h, double* th1, double* w1) {
    const double k1t = w, k1w = acc(th);
    const double k2t = w + 0.5 * h * k1w, k2w = acc(th + 0.5 * h * k1t);
    const double k3t = w + 0.5 * h * k2w, k3w = acc(th + 0.5 * h * k2t);
    const double k4t = w + h * k3w, k4w = acc(th + h * k3t);
    *th1 = th + h / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    *w1 = w + h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  };
  ExactSolution s;
  s.dt = dt;
  const size_t n = static_cast<size_t>(std::ceil(duration / dt)) + 1;
  double th = theta0, w = 0.0, t = 0.0;
  s.t.push_back(0.0);
  s.theta.push_back(th);
  s.omega.push_back(w);
  for (size_t i = 1; i < n; ++i) {
    double rem = dt;
    while (rem > 0.0) {
      double th1, w1;
      rk4(th, w, rem, &th1, &w1);
      if (th1 * side < 0.0) {
        // Crossing inside: bisect the sub-step length on the RK4 map.
        double lo = 0.0, hi = rem;
        for (int k = 0; k < 80; ++k) {
          const double mid = 0.5 * (lo + hi);
          double thm, wm;
          rk4(th, w, mid, &thm, &wm);
          (thm * side > 0.0 ? lo : hi) = mid;
        }
        double thc, wc;
        rk4(th, w, hi, &thc, &wc);
        s.impact_t.push_back(t + (dt - rem) + hi);
        s.impact_w_before.push_back(wc);
        s.impact_w_after.push_back(wc * e);
        th = 0.0;
        w = wc * e;
        side = -side;
        rem -= hi;
        continue;
      }
      th = th1;
      w = w1;
      rem = 0.0;
    }
    t = static_cast<double>(i) * dt;
    s.t.push_back(t);
    s.theta.push_back(th);
    s.omega.push_back(w);
  }
  return s;
}

// ----- One engine run -----
struct RunResult {
  History history;
  nlohmann::json summary, settings, diagnostics;
  double wall_s = 0.0, sim_s = 0.0;
  std::size_t max_contacts = 0;
};

RunResult RunDart(const EngineInput& in, const DartSettings& s) {
  RunResult r;
  const auto start = std::chrono::steady_clock::now();
  DartWorld world(in, s);
  Monitor monitor(in);
  monitor.Start(world.Read(0));
  for (std::int64_t n = 0; n < in.steps; ++n) {
    world.ApplyDrive(n);
    world.Step();
    r.max_contacts = std::max(r.max_contacts, world.LastContactCount());
    if (!monitor.Step(n + 1, world.Read(n + 1))) break;
  }
  monitor.Finish();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.sim_s = monitor.last().t_s;
  r.summary = monitor.Summary();
  r.settings = world.Settings();
  r.diagnostics = world.Diagnostics();
  r.history = monitor.TakeHistory();
  return r;
}

void PrintDiagnostics(const RunResult& r) {
  std::printf("  dart: %s\n", r.diagnostics.dump().c_str());
}

void PrintViolations(const nlohmann::json& summary) {
  const nlohmann::json* v = nullptr;
  for (const char* key : {"violations", "model_violations"}) {
    if (summary.contains(key)) v = &summary[key];
  }
  if (v == nullptr) {
    std::printf("  summary: %s\n", summary.dump().c_str());
    return;
  }
  std::printf("  violations:");
  for (auto it = v->begin(); it != v->end(); ++it) {
    if (it->is_number()) std::printf(" %s=%.3g", it.key().c_str(), it->get<double>());
  }
  std::printf("\n");
}

void PrintImpacts(const History& h, const ExactSolution* exact, int count) {
  int k = 0;
  for (const Event& e : h.events) {
    if (e.kind != "ground_impact" && e.kind != "interface_impact") continue;
    const double ratio = e.omega1_before != 0.0 ? e.omega1_after / e.omega1_before : 0.0;
    std::printf("    %-16s t=%.6f  w1 %+.5f -> %+.5f  ratio1 %.6f", e.kind.c_str(), e.t_s,
                e.omega1_before, e.omega1_after, ratio);
    if (h.two_blocks) {
      std::printf("  w2 %+.5f -> %+.5f", e.omega2_before, e.omega2_after);
    }
    if (exact && static_cast<size_t>(k) < exact->impact_t.size()) {
      std::printf("  | exact t=%.6f dt=%+.2e", exact->impact_t[k], e.t_s - exact->impact_t[k]);
    }
    std::printf("\n");
    if (++k >= count) break;
  }
}

DartSettings g_settings;
std::string g_csv;    // --csv: t, theta1 (engine), theta1 (exact) of the single block
std::string g_scene;  // --drives: the scene file

void RunSingle(double dt) {
  const Housner hb{0.2, 0.6, 9.81};
  const double theta0 = 0.5 * std::atan(0.4 / 1.2);
  const double duration = 2.5;

  Scene scene;
  scene.block1 = BlockDef{0.4, 1.2, 1.0, 100.0, 0.0};
  scene.initial.theta1_rad = theta0;
  scene.run.duration_s = duration;
  scene.run.output_interval_s = 0.005;
  scene.run.gravity_mps2 = hb.g;
  const GroundMotion motion;
  const reference::Result ref = reference::Simulate(scene, motion);
  const EngineInput in = MakeEngineInput(scene, motion, "dart", dt, DriveKind::kInertial, 0.0);

  static ExactSolution exact;
  if (exact.t.empty()) exact = SolveHousner(hb, theta0, duration + 0.01, 1e-6);

  DartSettings s = g_settings;
  s.time_step_s = dt;
  const RunResult r = RunDart(in, s);
  double err_exact = 0.0, err_ref = 0.0, ref_vs_exact = 0.0;
  for (const Sample& x : r.history.samples) {
    err_exact = std::max(err_exact, std::abs(x.theta1_rad - exact.At(x.t_s)));
    err_ref = std::max(err_ref, std::abs(x.theta1_rad - ref.trajectory.At(x.t_s).theta1_rad));
    ref_vs_exact =
        std::max(ref_vs_exact, std::abs(ref.trajectory.At(x.t_s).theta1_rad - exact.At(x.t_s)));
  }
  std::printf(
      "single dt=%.0e: max|theta1 err| %.3e rad (exact), %.3e (reference); reference vs exact "
      "%.1e; wall %.3f s = %.3f s per simulated s; status %s; max contacts %zu\n",
      dt, err_exact, err_ref, ref_vs_exact, r.wall_s, r.wall_s / r.sim_s,
      r.summary.value("status", std::string("?")).c_str(), r.max_contacts);
  std::printf("  Housner e = %.6f; exact impacts %zu in %.1f s, engine impacts %d\n", hb.e(),
              exact.impact_t.size(), duration,
              r.summary.contains("impacts") ? r.summary["impacts"].value("total", -1) : -1);
  PrintImpacts(r.history, &exact, 6);
  PrintViolations(r.summary);
  PrintDiagnostics(r);
  if (!g_csv.empty()) {
    std::ofstream f(g_csv);
    f.precision(17);
    for (const Sample& x : r.history.samples) {
      f << x.t_s << "," << x.theta1_rad << "," << exact.At(x.t_s) << "\n";
    }
  }
}

double g_stack_duration = 3.0;

void RunStack(double dt) {
  Scene scene = LoadScene("scenes/thesis_free_rocking.toml");
  scene.run.duration_s = g_stack_duration;
  const GroundMotion motion = GroundMotion::FromScene(scene);
  const reference::Result ref = reference::Simulate(scene, motion);
  const EngineInput in = MakeEngineInput(scene, motion, "dart", dt, DriveKind::kInertial, 0.0);
  DartSettings s = g_settings;
  s.time_step_s = dt;
  const RunResult r = RunDart(in, s);
  double e1 = 0.0, e2 = 0.0;
  for (const Sample& x : r.history.samples) {
    const Sample y = ref.trajectory.At(x.t_s);
    e1 = std::max(e1, std::abs(x.theta1_rad - y.theta1_rad));
    e2 = std::max(e2, std::abs(x.theta2_rad - y.theta2_rad));
  }
  int ref_impacts = ref.summary.impacts_ground + ref.summary.impacts_interface;
  std::printf(
      "stack dt=%.0e (%.1f s): max|theta1 err| %.3e rad, max|theta2 err| %.3e rad; wall %.3f s "
      "= %.3f s per simulated s; status %s; impacts engine %d, reference %d; max contacts %zu\n",
      dt, g_stack_duration, e1, e2, r.wall_s, r.wall_s / r.sim_s,
      r.summary.value("status", std::string("?")).c_str(),
      r.summary.contains("impacts") ? r.summary["impacts"].value("total", -1) : -1, ref_impacts,
      r.max_contacts);
  std::printf("  reference friction required: ground %.3f interface %.3f\n",
              ref.summary.friction_required_ground, ref.summary.friction_required_interface);
  PrintImpacts(r.history, nullptr, 4);
  PrintViolations(r.summary);
  PrintDiagnostics(r);
}

// Inertial against kinematic drive on a scene with base motion: max |delta theta| between the
// two histories (the same mechanics when the kinematic path is exact).
void RunDrives(const std::string& scene_path, double dt) {
  Scene scene = LoadScene(scene_path);
  const GroundMotion motion = GroundMotion::FromScene(scene);
  const EngineInput in_i = MakeEngineInput(scene, motion, "dart", dt, DriveKind::kInertial, 0.0);
  const EngineInput in_k = MakeEngineInput(scene, motion, "dart", dt, DriveKind::kKinematic, 0.0);
  DartSettings s = g_settings;
  s.time_step_s = dt;
  const RunResult ri = RunDart(in_i, s);
  const RunResult rk = RunDart(in_k, s);
  const reference::Result ref = reference::Simulate(scene, motion);
  double d1 = 0.0, d2 = 0.0, e1 = 0.0, e2 = 0.0;
  double first_1e8 = -1.0, first_1e5 = -1.0;
  const size_t n = std::min(ri.history.samples.size(), rk.history.samples.size());
  for (size_t i = 0; i < n; ++i) {
    const Sample& a = ri.history.samples[i];
    const Sample& b = rk.history.samples[i];
    d1 = std::max(d1, std::abs(a.theta1_rad - b.theta1_rad));
    d2 = std::max(d2, std::abs(a.theta2_rad - b.theta2_rad));
    const double d =
        std::max(std::abs(a.theta1_rad - b.theta1_rad), std::abs(a.theta2_rad - b.theta2_rad));
    if (first_1e8 < 0.0 && d > 1e-8) first_1e8 = a.t_s;
    if (first_1e5 < 0.0 && d > 1e-5) first_1e5 = a.t_s;
    const Sample y = ref.trajectory.At(a.t_s);
    e1 = std::max(e1, std::abs(a.theta1_rad - y.theta1_rad));
    e2 = std::max(e2, std::abs(a.theta2_rad - y.theta2_rad));
  }
  std::printf(
      "drives %s dt=%.0e: inertial vs kinematic max|dtheta1| %.2e, max|dtheta2| %.2e (samples "
      "%zu/%zu); inertial vs reference %.2e / %.2e; status %s / %s; peak ground displacement "
      "%.3f m; wall %.2f / %.2f s\n",
      scene_path.c_str(), dt, d1, d2, ri.history.samples.size(), rk.history.samples.size(), e1, e2,
      ri.summary.value("status", std::string("?")).c_str(),
      rk.summary.value("status", std::string("?")).c_str(), in_k.drive.peak_x_m, ri.wall_s,
      rk.wall_s);
  std::printf("  drives differ by 1e-8 rad from t = %.3f s, by 1e-5 rad from t = %.3f s\n",
              first_1e8, first_1e5);
  // Sensitivity: the inertial drive with gravity changed by 1e-14 (relative).
  EngineInput in_g = in_i;
  in_g.run.gravity_mps2 *= 1.0 + 1e-14;
  const RunResult rg = RunDart(in_g, s);
  double g1 = 0.0, g2 = 0.0;
  for (size_t i = 0; i < std::min(n, rg.history.samples.size()); ++i) {
    g1 =
        std::max(g1, std::abs(ri.history.samples[i].theta1_rad - rg.history.samples[i].theta1_rad));
    g2 =
        std::max(g2, std::abs(ri.history.samples[i].theta2_rad - rg.history.samples[i].theta2_rad));
  }
  std::printf(
      "  inertial vs inertial with g * (1 + 1e-14): max|dtheta1| %.2e, max|dtheta2| %.2e; "
      "reference initiation at t = %.4f s\n",
      g1, g2, [&] {
        for (const Event& e : ref.history.events)
          if (e.kind == "initiation") return e.t_s;
        return -1.0;
      }());
  PrintViolations(ri.summary);
  PrintViolations(rk.summary);
}

// Two worlds stepping at once on two threads must give the same histories as one at a time.
void RunThreads(double dt) {
  Scene scene = LoadScene("scenes/harmonic.toml");
  scene.run.duration_s = 2.0;
  const GroundMotion motion = GroundMotion::FromScene(scene);
  const EngineInput in = MakeEngineInput(scene, motion, "dart", dt, DriveKind::kInertial, 0.0);
  DartSettings s = g_settings;
  s.time_step_s = dt;
  const RunResult serial = RunDart(in, s);
  std::vector<RunResult> par(2);
  std::thread t0([&] { par[0] = RunDart(in, s); });
  std::thread t1([&] { par[1] = RunDart(in, s); });
  t0.join();
  t1.join();
  bool same = true;
  for (const RunResult& r : par) {
    same = same && r.history.samples.size() == serial.history.samples.size();
    for (size_t i = 0; same && i < r.history.samples.size(); ++i) {
      same = r.history.samples[i].theta1_rad == serial.history.samples[i].theta1_rad &&
             r.history.samples[i].theta2_rad == serial.history.samples[i].theta2_rad;
    }
  }
  std::printf(
      "threads dt=%.0e: two concurrent worlds %s the serial run (wall %.2f s serial, "
      "%.2f / %.2f s in parallel)\n",
      dt, same ? "bit-identical to" : "DIFFER from", serial.wall_s, par[0].wall_s, par[1].wall_s);
  // Another world with other contact parameters while one lives: refused.
  DartWorld a(in, s);
  DartSettings other = s;
  other.erp = s.erp + 0.1;
  try {
    DartWorld b(in, other);
    std::printf("threads: a second world with another erp was NOT refused\n");
  } catch (const std::invalid_argument& e) {
    std::printf("threads: a second world with another erp is refused: %s\n", e.what());
  }
}

long PeakRssKb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::atol(line.c_str() + 6);
  }
  return -1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string what = "all";
  std::vector<double> dts;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "single" || a == "stack" || a == "all" || a == "threads") {
      what = a;
    } else if (a == "--drives") {
      what = "drives";
      g_scene = next();
    } else if (a == "--collision") {
      g_settings.collision =
          next() == "fcl" ? dart_engine::DartCollision::kFcl : dart_engine::DartCollision::kDart;
    } else if (a == "--lcp") {
      g_settings.lcp_solver =
          next() == "pgs" ? dart_engine::DartLcpSolver::kPgs : dart_engine::DartLcpSolver::kDantzig;
    } else if (a == "--erp") {
      g_settings.erp = std::stod(next());
    } else if (a == "--erv") {
      g_settings.max_erv_mps = std::stod(next());
    } else if (a == "--cfm") {
      g_settings.cfm = std::stod(next());
    } else if (a == "--allowance") {
      g_settings.error_allowance_m = std::stod(next());
    } else if (a == "--friction") {
      g_settings.friction = std::stod(next());
    } else if (a == "--no-fallback") {
      g_settings.pgs_fallback = false;
    } else if (a == "--pgs-iterations") {
      g_settings.pgs_iterations = std::stoi(next());
    } else if (a == "--stack-duration") {
      g_stack_duration = std::stod(next());
    } else if (a == "--csv") {
      g_csv = next();
    } else {
      dts.push_back(std::stod(a));
    }
  }
  if (dts.empty()) dts = {1e-3, 1e-4, 1e-5};
  std::printf(
      "settings: collision %s, lcp %s, erp %g, max erv %g m/s, cfm %g, allowance %g m, "
      "friction %g\n",
      dart_engine::DartCollisionName(g_settings.collision),
      dart_engine::DartLcpSolverName(g_settings.lcp_solver), g_settings.erp, g_settings.max_erv_mps,
      g_settings.cfm, g_settings.error_allowance_m, g_settings.friction);
  for (double dt : dts) {
    if (what == "single" || what == "all") RunSingle(dt);
    if (what == "stack" || what == "all") RunStack(dt);
    if (what == "drives") RunDrives(g_scene, dt);
    if (what == "threads") RunThreads(dt);
    std::fflush(stdout);
  }
  std::printf("peak RSS %ld kB\n", PeakRssKb());
  return 0;
}
