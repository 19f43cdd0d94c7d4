#include "engines/box2d/box2d_world.h"

#include <box2d/box2d.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "scene/stack_pose.h"

namespace rockbench::box2d_engine {
namespace {

static_assert(sizeof(decltype(b2Vec2::x)) == sizeof(float), "Box2D 2.4 is single precision");

// Box2D's compile-time lengths, in Box2D's metres (b2_common.h).
constexpr double kSkin = b2_polygonRadius;                 // 0.01: polygons are rounded by it
constexpr double kSlop = b2_linearSlop;                    // 0.005: penetration left alone
constexpr double kMaxTranslation = b2_maxTranslation;      // 2: a body's largest move per step
constexpr double kMaxCorrection = b2_maxLinearCorrection;  // 0.2: largest push-out per iteration

// Whether a double fits a float (Box2D's) as a finite number.
bool FitsFloat(double v) {
  return std::abs(v) <= static_cast<double>(FLT_MAX);
}

// The input's own consistency (the settings' ranges are the [box2d] schema's, box2d_settings.cc;
// the step is checked by MakeEngineInput).
void CheckInput(const EngineInput& in) {
  if (in.drive_kind == DriveKind::kKinematic) {
    const size_t need = static_cast<size_t>(in.steps) + 1;
    if (in.drive.ux_m.size() < need || in.drive.uy_m.size() < need) {
      throw std::invalid_argument("box2d: kinematic drive needs ux_m and uy_m at n = 0..steps");
    }
  }
}

// A body's fixture index: 0 the ground, k block k (bottom first, from 1).
int IndexOf(b2Fixture* f) {
  return static_cast<int>(f->GetUserData().pointer);
}

}  // namespace

// The contact filter (neighbours only) and the friction of each contact (its interface's).
struct Box2dWorld::Callbacks final : public b2ContactFilter, public b2ContactListener {
  int blocks = 1;
  // mu[k]: the coefficient between block k + 1 and its support (k = 0: the ground); other:
  // block 2 on the ground (two blocks only), the settings' value.
  std::vector<float> mu;
  float other = 0.0f;

  bool ShouldCollide(b2Fixture* a, b2Fixture* b) override {
    const int i = IndexOf(a), j = IndexOf(b);
    if (std::abs(i - j) == 1) return true;
    // Two blocks: also block 2 on the ground, once it has fallen off block 1 (as ODE).
    return blocks == 2 && std::min(i, j) == 0 && std::max(i, j) == 2;
  }

  void PreSolve(b2Contact* contact, const b2Manifold* /*old_manifold*/) override {
    const int i = IndexOf(contact->GetFixtureA()), j = IndexOf(contact->GetFixtureB());
    const int upper = std::max(i, j);
    contact->SetFriction(std::abs(i - j) == 1 ? mu[static_cast<size_t>(upper - 1)] : other);
  }
};

Box2dWorld::Box2dWorld(const EngineInput& input, const Box2dSettings& settings)
    : WorldBase(input, settings) {
  CheckInput(in_);
  dt_ = in_.time_step_s;
  scale_ = s_.length_scale;
  const double s = scale_;
  const int n = in_.block_count();

  // Every block must be larger than the skin it is shrunk by, with a slop to spare (Box2D
  // welds polygon vertices closer than half a slop).
  for (int k = 0; k < n; ++k) {
    const BlockDef& def = in_.blocks[static_cast<size_t>(k)];
    const double half = 0.5 * std::min(def.width_m, def.height_m);
    if (!(s * half - kSkin > kSlop)) {
      char buf[300];
      std::snprintf(buf, sizeof buf,
                    "box2d: block %d's half size %.3g m is too small for Box2D's %.3g m skin at "
                    "length_scale %.3g (it must exceed %.3g m): raise box2d.length_scale",
                    k + 1, half, kSkin / s, s, (kSkin + kSlop) / s);
      throw std::invalid_argument(buf);
    }
  }
  ground_half_depth_ = 0.5 * s_.ground_depth_m * s;
  if (!(ground_half_depth_ - kSkin > kSlop)) {
    throw std::invalid_argument(
        "box2d: ground_depth times length_scale is too small for "
        "Box2D's skin");
  }

  world_ = std::make_unique<b2World>(b2Vec2(0.0f, static_cast<float>(-in_.run.gravity_mps2 * s)));
  world_->SetAllowSleeping(false);
  world_->SetWarmStarting(s_.warm_starting);
  world_->SetContinuousPhysics(s_.continuous);
  world_->SetSubStepping(false);
  world_->SetAutoClearForces(true);

  callbacks_ = std::make_unique<Callbacks>();
  callbacks_->blocks = n;
  const double engine_mu = std::min(s_.friction, kMaxFriction);
  for (int k = 0; k < n; ++k) {
    callbacks_->mu.push_back(
        static_cast<float>(std::min(InterfaceFriction(in_, k, s_.friction), kMaxFriction)));
  }
  callbacks_->other = static_cast<float>(engine_mu);
  world_->SetContactFilter(callbacks_.get());
  world_->SetContactListener(callbacks_.get());

  auto fixture = [&](b2Body* body, double half_w, double half_h, int index) {
    b2PolygonShape box;  // its radius is b2_polygonRadius
    box.SetAsBox(static_cast<float>(half_w - kSkin), static_cast<float>(half_h - kSkin));
    b2FixtureDef fd;
    fd.shape = &box;
    fd.density = 0.0f;  // the mass is set below (b2PolygonShape::ComputeMass ignores the skin)
    fd.friction = static_cast<float>(engine_mu);
    fd.restitution = static_cast<float>(s_.restitution);
    fd.restitutionThreshold = static_cast<float>(s_.restitution_threshold_mps * s);
    fd.userData.pointer = static_cast<uintptr_t>(index);
    body->CreateFixture(&fd);
  };

  // Ground: a box whose skin's top face is y = 0 in the base frame, much wider than the stack.
  double size = 0.5;
  for (const BlockDef& def : in_.blocks)
    size = std::max({size, 0.5 * def.width_m, 0.5 * def.height_m});
  // The world's origin is the ground's reference point at t = 0 (see ApplyDrive).
  origin_x_ = kinematic_ ? in_.drive.ux_m.front() * s : 0.0;
  origin_y_ = kinematic_ ? in_.drive.uy_m.front() * s : 0.0;
  const double gvx = kinematic_ ? in_.drive.ux0_mps : 0.0;
  const double gvy = kinematic_ ? in_.drive.uy0_mps : 0.0;
  {
    b2BodyDef gd;
    gd.type = kinematic_ ? b2_kinematicBody : b2_staticBody;
    gd.position.Set(0.0f, static_cast<float>(-ground_half_depth_));
    gd.linearVelocity.Set(static_cast<float>(gvx * s), static_cast<float>(gvy * s));
    gd.allowSleep = false;
    ground_ = world_->CreateBody(&gd);
    fixture(ground_, 20.0 * size * s, ground_half_depth_, 0);
  }

  // Blocks, placed by the pivot chain in the base frame then shifted with the ground; bottom
  // first.
  const StackPlacement place = PlaceStack(in_.blocks, in_.initial);
  bodies_.assign(static_cast<size_t>(n), nullptr);
  for (int k = 0; k < n; ++k) {
    const BlockDef& def = in_.blocks[static_cast<size_t>(k)];
    const PlanarPose& pose = place.blocks[static_cast<size_t>(k)];
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position.Set(static_cast<float>(pose.x_m * s), static_cast<float>(pose.y_m * s));
    bd.angle = static_cast<float>(pose.phi_rad);
    bd.linearVelocity.Set(static_cast<float>((pose.vx_mps + gvx) * s),
                          static_cast<float>((pose.vy_mps + gvy) * s));
    bd.angularVelocity = static_cast<float>(pose.w_radps);
    bd.linearDamping = 0.0f;
    bd.angularDamping = 0.0f;
    bd.allowSleep = false;
    bd.awake = true;
    bd.bullet = s_.bullet;
    b2Body* body = world_->CreateBody(&bd);
    fixture(body, 0.5 * def.width_m * s, 0.5 * def.height_m * s, k + 1);
    // Uniform box about its centre, the model's: I = m (w^2 + h^2) / 12, lengths scaled.
    b2MassData md;
    md.mass = static_cast<float>(def.mass_kg);
    md.center.SetZero();
    md.I = static_cast<float>(def.mass_kg * s * s *
                              (def.width_m * def.width_m + def.height_m * def.height_m) / 12.0);
    body->SetMassData(&md);
    bodies_[static_cast<size_t>(k)] = body;
  }
}

Box2dWorld::~Box2dWorld() {
  world_.reset();  // destroys the bodies and contacts, which may call the listener
}

void Box2dWorld::ApplyDrive(std::int64_t n) {
  const size_t i = static_cast<size_t>(n);
  const double s = scale_;
  char buf[200];
  if (!kinematic_) {
    const double ax = in_.drive.ax_mps2.empty() ? 0.0 : in_.drive.ax_mps2[i];
    const double ay = in_.drive.ay_mps2.empty() ? 0.0 : in_.drive.ay_mps2[i];
    // The exact equivalent of a translating base: effective gravity in the base frame.
    const double gx = -ax * s, gy = -(in_.run.gravity_mps2 + ay) * s;
    if (!FitsFloat(gx) || !FitsFloat(gy)) {
      std::snprintf(buf, sizeof buf,
                    "the effective gravity (%.3g, %.3g) m/s^2 times length_scale is beyond the "
                    "range of Box2D's float: the step was not taken",
                    -ax, -(in_.run.gravity_mps2 + ay));
      fault_ = buf;
      return;
    }
    world_->SetGravity(b2Vec2(static_cast<float>(gx), static_cast<float>(gy)));
    return;
  }
  // Kinematic: the ground at u_n (where collision detection sees it, with the blocks) moving
  // with (u_{n+1} - u_n) / dt; Box2D moves it on to about u_{n+1} (reset here, from the double).
  // The world's origin follows the ground (b2World::ShiftOrigin): Box2D's float coordinates
  // stay those relative to the ground, whose rounding does not grow with the distance carried
  // (2.2 m carried at 0.49 m/s drifted the blocks by 4.5e-4 m against the ground with a fixed
  // origin, every step rounding their move by the same fraction of an ulp at 220 m of Box2D's).
  const double ux = in_.drive.ux_m[i], uy = in_.drive.uy_m[i];
  const double vx = (in_.drive.ux_m[i + 1] - ux) / dt_, vy = (in_.drive.uy_m[i + 1] - uy) / dt_;
  const double shift_x = ux * s - origin_x_, shift_y = uy * s - origin_y_;
  if (!FitsFloat(shift_x) || !FitsFloat(shift_y) || !FitsFloat(vx * s) || !FitsFloat(vy * s)) {
    std::snprintf(buf, sizeof buf,
                  "the ground's position (%.3g, %.3g) m or velocity (%.3g, %.3g) m/s times "
                  "length_scale is beyond the range of Box2D's float: the step was not taken",
                  ux, uy, vx, vy);
    fault_ = buf;
    return;
  }
  const b2Vec2 shift(static_cast<float>(shift_x), static_cast<float>(shift_y));
  world_->ShiftOrigin(shift);
  origin_x_ += static_cast<double>(shift.x);
  origin_y_ += static_cast<double>(shift.y);
  ground_->SetTransform(b2Vec2(static_cast<float>(ux * s - origin_x_),
                               static_cast<float>(uy * s - origin_y_ - ground_half_depth_)),
                        0.0f);
  ground_->SetLinearVelocity(b2Vec2(static_cast<float>(vx * s), static_cast<float>(vy * s)));
}

void Box2dWorld::Step() {
  if (!fault_.empty()) return;  // the run has ended (see the header)
  world_->Step(static_cast<float>(dt_), s_.velocity_iterations, s_.position_iterations);
  ++steps_;
  // b2Island::Solve scales a velocity down to b2_maxTranslation per step (in float: a capped
  // body moves 2 m of Box2D's, to rounding).
  const double cap = 0.999 * kMaxTranslation / dt_;
  for (const b2Body* b : bodies_) {
    if (static_cast<double>(b->GetLinearVelocity().Length()) >= cap) {
      if (capped_steps_++ == 0) first_capped_t_s_ = static_cast<double>(steps_) * dt_;
      break;
    }
  }
}

StepReadout Box2dWorld::Read(std::int64_t n) const {
  StepReadout out(in_.block_count());
  out.t_s = static_cast<double>(n) * dt_;
  const double inv = 1.0 / scale_;
  for (size_t k = 0; k < bodies_.size(); ++k) {
    const b2Body* b = bodies_[k];
    const b2Vec2 p = b->GetPosition();  // the body's origin: the block's centre
    const double phi = b->GetAngle();
    const b2Vec2 v = b->GetLinearVelocity();
    BodyReadout& r = out.blocks[k];
    r.x_m = (origin_x_ + p.x) * inv;
    r.y_m = (origin_y_ + p.y) * inv;
    r.cos_phi = std::cos(phi);
    r.sin_phi = std::sin(phi);
    r.vx_mps = v.x * inv;
    r.vy_mps = v.y * inv;
    r.w_radps = b->GetAngularVelocity();
  }
  out.out_of_plane_m = 0.0;  // a planar engine
  out.out_of_plane_rad = 0.0;
  ReadBaseMotion(in_, n, &out);
  out.engine_fault = fault_;
  return out;
}

nlohmann::json Box2dWorld::Settings() const {
  const double s = scale_;
  nlohmann::json j;
  char version[32];
  std::snprintf(version, sizeof version, "%d.%d.%d", b2_version.major, b2_version.minor,
                b2_version.revision);
  j["box2d_version"] = version;
  j["precision"] = "float";
  j["drive"] = DriveKindName(in_.drive_kind);
  j["time_step_s"] = dt_;
  j["output_interval_s"] = in_.run.output_interval_s;
  j["substeps_per_sample"] = std::max(1.0, std::round(in_.run.output_interval_s / dt_));
  j["velocity_iterations"] = s_.velocity_iterations;
  j["position_iterations"] = s_.position_iterations;
  j["length_scale"] = s;
  // Box2D's fixed lengths in the scene's metres, and the speed its per-step cap allows.
  j["polygon_radius_m"] = kSkin / s;
  j["linear_slop_m"] = kSlop / s;
  j["max_linear_correction_m"] = kMaxCorrection / s;
  j["max_speed_mps"] = kMaxTranslation / (s * dt_);
  j["friction"] = std::min(s_.friction, kMaxFriction);
  // Friction from the scene: each interface's coefficient, block 1 on the ground first.
  if (HasFiniteFriction(in_)) {
    nlohmann::json mu = nlohmann::json::array();
    for (int k = 0; k < in_.block_count(); ++k) {
      mu.push_back(std::min(InterfaceFriction(in_, k, s_.friction), kMaxFriction));
    }
    j["interface_friction"] = mu;
  }
  j["restitution"] = s_.restitution;
  j["restitution_threshold_mps"] = s_.restitution_threshold_mps;
  j["warm_starting"] = world_->GetWarmStarting();
  j["continuous"] = world_->GetContinuousPhysics();
  j["bullet"] = s_.bullet;
  j["sleeping"] = world_->GetAllowSleeping();
  j["ground_depth_m"] = s_.ground_depth_m;
  j["kinematic_highpass_hz"] = in_.kinematic_highpass_hz;
  // Three or more blocks: contacts between neighbours only (two: block 2 and the ground too).
  if (bodies_.size() >= 3) j["collision_pairs"] = "neighbours";
  return j;
}

nlohmann::json Box2dWorld::Diagnostics() const {
  nlohmann::json j;
  j["max_translation_capped_steps"] = capped_steps_;
  if (capped_steps_ > 0) j["max_translation_first_capped_t_s"] = first_capped_t_s_;
  return j;
}

}  // namespace rockbench::box2d_engine
