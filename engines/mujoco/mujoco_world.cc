#include "engines/mujoco/mujoco_world.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "engines/mujoco/mujoco_mjcf.h"
#include "engines/mujoco/mujoco_world_parts.h"
#include "scene/stack_pose.h"

// Kinematic drive. A moving ground in MuJoCo would be a mocap body (or a body welded to one).
// Mocap bodies have no degrees of freedom: mj_comVel gives them zero velocity, and the contact
// Jacobian of a contact with a mocap geom has no columns for it, so the contact's relative
// velocity (hence its damping term and the impact) is that of the blocks alone: moving the
// mocap body teleports the ground by u_{n+1} - u_n every step and the contact sees it only as a
// penetration to be pushed out by the contact spring. That is not the ground at u(t_n) moving
// with (u_{n+1} - u_n) / dt that Bullet's kinematic drive is, so the [mujoco] table's drive
// offers only "inertial" (mujoco_settings.cc).
// (Checked on 2.2.2: a 100 kg box resting with friction 10 on a mocap ground moved at 1 m/s for
// 0.5 s stays where it is, velocity 0, while the ground slides 0.5 m under it.)

namespace rockbench::mujoco {
namespace {

// The settings' ranges are the [mujoco] schema's (mujoco_settings.cc, which also refuses the
// kinematic drive), checked when the table was resolved; the step is the input's, checked by
// MakeEngineInput. What is left: the stiff contact's solimp, a constant no key sets, and the
// blocks.
void CheckModel(const EngineInput& in, const MujocoSettings& s) {
  CheckSolimp(s);
  auto block_ok = [](const BlockDef& b) {
    return b.width_m > 0.0 && b.height_m > 0.0 && b.depth_m > 0.0 && b.mass_kg > 0.0;
  };
  Check(!in.blocks.empty() && std::all_of(in.blocks.begin(), in.blocks.end(), block_ok),
        "blocks need a positive width, height, depth and mass");
}

// One block: a body at the world origin with slide x, slide y and hinge z joints (qpos = the
// mass centre's x, y and the CCW angle), a box geom and its exact inertia.
std::string BlockMjcf(const std::string& name, const BlockDef& b) {
  const double m = b.mass_kg, w = b.width_m, h = b.height_m, d = b.depth_m;
  const double ixx = m * (h * h + d * d) / 12.0, iyy = m * (w * w + d * d) / 12.0;
  const double izz = m * (w * w + h * h) / 12.0;
  const std::string n = name;
  std::string s;
  s += "    <body name=\"" + n + "\" pos=\"0 0 0\">\n";
  s += "      <joint name=\"" + n + "_x\" type=\"slide\" axis=\"1 0 0\"/>\n";
  s += "      <joint name=\"" + n + "_y\" type=\"slide\" axis=\"0 1 0\"/>\n";
  s += "      <joint name=\"" + n + "_phi\" type=\"hinge\" axis=\"0 0 1\" pos=\"0 0 0\"/>\n";
  s += "      <inertial pos=\"0 0 0\" mass=\"" + Num(m) + "\" diaginertia=\"" + Num(ixx) + " " +
       Num(iyy) + " " + Num(izz) + "\"/>\n";
  s += "      <geom name=\"" + n + "\" type=\"box\" size=\"" + Num(0.5 * w) + " " + Num(0.5 * h) +
       " " + Num(0.5 * d) + "\"/>\n";
  s += "    </body>\n";
  return s;
}

// Friction from the scene: each interface whose block has a finite friction is an explicit
// contact pair with exactly that coefficient (MuJoCo would combine two geoms' values by their
// maximum), its other parameters those the geoms' defaults give the dynamic pair (condim 3, the
// contact's solref and solimp, margin and gap 0); a coefficient of 0 is a frictionless pair
// (condim 1: MuJoCo's friction is at least mjMINMU). The dynamic pair of the same two bodies is
// excluded. Empty when every block's friction is infinite.
std::string SceneFrictionPairs(const EngineInput& in, const ContactParams& c) {
  std::string x;
  for (int k = 0; k < in.block_count(); ++k) {
    const double mu = in.blocks[k].friction;
    if (!std::isfinite(mu)) continue;
    const std::string upper = std::string("block") + std::to_string(k + 1);
    const std::string lower =
        k == 0 ? std::string("ground") : std::string("block") + std::to_string(k);
    const std::string lower_body = k == 0 ? std::string("world") : lower;
    x += SceneFrictionPairMjcf(lower_body, upper, lower, upper, mu, c);
  }
  return x;
}

std::string ModelMjcf(const EngineInput& in, const MujocoSettings& s) {
  const ContactParams c = ContactParamsOf(s, in.time_step_s);
  std::string x;
  x += "<mujoco model=\"rockbench\">\n";
  x += "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  // Contacts: at most 4 per block on the plane and 8 between the boxes; 4 rows each (pyramidal
  // cone, condim 3) or 3 (elliptic). 100 contacts up to 10 blocks, 10 per block beyond.
  const int blocks = in.block_count();
  const int nconmax = std::max(100, 10 * blocks);
  x += std::string("  <size njmax=\"") + std::to_string(4 * nconmax) + "\" nconmax=\"" +
       std::to_string(nconmax) + "\"/>\n";
  x += OptionMjcf(in, s, "0 " + Num(-in.run.gravity_mps2) + " 0");
  x += "  <default>\n";
  x += "    <joint limited=\"false\" damping=\"0\" armature=\"0\" stiffness=\"0\" "
       "frictionloss=\"0\"/>\n";
  x += GeomDefaultMjcf(s, c);
  x += "  </default>\n";
  x += "  <worldbody>\n";
  // The ground: a plane (half-space) whose normal is +y through the origin.
  x += "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" zaxis=\"0 1 0\"/>\n";
  // Every block is a child of the world body: MuJoCo's parent-child contact filter does not
  // apply to them, so block 2 collides with block 1 (and with the ground).
  for (int k = 0; k < blocks; ++k)
    x += BlockMjcf(std::string("block") + std::to_string(k + 1), in.blocks[k]);
  x += "  </worldbody>\n";
  std::string contact;
  if (blocks >= 3) {
    // Three or more blocks: contacts between neighbours only (block 1 and the ground, block k
    // and block k - 1), as the model; every other pair excluded. (Two blocks keep block 2 and
    // the ground, as before issue 23.)
    for (int k = 2; k <= blocks; ++k) {
      contact +=
          std::string("    <exclude body1=\"world\" body2=\"block") + std::to_string(k) + "\"/>\n";
    }
    for (int i = 1; i <= blocks; ++i) {
      for (int j = i + 2; j <= blocks; ++j) {
        contact += std::string("    <exclude body1=\"block") + std::to_string(i) +
                   "\" body2=\"block" + std::to_string(j) + "\"/>\n";
      }
    }
  }
  contact += SceneFrictionPairs(in, c);
  if (!contact.empty()) x += std::string("  <contact>\n") + contact + "  </contact>\n";
  x += "</mujoco>\n";
  return x;
}

int JointQpos(const mjModel* m, const std::string& name, int* qvel_adr) {
  const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
  if (j < 0) throw std::runtime_error("mujoco: joint " + name + " missing from the model");
  *qvel_adr = m->jnt_dofadr[j];
  return m->jnt_qposadr[j];
}

void SetPose(mjData* d, int qpos, int qvel, const PlanarPose& p) {
  d->qpos[qpos + 0] = p.x_m;
  d->qpos[qpos + 1] = p.y_m;
  d->qpos[qpos + 2] = p.phi_rad;
  d->qvel[qvel + 0] = p.vx_mps;
  d->qvel[qvel + 1] = p.vy_mps;
  d->qvel[qvel + 2] = p.w_radps;
}

void ReadBody(const mjData* d, int qpos, int qvel, BodyReadout* out) {
  out->x_m = d->qpos[qpos + 0];
  out->y_m = d->qpos[qpos + 1];
  const double phi = d->qpos[qpos + 2];
  out->cos_phi = std::cos(phi);
  out->sin_phi = std::sin(phi);
  out->vx_mps = d->qvel[qvel + 0];
  out->vy_mps = d->qvel[qvel + 1];
  out->w_radps = d->qvel[qvel + 2];
}

void SetNaN(BodyReadout* b) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  *b = {nan, nan, nan, nan, nan, nan, nan};
}

}  // namespace

MujocoWorld::MujocoWorld(const EngineInput& input, const MujocoSettings& settings)
    : in_(input), s_(settings) {
  CheckModel(in_, s_);
  InstallQuietWarningHandler();
  dt_ = in_.time_step_s;
  xml_ = ModelMjcf(in_, s_);
  sim_ = std::make_unique<MujocoSim>(xml_);
  m_ = sim_->m();
  d_ = sim_->d();
  // Each block's joints are consecutive: (x, y, phi) at qpos_[k] .. qpos_[k] + 2.
  const int n = in_.block_count();
  qpos_.assign(static_cast<size_t>(n), 0);
  qvel_.assign(static_cast<size_t>(n), 0);
  for (int k = 0; k < n; ++k) {
    const std::string name = std::string("block") + std::to_string(k + 1);
    int v = 0;
    qpos_[k] = JointQpos(m_, name + "_x", &qvel_[k]);
    if (JointQpos(m_, name + "_phi", &v) != qpos_[k] + 2 || v != qvel_[k] + 2) {
      throw std::runtime_error("mujoco: unexpected joint layout");
    }
  }
  const StackPlacement place = PlaceStack(in_.blocks, in_.initial);
  for (int k = 0; k < n; ++k) SetPose(d_, qpos_[k], qvel_[k], place.blocks[k]);
  mj_forward(m_, d_);
}

MujocoWorld::~MujocoWorld() = default;

const mjModel_* MujocoWorld::model() const {
  return m_;
}

const mjData_* MujocoWorld::data() const {
  return d_;
}

void MujocoWorld::ApplyDrive(std::int64_t n) {
  const size_t i = static_cast<size_t>(n);
  const double ax = in_.drive.ax_mps2.empty() ? 0.0 : in_.drive.ax_mps2[i];
  const double ay = in_.drive.ay_mps2.empty() ? 0.0 : in_.drive.ay_mps2[i];
  // The exact equivalent of a translating base: effective gravity in the base frame.
  m_->opt.gravity[0] = -ax;
  m_->opt.gravity[1] = -(in_.run.gravity_mps2 + ay);
  m_->opt.gravity[2] = 0.0;
}

void MujocoWorld::Step() {
  sim_->Step();
}

StepReadout MujocoWorld::Read(std::int64_t n) const {
  StepReadout s(in_.block_count());
  s.t_s = static_cast<double>(n) * dt_;
  if (sim_->blown_up()) {
    for (BodyReadout& b : s.blocks) SetNaN(&b);
    return s;
  }
  for (size_t k = 0; k < qpos_.size(); ++k) ReadBody(d_, qpos_[k], qvel_[k], &s.blocks[k]);
  // The joints hold the plane exactly: no out-of-plane motion to report.
  s.out_of_plane_m = 0.0;
  s.out_of_plane_rad = 0.0;
  ReadBaseMotion(in_, n, &s);
  return s;
}

nlohmann::json MujocoWorld::Settings() const {
  nlohmann::json j = CommonSettings(in_, s_, m_);
  j["substeps_per_sample"] = std::max(1.0, std::round(in_.run.output_interval_s / dt_));
  j["friction_combined"] = s_.friction;  // MuJoCo takes the larger of the two geoms'
  j["condim"] = 3;
  j["ground"] = "plane y = 0";
  j["planar_joints"] = "slide x, slide y, hinge z per block";
  // Three or more blocks: contacts between neighbours only (two: block 2 and the ground too).
  if (qpos_.size() >= 3) j["collision_pairs"] = "neighbours";
  // Friction from the scene: each interface's coefficient as the compiled model has it, block 1
  // on the ground first: its explicit pair's (0 for a frictionless one), else the larger of the
  // two geoms' (MuJoCo's rule for a dynamic pair).
  if (HasFiniteFriction(in_)) {
    auto geom = [this](int k) {
      const std::string name =
          k == 0 ? std::string("ground") : std::string("block") + std::to_string(k);
      return mj_name2id(m_, mjOBJ_GEOM, name.c_str());
    };
    nlohmann::json mu = nlohmann::json::array();
    for (int k = 0; k < in_.block_count(); ++k) {
      const int lower = geom(k), upper = geom(k + 1);
      double v = std::max(m_->geom_friction[3 * lower], m_->geom_friction[3 * upper]);
      for (int p = 0; p < m_->npair; ++p) {
        if (m_->pair_geom1[p] == lower && m_->pair_geom2[p] == upper) {
          v = m_->pair_dim[p] == 1 ? 0.0 : m_->pair_friction[5 * p];
        }
      }
      mu.push_back(v);
    }
    j["interface_friction"] = mu;
  }
  return j;
}

nlohmann::json MujocoWorld::Diagnostics() const {
  return sim_->Diagnostics();
}

}  // namespace rockbench::mujoco
