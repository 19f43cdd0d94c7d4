// ode_probe: accuracy probe of the ODE engine (not part of the CMake build). Runs
//  1. Housner's single block (B = 0.4 m, H = 1.2 m, 100 kg, released from theta1 = alpha / 2,
//     no base motion, g = 9.81) for 2.5 s against an exact solution (RK4 at 1e-6 s between
//     impacts, impacts located by bisection, Housner's rate ratio e = 1 - 1.5 sin^2 alpha) and
//     against the reference model (rockbench::reference, dopri5 at rtol 1e-12);
//  2. the thesis's stack (scenes/thesis_free_rocking.toml) for 3 s against the reference;
// at time steps 1e-3, 1e-4, 1e-5 s, with the Monitor watching each run as the engine would.
//
// Usage: ode_probe [key=value ...]
//   dts=1e-3,1e-4,1e-5  single=1  stack=1  events=4
//   and any OdeSettings field (shown with its default; "inf" for infinity):
//   stepper=world_step|quick_step quick_step_iterations=100 quick_step_w=1.3 erp=0.2
//   cfm=1e-10 contact_erp=0.2 contact_cfm=1e-10 contact_max_correcting_vel_mps=1e-4
//   contact_surface_layer_m=0 friction=inf friction_pyramid=0 restitution=0 max_contacts=8
//   finite_rotation=1 ground_depth_m=1
//
// Build by hand, e.g. from engines/ode (one line):
//   g++ -std=c++20 -O2 -I/work/main -I/work/main/src -DTOML_HEADER_ONLY=0 -DTOML_SHARED_LIB=1
//     $(pkg-config --cflags ode) ode_probe.cc ode_world.cc ../common/*.cc ../../reference/*.cc
//     ../../src/scene/*.cc -ltomlplusplus $(pkg-config --libs ode)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engines/common/engine_input.h"
#include "engines/common/monitor.h"
#include "engines/ode/ode_world.h"
#include "reference/simulate.h"
#include "scene/ground_motion.h"
#include "scene/scene.h"

namespace {

using rockbench::DriveKind;
using rockbench::EngineInput;
using rockbench::Event;
using rockbench::GroundMotion;
using rockbench::Monitor;
using rockbench::Scene;
using rockbench::ode::OdeSettings;
using rockbench::ode::OdeWorld;

double ParseDouble(const std::string& v) {
  if (v == "inf" || v == "infinity") return std::numeric_limits<double>::infinity();
  return std::stod(v);
}

// Exact free rocking of one block (thesis sign: theta > 0 about the right corner).
struct Exact {
  double p2 = 0.0, alpha = 0.0, e = 0.0;
  struct Impact {
    double t_s, omega_before, omega_after;
  };
  std::vector<double> t, th, om;  // on a fine grid with the impacts inserted
  std::vector<Impact> impacts;

  Exact(double b, double h, double g, double theta0, double t_end) {
    const double r = std::hypot(b, h);
    alpha = std::atan(b / h);
    p2 = 3.0 * g / (4.0 * r);  // m g R / I_O with I_O = 4/3 m R^2
    e = 1.0 - 1.5 * std::pow(std::sin(alpha), 2);
    const double hs = 1e-6;
    double tc = 0.0, x = theta0, v = 0.0;
    int side = theta0 > 0 ? 1 : -1;
    t.push_back(tc);
    th.push_back(x);
    om.push_back(v);
    auto f = [&](double xx) { return -p2 * std::sin(side * alpha - xx); };
    auto rk4 = [&](double& xx, double& vv, double dt) {
      const double k1x = vv, k1v = f(xx);
      const double k2x = vv + 0.5 * dt * k1v, k2v = f(xx + 0.5 * dt * k1x);
      const double k3x = vv + 0.5 * dt * k2v, k3v = f(xx + 0.5 * dt * k2x);
      const double k4x = vv + dt * k3v, k4v = f(xx + dt * k3x);
      xx += dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
      vv += dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    };
    while (tc < t_end) {
      double x1 = x, v1 = v;
      rk4(x1, v1, hs);
      if (x1 * side < 0.0) {
        // Crossing zero inside the step: bisect on the step length.
        double lo = 0.0, hi = hs;
        for (int k = 0; k < 80; ++k) {
          const double mid = 0.5 * (lo + hi);
          double xm = x, vm = v;
          rk4(xm, vm, mid);
          ((xm * side > 0.0) ? lo : hi) = mid;
        }
        double xm = x, vm = v;
        rk4(xm, vm, hi);
        tc += hi;
        impacts.push_back({tc, vm, e * vm});
        x = 0.0;
        v = e * vm;
        side = -side;
      } else {
        x = x1;
        v = v1;
        tc += hs;
      }
      t.push_back(tc);
      th.push_back(x);
      om.push_back(v);
    }
  }
  // Linear interpolation on the 1e-6 s grid: error ~ omega' dt^2 / 8 ~ 1e-12 rad.
  double ThetaAt(double tq) const {
    size_t i = static_cast<size_t>(std::lower_bound(t.begin(), t.end(), tq) - t.begin());
    if (i == 0) return th[0];
    if (i >= t.size()) return th.back();
    const double s = (tq - t[i - 1]) / (t[i] - t[i - 1]);
    return th[i - 1] + s * (th[i] - th[i - 1]);
  }
};

struct RunResult {
  double max_err1 = 0.0, max_err2 = 0.0, max_err1_exact = 0.0;
  double t_err1 = 0.0, t_err2 = 0.0;
  double wall_s = 0.0, cpu_s = 0.0, sim_s = 0.0;
  nlohmann::json summary;
  std::vector<Event> events;
  int max_contacts_ground = 0, max_contacts_interface = 0;
};

RunResult RunEngine(const Scene& scene, double dt, const OdeSettings& settings,
                    const rockbench::reference::Result& ref, const Exact* exact) {
  GroundMotion motion;
  EngineInput in = rockbench::MakeEngineInput(scene, motion, "ode", dt, DriveKind::kInertial, 0.0);
  RunResult out;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  OdeWorld world(in, settings);
  Monitor monitor(in);
  monitor.Start(world.Read(0));
  double wall_cmp = 0.0, cpu_cmp = 0.0;
  for (std::int64_t n = 0; n < in.steps; ++n) {
    world.ApplyDrive(n);
    world.Step();
    out.max_contacts_ground = std::max(out.max_contacts_ground, world.last_contacts_ground());
    out.max_contacts_interface =
        std::max(out.max_contacts_interface, world.last_contacts_interface());
    const rockbench::StepReadout r = world.Read(n + 1);
    const bool go = monitor.Step(n + 1, r);
    // Comparison (timed apart: not the engine's cost).
    const auto c0 = std::chrono::steady_clock::now();
    const std::clock_t k0 = std::clock();
    const double th1 = -std::atan2(r.block1.sin_phi, r.block1.cos_phi);
    const rockbench::Sample s = ref.trajectory.At(r.t_s);
    const double e1 = std::abs(th1 - s.theta1_rad);
    if (e1 > out.max_err1) {
      out.max_err1 = e1;
      out.t_err1 = r.t_s;
    }
    if (exact)
      out.max_err1_exact = std::max(out.max_err1_exact, std::abs(th1 - exact->ThetaAt(r.t_s)));
    if (in.two_blocks()) {
      const double th2 = -std::atan2(r.block2.sin_phi, r.block2.cos_phi);
      const double e2 = std::abs(th2 - s.theta2_rad);
      if (e2 > out.max_err2) {
        out.max_err2 = e2;
        out.t_err2 = r.t_s;
      }
    }
    wall_cmp += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
    cpu_cmp += static_cast<double>(std::clock() - k0) / CLOCKS_PER_SEC;
    if (!go) break;
  }
  monitor.Finish();
  out.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - wall_cmp;
  out.cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC - cpu_cmp;
  out.sim_s = monitor.last().t_s;
  out.summary = monitor.Summary();
  out.summary["settings"] = world.Settings();
  out.events = monitor.history().events;
  return out;
}

void PrintViolations(const RunResult& r, bool two) {
  const auto& v = r.summary["violations"];
  std::printf("    status %s; penetration ground %.3g m",
              r.summary["status"].get<std::string>().c_str(),
              v["penetration_ground_max_m"].get<double>());
  if (two) std::printf(", interface %.3g m", v["penetration_interface_max_m"].get<double>());
  std::printf("; slip ground %.3g m", v["slip_ground_m"].get<double>());
  if (two) std::printf(", interface %.3g m", v["slip_interface_m"].get<double>());
  std::printf("; uplift episodes %d", v["uplift_ground_episodes"].get<int>());
  if (two) std::printf("/%d", v["uplift_interface_episodes"].get<int>());
  std::printf(" (max %.3g m)", v["uplift_ground_max_m"].get<double>());
  std::printf("; energy gain %.3g of tipping; out of plane %.3g m %.3g rad; contacts <= %d/%d\n",
              v["energy_gain_rel"].get<double>(), v["out_of_plane_m"].get<double>(),
              v["out_of_plane_rad"].get<double>(), r.max_contacts_ground, r.max_contacts_interface);
}

}  // namespace

int main(int argc, char** argv) {
  OdeSettings settings;
  std::vector<double> dts = {1e-3, 1e-4, 1e-5};
  bool single = true, stack = true;
  int n_events = 4;
  try {
    for (int a = 1; a < argc; ++a) {
      const std::string arg = argv[a];
      const size_t eq = arg.find('=');
      if (eq == std::string::npos) throw std::invalid_argument("expected key=value: " + arg);
      const std::string k = arg.substr(0, eq), v = arg.substr(eq + 1);
      if (k == "dts") {
        dts.clear();
        std::stringstream ss(v);
        std::string item;
        while (std::getline(ss, item, ',')) dts.push_back(std::stod(item));
      } else if (k == "single") {
        single = v != "0";
      } else if (k == "stack") {
        stack = v != "0";
      } else if (k == "events") {
        n_events = std::stoi(v);
      } else if (k == "stepper") {
        auto st = rockbench::ode::ParseOdeStepper(v);
        if (!st) throw std::invalid_argument("stepper: world_step or quick_step");
        settings.stepper = *st;
      } else if (k == "quick_step_iterations") {
        settings.quick_step_iterations = std::stoi(v);
      } else if (k == "quick_step_w") {
        settings.quick_step_w = ParseDouble(v);
      } else if (k == "erp") {
        settings.erp = ParseDouble(v);
      } else if (k == "cfm") {
        settings.cfm = ParseDouble(v);
      } else if (k == "contact_erp") {
        settings.contact_erp = ParseDouble(v);
      } else if (k == "contact_cfm") {
        settings.contact_cfm = ParseDouble(v);
      } else if (k == "contact_max_correcting_vel_mps") {
        settings.contact_max_correcting_vel_mps = ParseDouble(v);
      } else if (k == "contact_surface_layer_m") {
        settings.contact_surface_layer_m = ParseDouble(v);
      } else if (k == "friction") {
        settings.friction = ParseDouble(v);
      } else if (k == "friction_pyramid") {
        settings.friction_pyramid = v != "0";
      } else if (k == "restitution") {
        settings.restitution = ParseDouble(v);
      } else if (k == "max_contacts") {
        settings.max_contacts = std::stoi(v);
      } else if (k == "finite_rotation") {
        settings.finite_rotation = v != "0";
      } else if (k == "ground_depth_m") {
        settings.ground_depth_m = ParseDouble(v);
      } else {
        throw std::invalid_argument("unknown key " + k);
      }
    }

    if (single) {
      Scene sc;
      sc.block1.width_m = 0.4;
      sc.block1.height_m = 1.2;
      sc.block1.depth_m = 1.0;
      sc.block1.mass_kg = 100.0;
      const double alpha = std::atan(0.4 / 1.2);
      sc.initial.theta1_rad = 0.5 * alpha;
      sc.run.duration_s = 2.5;
      sc.run.output_interval_s = 1e-3;
      sc.run.gravity_mps2 = 9.81;
      rockbench::ValidateScene(sc);
      GroundMotion none;
      const auto ref = rockbench::reference::Simulate(sc, none);
      const Exact exact(0.2, 0.6, 9.81, sc.initial.theta1_rad, 2.5);
      double ref_vs_exact = 0.0;
      for (double t = 0.0; t <= 2.5; t += 1e-4) {
        ref_vs_exact =
            std::max(ref_vs_exact, std::abs(ref.trajectory.At(t).theta1_rad - exact.ThetaAt(t)));
      }
      std::printf("Housner block 0.4 x 1.2 m, theta0 = alpha/2 = %.6f rad, e = %.6f\n",
                  sc.initial.theta1_rad, exact.e);
      std::printf("  exact (RK4 1e-6 s + bisection) vs reference model: max |dtheta| %.3g rad\n",
                  ref_vs_exact);
      std::printf("  exact impacts:");
      for (size_t k = 0; k < exact.impacts.size() && k < static_cast<size_t>(n_events); ++k) {
        std::printf("  t=%.6f ratio=%.6f", exact.impacts[k].t_s,
                    exact.impacts[k].omega_after / exact.impacts[k].omega_before);
      }
      std::printf("  (%zu impacts in 2.5 s)\n", exact.impacts.size());
      for (double dt : dts) {
        const RunResult r = RunEngine(sc, dt, settings, ref, &exact);
        std::printf(
            "  dt %.0e: max |theta1 err| %.3e rad at t=%.4f (vs exact %.3e); wall %.3f s "
            "(CPU %.3f s) per simulated s\n",
            dt, r.max_err1, r.t_err1, r.max_err1_exact, r.wall_s / r.sim_s, r.cpu_s / r.sim_s);
        std::printf("    impacts:");
        int k = 0;
        for (const Event& ev : r.events) {
          if (ev.kind != "ground_impact") continue;
          if (k < n_events && static_cast<size_t>(k) < exact.impacts.size()) {
            std::printf("  t=%.6f (%+.1e) ratio=%.6f", ev.t_s, ev.t_s - exact.impacts[k].t_s,
                        ev.omega1_before != 0.0 ? ev.omega1_after / ev.omega1_before : 0.0);
          }
          ++k;
        }
        std::printf("  (%d impacts)\n", r.summary["impacts"]["ground"].get<int>());
        PrintViolations(r, false);
      }
    }

    if (stack) {
      Scene sc = rockbench::LoadScene("/work/main/scenes/thesis_free_rocking.toml",
                                      {"run.duration=3", "run.output_interval=0.001"});
      GroundMotion none;
      const auto ref = rockbench::reference::Simulate(sc, none);
      std::printf(
          "Thesis stack (free rocking, 3 s): reference impacts ground %d interface %d, "
          "friction required ground %.3g interface %.3g\n",
          ref.summary.impacts_ground, ref.summary.impacts_interface,
          ref.summary.friction_required_ground, ref.summary.friction_required_interface);
      std::printf("  reference events:");
      int k = 0;
      for (const Event& ev : ref.history.events) {
        if (ev.kind.find("impact") == std::string::npos) continue;
        if (k++ < n_events) std::printf("  %s t=%.6f", ev.kind.c_str(), ev.t_s);
      }
      std::printf("\n");
      for (double dt : dts) {
        const RunResult r = RunEngine(sc, dt, settings, ref, nullptr);
        std::printf(
            "  dt %.0e: max |theta1 err| %.3e rad at t=%.4f, max |theta2 err| %.3e rad "
            "at t=%.4f; wall %.3f s (CPU %.3f s) per simulated s\n",
            dt, r.max_err1, r.t_err1, r.max_err2, r.t_err2, r.wall_s / r.sim_s, r.cpu_s / r.sim_s);
        std::printf("    events:");
        int j = 0;
        for (const Event& ev : r.events) {
          if (ev.kind.find("impact") == std::string::npos) continue;
          if (j++ < n_events) std::printf("  %s t=%.6f", ev.kind.c_str(), ev.t_s);
        }
        std::printf("  (impacts ground %d interface %d)\n",
                    r.summary["impacts"]["ground"].get<int>(),
                    r.summary["impacts"]["interface"].get<int>());
        PrintViolations(r, true);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ode_probe: %s\n", e.what());
    return 1;
  }
  return 0;
}
