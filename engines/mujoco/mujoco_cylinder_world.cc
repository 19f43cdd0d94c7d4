#include "engines/mujoco/mujoco_cylinder_world.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engines/mujoco/mujoco_mjcf.h"
#include "engines/mujoco/mujoco_world_parts.h"

namespace rockbench::mujoco {
namespace {

// The cylinder's geom, body and joint name.
constexpr const char* kCylinder = "cylinder";

std::string ModelMjcf(const EngineInput& in, const MujocoSettings& s) {
  const ContactParams c = ContactParamsOf(s, in.time_step_s);
  const CylinderBodyDef b = CylinderBodyOf(in);
  std::string x;
  x += "<mujoco model=\"rockbench_cylinder\">\n";
  x += "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  // At most 4 contacts with the plane (mjc_PlaneCylinder); 3 rows each (elliptic cone, condim
  // 3) or 4 (pyramidal).
  x += "  <size njmax=\"64\" nconmax=\"16\"/>\n";
  x += OptionMjcf(in, s, "0 0 " + Num(-in.run.gravity_mps2));
  x += "  <default>\n";
  x += GeomDefaultMjcf(s, c);
  x += "  </default>\n";
  x += "  <worldbody>\n";
  // The ground: the half-space z <= 0.
  x += "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\"/>\n";
  // The cylinder: body frame at the mass centre, body z its axis; mass and central inertia
  // CylinderBodyOf's.
  x += std::string("    <body name=\"") + kCylinder + "\" pos=\"0 0 0\">\n";
  x += std::string("      <freejoint name=\"") + kCylinder + "\"/>\n";
  x += "      <inertial pos=\"0 0 0\" mass=\"" + Num(b.mass_kg) + "\" diaginertia=\"" +
       Num(b.inertia_transverse_kgm2) + " " + Num(b.inertia_transverse_kgm2) + " " +
       Num(b.inertia_axial_kgm2) + "\"/>\n";
  x += std::string("      <geom name=\"") + kCylinder + "\" type=\"cylinder\" size=\"" +
       Num(b.radius_m) + " " + Num(b.half_height_m) + "\"/>\n";
  x += "    </body>\n";
  x += "  </worldbody>\n";
  // Friction from the scene: an explicit pair with exactly that coefficient (MuJoCo would take
  // the larger of the two geoms'), frictionless (condim 1) at 0; the dynamic pair excluded.
  if (std::isfinite(b.friction)) {
    x += "  <contact>\n";
    x += SceneFrictionPairMjcf("world", kCylinder, "ground", kCylinder, b.friction, c);
    x += "  </contact>\n";
  }
  x += "</mujoco>\n";
  return x;
}

Vec3d NaN3() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return {nan, nan, nan};
}

}  // namespace

MujocoCylinderWorld::MujocoCylinderWorld(const EngineInput& input, const MujocoSettings& settings)
    : in_(input), s_(settings) {
  Check(in_.drive_kind == DriveKind::kInertial,
        "the cylinder takes the inertial drive only (a mocap ground has no velocity in the "
        "contact equations)");
  CheckSolimp(s_);
  const CylinderBodyDef b = CylinderBodyOf(in_);
  Check(b.radius_m > 0.0 && b.half_height_m > 0.0 && b.mass_kg > 0.0,
        "the cylinder needs a positive diameter, height and mass");
  InstallQuietWarningHandler();
  xml_ = ModelMjcf(in_, s_);
  sim_ = std::make_unique<MujocoSim>(xml_);
  m_ = sim_->m();
  d_ = sim_->d();
  const int j = mj_name2id(m_, mjOBJ_JOINT, kCylinder);
  if (j != 0 || m_->jnt_type[0] != mjJNT_FREE || m_->nq != 7 || m_->nv != 6) {
    throw std::runtime_error("mujoco: unexpected joint layout of the cylinder");
  }
  // The free joint: qpos = (centre, quaternion w x y z), qvel = (centre velocity in the world,
  // angular velocity in the body frame).
  const CylinderPose p = CylinderStartPose(in_);
  mjtNum quat[4];
  mju_mat2Quat(quat, p.rotation.data());
  for (int i = 0; i < 3; ++i) d_->qpos[i] = p.centre_m[i];
  for (int i = 0; i < 4; ++i) d_->qpos[3 + i] = quat[i];
  for (int i = 0; i < 3; ++i) d_->qvel[i] = p.velocity_mps[i];
  mju_mulMatTVec(d_->qvel + 3, p.rotation.data(), p.omega_radps.data(), 3, 3);
  mj_forward(m_, d_);
}

MujocoCylinderWorld::~MujocoCylinderWorld() = default;

void MujocoCylinderWorld::ApplyDrive(std::int64_t n) {
  const Vec3d a = CylinderDriveAccel(in_, n);
  // The exact equivalent of a translating base: effective gravity in the base frame.
  m_->opt.gravity[0] = -a[0];
  m_->opt.gravity[1] = -a[1];
  m_->opt.gravity[2] = -(in_.run.gravity_mps2 + a[2]);
}

void MujocoCylinderWorld::Step() {
  // mj_step detects the contacts at the state before the step.
  if (sim_->Step()) ++steps_with_contacts_[std::min(d_->ncon, 4)];
}

CylinderPose MujocoCylinderWorld::ReadPose() const {
  CylinderPose p;
  if (sim_->blown_up()) {
    p.centre_m = p.velocity_mps = p.omega_radps = NaN3();
    p.rotation.fill(std::numeric_limits<double>::quiet_NaN());
    return p;
  }
  // qpos and qvel hold the state after the step (xpos and xmat still hold the one before).
  mjtNum quat[4] = {d_->qpos[3], d_->qpos[4], d_->qpos[5], d_->qpos[6]};
  mju_normalize4(quat);
  mju_quat2Mat(p.rotation.data(), quat);
  for (int i = 0; i < 3; ++i) {
    p.centre_m[i] = d_->qpos[i];
    p.velocity_mps[i] = d_->qvel[i];
  }
  mju_mulMatVec(p.omega_radps.data(), p.rotation.data(), d_->qvel + 3, 3, 3);
  return p;
}

nlohmann::json MujocoCylinderWorld::Settings() const {
  const CylinderBodyDef b = CylinderBodyOf(in_);
  nlohmann::json j = CommonSettings(in_, s_, m_);
  // The coefficient the compiled model has: the explicit pair's (0 for a frictionless one), else
  // the larger of the two geoms'.
  const int ground = mj_name2id(m_, mjOBJ_GEOM, "ground");
  const int body = mj_name2id(m_, mjOBJ_GEOM, kCylinder);
  double mu = std::max(m_->geom_friction[3 * ground], m_->geom_friction[3 * body]);
  if (m_->npair > 0) mu = m_->pair_dim[0] == 1 ? 0.0 : m_->pair_friction[0];
  j["friction_combined"] = mu;
  j["condim"] = m_->npair > 0 ? m_->pair_dim[0] : m_->geom_condim[body];
  j["ground"] = "plane z = 0";
  j["body"] = "free joint, MuJoCo cylinder geom (plane contact: exact lowest rim point)";
  j["radius_m"] = b.radius_m;
  j["half_height_m"] = b.half_height_m;
  j["mass_kg"] = m_->body_mass[1];
  j["inertia_kgm2"] = {m_->body_inertia[3], m_->body_inertia[4], m_->body_inertia[5]};
  return j;
}

nlohmann::json MujocoCylinderWorld::Diagnostics() const {
  nlohmann::json j = sim_->Diagnostics();
  j["steps_with_contacts"] = {{"0", steps_with_contacts_[0]},
                              {"1", steps_with_contacts_[1]},
                              {"2", steps_with_contacts_[2]},
                              {"3", steps_with_contacts_[3]},
                              {"4", steps_with_contacts_[4]}};
  return j;
}

}  // namespace rockbench::mujoco
