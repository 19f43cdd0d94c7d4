#include "reference/mechanics.h"

#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "reference/thesis/impact.h"
#include "reference/thesis/kinematics.h"
#include "reference/thesis/modes.h"
#include "reference/thesis/observables.h"
#include "reference/thesis/transitions.h"

namespace rockbench::reference {
namespace {

State ToState(const Vec4& y) {
  return {y[0], y[1], y[2], y[3]};
}
Vec4 ToVec(const State& s) {
  return {s.theta1, s.theta2, s.omega1, s.omega2};
}

}  // namespace

// ---- ThesisMechanics ----

ThesisMechanics::ThesisMechanics(const Scene& scene)
    : geo_(MakeGeometry(scene)), equations_(scene.model.equations) {}

double ThesisMechanics::time_scale_s() const {
  return std::sqrt(geo_.R / geo_.g);
}

ThesisMechanics::Y ThesisMechanics::Initial(const InitialState& in) const {
  // One block: the stack is the one block (theta2 = theta1), as the equations expect.
  const int top = geo_.two_blocks ? 1 : 0;
  return {in.theta_rad[0], in.theta_rad[top], in.omega_radps[0], in.omega_radps[top]};
}

namespace {
ThesisMechanics::Margins MarginsOf(const ContactMargins& cm) {
  ThesisMechanics::Margins m;
  m.face = cm.face;
  m.point = cm.point;
  m.normal_n = {cm.reactions.N_ground, cm.reactions.N_interface};
  m.mu = {cm.mu_ground, cm.mu_interface};
  return m;
}
}  // namespace

ThesisMechanics::Margins ThesisMechanics::Evaluate(const Configuration& c, const Y& y, double xg,
                                                   double yg) const {
  // EvaluateContacts(geo_, mode, state, xg, yg, equations_), with the tilts from the memo.
  const Mode mode = *ModeOfConfiguration(c);
  const State s = ToState(y);
  const Tilts tilts = TiltsAt(y);
  const auto acc = ModeAccelerations(geo_, mode, s, tilts, xg, yg, equations_);
  return MarginsOf(EvaluateContacts(geo_, mode, s, tilts, acc, xg, yg));
}

ThesisMechanics::Margins ThesisMechanics::EvaluateWithRhs(const Configuration& c, const Y& y,
                                                          const Y& f, double xg, double yg) const {
  return MarginsOf(EvaluateContacts(geo_, *ModeOfConfiguration(c), ToState(y), TiltsAt(y),
                                    {f[2], f[3]}, xg, yg));
}

Selection ThesisMechanics::Select(const Y& y, double xg, double yg) const {
  const ModeSelection sel = SelectMode(geo_, ToState(y), xg, yg, equations_);
  return {ConfigurationOf(sel.mode, blocks()), sel.consistent, ""};
}

bool ThesisMechanics::NonFiniteForces(const Y& y, double xg, double yg, double* value) const {
  for (const Contact g : {Contact::kFace, Contact::kRight, Contact::kLeft}) {
    for (const Contact i : {Contact::kFace, Contact::kRight, Contact::kLeft}) {
      if (!geo_.two_blocks && i != Contact::kFace) continue;
      const ContactMargins cm =
          EvaluateContacts(geo_, ModeOf({g, i}, geo_.two_blocks), ToState(y), xg, yg, equations_);
      for (const double m : {cm.face, cm.point}) {
        if (!std::isfinite(m)) {
          *value = m;
          return true;
        }
      }
    }
  }
  return false;
}

ThesisMechanics::Impact ThesisMechanics::ResolveImpact(const Configuration& c, const Y& y,
                                                       int interface, double rest_rel) const {
  const ImpactResult ir = ::rockbench::reference::ResolveImpact(
      geo_, *ModeOfConfiguration(c), ToState(y),
      interface == 0 ? ImpactKind::kGround : ImpactKind::kInterface, rest_rel);
  Impact out;
  out.config = ConfigurationOf(ir.chosen.mode, blocks());
  out.y = ToVec(ir.chosen.state);
  out.admissible = ir.admissible;
  out.admissible_outcomes = ir.admissible_outcomes;
  out.settled = ir.settled;
  out.energy_before_j = ir.energy_before_j;
  out.energy_after_j = ir.chosen.energy_after_j;
  out.note = ir.note;
  return out;
}

double ThesisMechanics::Energy(const Configuration& c, const Y& y) const {
  return ::rockbench::reference::Energy(geo_, *ModeOfConfiguration(c), ToState(y));
}

// ---- ChainMechanics ----

StackGeometry StackGeometryOf(const Scene& scene) {
  std::vector<BlockSize> sizes;
  for (const BlockDef& b : scene.blocks) sizes.push_back({b.width_m, b.height_m, b.mass_kg});
  return MakeStackGeometry(sizes, scene.run.gravity_mps2);
}

namespace {
StackGeometry CheckedGeometry(const Scene& scene, size_t cap) {
  // ValidateScene has refused the linearized equations for the chain.
  StackGeometry geo = StackGeometryOf(scene);
  if (geo.blocks.size() > cap) {
    throw SceneError(scene.path.string() + ": internal: " + std::to_string(geo.blocks.size()) +
                     " blocks in a chain of capacity " + std::to_string(cap));
  }
  return geo;
}
}  // namespace

template <size_t Cap>
ChainMechanics<Cap>::ChainMechanics(const Scene& scene) : contacts_(CheckedGeometry(scene, Cap)) {
  n_ = contacts_.size();
}

template <size_t Cap>
typename ChainMechanics<Cap>::Y ChainMechanics<Cap>::Initial(const InitialState& in) const {
  Y y{};
  for (int i = 0; i < n_; ++i) {
    y[i] = in.theta_rad[i];
    y[Cap + i] = in.omega_radps[i];
  }
  return y;
}

template <size_t Cap>
double ChainMechanics<Cap>::time_scale_s() const {
  return std::sqrt(contacts_.rest_radius_m(0) / contacts_.geometry().g);
}

template <size_t Cap>
typename ChainMechanics<Cap>::Y ChainMechanics<Cap>::Rhs(const Configuration& c, const Y& y,
                                                         double xg, double yg) const {
  std::array<double, Cap> acc;
  StackChain& chain = contacts_.chain();
  chain.Place(c, y.data(), y.data() + Cap);
  chain.Accelerations(xg, yg, acc.data());
  Y f{};
  for (int i = 0; i < n_; ++i) {
    f[i] = y[Cap + i];
    f[Cap + i] = acc[i];
  }
  return f;
}

template <size_t Cap>
typename ChainMechanics<Cap>::Y ChainMechanics<Cap>::Project(const Configuration& c,
                                                             const Y& y) const {
  Y p = y;
  for (int k = 0; k < n_; ++k) {
    if (c[k] != Contact::kFace) continue;
    p[k] = k == 0 ? 0.0 : p[k - 1];
    p[Cap + k] = k == 0 ? 0.0 : p[Cap + k - 1];
  }
  return p;
}

template <size_t Cap>
typename ChainMechanics<Cap>::Y ChainMechanics<Cap>::Land(const Configuration& c, Y y,
                                                          int interface) const {
  y[interface] = interface == 0 ? 0.0 : y[interface - 1];
  for (int k = interface + 1; k < n_ && c[k] == Contact::kFace; ++k) y[k] = y[k - 1];
  return y;
}

template <size_t Cap>
typename ChainMechanics<Cap>::Margins ChainMechanics<Cap>::Evaluate(const Configuration& c,
                                                                    const Y& y, double xg,
                                                                    double yg) const {
  std::array<double, Cap> acc;
  const StackMargins sm = contacts_.Evaluate(c, y.data(), y.data() + Cap, xg, yg, acc.data());
  Margins m;
  m.face = sm.face;
  m.point = sm.point;
  for (int k = 0; k < n_; ++k) {
    const InterfaceLoad& L = contacts_.loads()[k];
    m.normal_n[k] = L.normal_n;
    m.mu[k] = RequiredFriction(L.normal_n, L.tangential_n);
  }
  return m;
}

template <size_t Cap>
Selection ChainMechanics<Cap>::Select(const Y& y, double xg, double yg) const {
  const StackSelection sel = contacts_.Select(y.data(), y.data() + Cap, xg, yg);
  Selection out{sel.config, sel.consistent, ""};
  if (sel.search_capped) {
    out.note = "no configuration found among the first " +
               std::to_string(StackContacts::kMaxCandidates) + " (search stopped)";
  }
  return out;
}

template <size_t Cap>
bool ChainMechanics<Cap>::NonFiniteForces(const Y& y, double xg, double yg, double* value) const {
  // The configuration that keeps every closed interface closed.
  Configuration c(n_);
  for (int k = 0; k < n_; ++k) {
    if (StackContacts::Closed(y.data(), y.data() + Cap, k)) continue;
    const double gap = k == 0 ? y[0] : y[k] - y[k - 1];
    const double rate = k == 0 ? y[Cap] : y[Cap + k] - y[Cap + k - 1];
    c.set(k, (gap != 0.0 ? gap : rate) > 0.0 ? Contact::kRight : Contact::kLeft);
  }
  const Margins m = Evaluate(c, y, xg, yg);
  for (const double v : {m.face, m.point}) {
    if (!std::isfinite(v)) {
      *value = v;
      return true;
    }
  }
  return false;
}

template <size_t Cap>
typename ChainMechanics<Cap>::Impact ChainMechanics<Cap>::ResolveImpact(const Configuration& c,
                                                                        const Y& y, int interface,
                                                                        double rest_rel) const {
  const StackImpact si = contacts_.ResolveImpact(c, y.data(), y.data() + Cap, interface, rest_rel);
  Impact out;
  out.config = si.chosen.config;
  out.y = y;
  for (int i = 0; i < n_; ++i) out.y[Cap + i] = si.chosen.omega_radps[i];
  out.admissible = si.admissible;
  out.admissible_outcomes = si.admissible_outcomes;
  out.settled = si.settled;
  out.energy_before_j = si.energy_before_j;
  out.energy_after_j = si.chosen.energy_after_j;
  out.note = si.note;
  return out;
}

template <size_t Cap>
double ChainMechanics<Cap>::Energy(const Configuration& c, const Y& y) const {
  StackChain& chain = contacts_.chain();
  chain.Place(c, y.data(), y.data() + Cap);
  return chain.Energy();
}

template class ChainMechanics<2>;
template class ChainMechanics<4>;
template class ChainMechanics<8>;
template class ChainMechanics<16>;
template class ChainMechanics<32>;
template class ChainMechanics<64>;

}  // namespace rockbench::reference
