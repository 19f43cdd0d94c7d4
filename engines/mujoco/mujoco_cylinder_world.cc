#include "engines/mujoco/mujoco_cylinder_world.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engines/mujoco/mujoco_mjcf.h"

namespace rockbench::mujoco {
namespace {

// The cylinder's geom, body and joint name.
constexpr const char* kCylinder = "cylinder";

// The solref and solimp attributes of a contact.
std::string ContactAttributes(const ContactParams& c) {
  return "solref=\"" + Num(c.solref[0]) + " " + Num(c.solref[1]) + "\" solimp=\"" +
         Num(c.solimp[0]) + " " + Num(c.solimp[1]) + " " + Num(c.solimp[2]) + " " +
         Num(c.solimp[3]) + " " + Num(c.solimp[4]) + "\"";
}

std::string ModelMjcf(const EngineInput& in, const MujocoSettings& s) {
  const ContactParams c = ContactParamsOf(s, in.time_step_s);
  const CylinderBodyDef b = CylinderBodyOf(in);
  std::string x;
  x += "<mujoco model=\"rockbench_cylinder\">\n";
  x += "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  // At most 4 contacts with the plane (mjc_PlaneCylinder); 3 rows each (elliptic cone, condim
  // 3) or 4 (pyramidal).
  x += "  <size njmax=\"64\" nconmax=\"16\"/>\n";
  x += "  <option timestep=\"" + Num(in.time_step_s) + "\" gravity=\"0 0 " +
       Num(-in.run.gravity_mps2) + "\" integrator=\"" + MjcfIntegrator(s.integrator) +
       "\" solver=\"" + MjcfSolver(s.solver) + "\" iterations=\"" + std::to_string(s.iterations) +
       "\" tolerance=\"" + Num(s.tolerance) + "\" cone=\"" + std::string(ConeName(s.cone)) +
       "\" impratio=\"" + Num(s.impratio) + "\" noslip_iterations=\"" +
       std::to_string(s.noslip_iterations) + "\" noslip_tolerance=\"" + Num(s.noslip_tolerance) +
       "\"/>\n";
  x += "  <default>\n";
  x += "    <geom condim=\"3\" friction=\"" + Num(s.friction) +
       " 0.005 0.0001\" margin=\"0\" gap=\"0\" " + ContactAttributes(c) + "/>\n";
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
    x += std::string("    <exclude body1=\"world\" body2=\"") + kCylinder + "\"/>\n";
    x += std::string("    <pair geom1=\"ground\" geom2=\"") + kCylinder + "\" condim=\"" +
         (b.friction > 0.0 ? "3" : "1") + "\" friction=\"" + Num(b.friction) + " " +
         Num(b.friction) + " 0.005 0.0001 0.0001\" " + ContactAttributes(c) +
         " margin=\"0\" gap=\"0\"/>\n";
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
  m_ = CompileMjcf(xml_);
  d_ = mj_makeData(m_);
  if (!d_) {
    mj_deleteModel(m_);
    throw std::runtime_error("mujoco: mj_makeData failed");
  }
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

MujocoCylinderWorld::~MujocoCylinderWorld() {
  if (d_) mj_deleteData(d_);
  if (m_) mj_deleteModel(m_);
}

void MujocoCylinderWorld::ApplyDrive(std::int64_t n) {
  const Vec3d a = CylinderDriveAccel(in_, n);
  // The exact equivalent of a translating base: effective gravity in the base frame.
  m_->opt.gravity[0] = -a[0];
  m_->opt.gravity[1] = -a[1];
  m_->opt.gravity[2] = -(in_.run.gravity_mps2 + a[2]);
}

void MujocoCylinderWorld::Step() {
  if (blown_up_) return;
  const double t_before = d_->time;
  mj_step(m_, d_);
  // mj_step detects the contacts at the state before the step.
  max_contacts_ = std::max(max_contacts_, d_->ncon);
  ++steps_with_contacts_[std::min(d_->ncon, 4)];
  max_iterations_ = std::max(max_iterations_, d_->solver_iter);
  // MuJoCo resets the simulation (time back to 0) when it meets a bad number: the end of the
  // run.
  if (d_->warning[mjWARN_BADQPOS].number > 0 || d_->warning[mjWARN_BADQVEL].number > 0 ||
      d_->warning[mjWARN_BADQACC].number > 0 || !(d_->time > t_before)) {
    blown_up_ = true;
  }
}

CylinderPose MujocoCylinderWorld::ReadPose() const {
  CylinderPose p;
  if (blown_up_) {
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
  const ContactParams c = ContactParamsOf(s_, in_.time_step_s);
  const CylinderBodyDef b = CylinderBodyOf(in_);
  nlohmann::json j;
  j["mujoco_version"] = mj_versionString();
  j["drive"] = "inertial";
  j["time_step_s"] = in_.time_step_s;
  j["output_interval_s"] = in_.run.output_interval_s;
  j["contact"] = std::string(ContactModelName(s_.contact));
  j["solref"] = {c.solref[0], c.solref[1]};
  j["solimp"] = {c.solimp[0], c.solimp[1], c.solimp[2], c.solimp[3], c.solimp[4]};
  if (s_.contact == ContactModel::kStiff) {
    j["stiff_timeconst_steps"] = s_.stiff_timeconst_steps;
    j["stiff_dampratio"] = s_.stiff_dampratio;
  }
  j["solver"] = std::string(SolverName(s_.solver));
  j["iterations"] = s_.iterations;
  j["tolerance"] = s_.tolerance;
  j["integrator"] = std::string(IntegratorName(s_.integrator));
  j["cone"] = std::string(ConeName(s_.cone));
  j["impratio"] = s_.impratio;
  j["friction"] = s_.friction;
  // The coefficient the compiled model has: the explicit pair's (0 for a frictionless one), else
  // the larger of the two geoms'.
  const int ground = mj_name2id(m_, mjOBJ_GEOM, "ground");
  const int body = mj_name2id(m_, mjOBJ_GEOM, kCylinder);
  double mu = std::max(m_->geom_friction[3 * ground], m_->geom_friction[3 * body]);
  if (m_->npair > 0) mu = m_->pair_dim[0] == 1 ? 0.0 : m_->pair_friction[0];
  j["friction_combined"] = mu;
  j["noslip_iterations"] = s_.noslip_iterations;
  j["noslip_tolerance"] = s_.noslip_tolerance;
  j["condim"] = m_->npair > 0 ? m_->pair_dim[0] : m_->geom_condim[body];
  j["margin_m"] = 0.0;
  j["ground"] = "plane z = 0";
  j["body"] = "free joint, MuJoCo cylinder geom (plane contact: exact lowest rim point)";
  j["radius_m"] = b.radius_m;
  j["half_height_m"] = b.half_height_m;
  j["mass_kg"] = m_->body_mass[1];
  j["inertia_kgm2"] = {m_->body_inertia[3], m_->body_inertia[4], m_->body_inertia[5]};
  j["refsafe"] = (m_->opt.disableflags & mjDSBL_REFSAFE) == 0;
  j["warmstart"] = (m_->opt.disableflags & mjDSBL_WARMSTART) == 0;
  return j;
}

nlohmann::json MujocoCylinderWorld::Diagnostics() const {
  nlohmann::json j;
  j["contact_buffer_full"] = d_->warning[mjWARN_CONTACTFULL].number;
  j["constraint_buffer_full"] = d_->warning[mjWARN_CNSTRFULL].number;
  j["bad_qpos"] = d_->warning[mjWARN_BADQPOS].number;
  j["bad_qvel"] = d_->warning[mjWARN_BADQVEL].number;
  j["bad_qacc"] = d_->warning[mjWARN_BADQACC].number;
  j["max_contacts"] = max_contacts_;
  j["steps_with_contacts"] = {{"0", steps_with_contacts_[0]},
                              {"1", steps_with_contacts_[1]},
                              {"2", steps_with_contacts_[2]},
                              {"3", steps_with_contacts_[3]},
                              {"4", steps_with_contacts_[4]}};
  j["max_solver_iterations"] = max_iterations_;
  j["blown_up"] = blown_up_;
  return j;
}

}  // namespace rockbench::mujoco
