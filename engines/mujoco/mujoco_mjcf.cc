#include "engines/mujoco/mujoco_mjcf.h"

#include <mujoco/mujoco.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace rockbench::mujoco {
namespace {

// mj_loadXML parses into a global (the model mj_saveLastXML writes) and compiles with MuJoCo's
// error handlers; serialise it.
std::mutex& CompileMutex() {
  static std::mutex mutex;
  return mutex;
}

void QuietWarning(const char*) {}

}  // namespace

std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

const char* MjcfIntegrator(Integrator i) {
  switch (i) {
    case Integrator::kEuler:
      return "Euler";
    case Integrator::kRK4:
      return "RK4";
    case Integrator::kImplicit:
      return "implicit";
  }
  return "Euler";
}

const char* MjcfSolver(Solver s) {
  switch (s) {
    case Solver::kNewton:
      return "Newton";
    case Solver::kCG:
      return "CG";
    case Solver::kPGS:
      return "PGS";
  }
  return "Newton";
}

ContactParams ContactParamsOf(const MujocoSettings& s, double dt_s) {
  if (s.contact == ContactModel::kMujocoDefault) {
    return {{0.02, 1.0}, {0.9, 0.95, 0.001, 0.5, 2.0}};
  }
  ContactParams p{{s.stiff_timeconst_steps * dt_s, s.stiff_dampratio}, {}};
  for (int i = 0; i < 5; ++i) p.solimp[i] = s.stiff_solimp[i];
  return p;
}

void Check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("mujoco: " + what);
}

void CheckSolimp(const MujocoSettings& s) {
  const auto& si = s.stiff_solimp;
  // MuJoCo would clamp impedances outside [mjMINIMP, mjMAXIMP] silently.
  Check(si[0] >= mjMINIMP && si[0] <= mjMAXIMP && si[1] >= mjMINIMP && si[1] <= mjMAXIMP,
        "stiff_solimp: dmin and dmax must lie in [0.0001, 0.9999] (MuJoCo's mjMINIMP, "
        "mjMAXIMP)");
  Check(si[2] >= 0.0 && si[3] > 0.0 && si[3] < 1.0 && si[4] >= 1.0,
        "stiff_solimp: expected width >= 0, midpoint in (0, 1), power >= 1");
}

void InstallQuietWarningHandler() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (mju_user_warning == nullptr) mju_user_warning = QuietWarning;
  });
}

mjModel* CompileMjcf(const std::string& xml) {
  static constexpr const char* kFile = "rockbench_mujoco.xml";
  auto vfs = std::make_unique<mjVFS>();  // 2 MB of file names: not on the stack
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), kFile, static_cast<int>(xml.size())) != 0) {
    throw std::runtime_error("mujoco: cannot make the model's virtual file");
  }
  const int i = mj_findFileVFS(vfs.get(), kFile);
  std::memcpy(vfs->filedata[i], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = nullptr;
  {
    std::lock_guard<std::mutex> lock(CompileMutex());
    m = mj_loadXML(kFile, vfs.get(), error, sizeof error);
  }
  mj_deleteVFS(vfs.get());
  if (!m) throw std::runtime_error(std::string("mujoco: model does not compile: ") + error);
  return m;
}

}  // namespace rockbench::mujoco
