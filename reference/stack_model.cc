#include "reference/stack_model.h"

#include <optional>

#include "reference/chain/stack_contacts.h"
#include "reference/mechanics.h"
#include "reference/thesis/geometry.h"
#include "reference/thesis/observables.h"
#include "reference/thesis/transitions.h"

namespace rockbench::reference {

struct StackModel::Impl {
  int blocks = 1;
  double weight_n = 0.0;
  Equations equations = Equations::kNonlinear;
  std::optional<Geometry> geo;
  // The chain keeps a workspace (N >= 3).
  std::optional<StackContacts> chain;
  std::vector<double> acc, zeros;
  double rest_energy_j = 0.0;
};

StackModel::StackModel(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.blocks = scene.block_count();
  m.equations = scene.model.equations;
  m.acc.assign(static_cast<size_t>(m.blocks), 0.0);
  m.zeros.assign(static_cast<size_t>(m.blocks), 0.0);
  if (m.blocks <= 2) {
    m.geo = MakeGeometry(scene);
    m.weight_n = m.geo->M * m.geo->g;
    return;
  }
  m.chain.emplace(StackGeometryOf(scene));
  double mass_kg = 0.0;
  for (const BlockDef& b : scene.blocks) mass_kg += b.mass_kg;
  m.weight_n = mass_kg * scene.run.gravity_mps2;
  m.chain->chain().Place(Configuration(m.blocks), m.zeros.data(), m.zeros.data());
  m.rest_energy_j = m.chain->chain().Energy();
}

StackModel::~StackModel() = default;

int StackModel::blocks() const {
  return impl_->blocks;
}

double StackModel::weight_n() const {
  return impl_->weight_n;
}

double StackModel::EnergyAboveRest_j(const Sample& s) const {
  Impl& m = *impl_;
  if (m.geo) return reference::EnergyAboveRest_j(*m.geo, StateOf(s, m.geo->two_blocks));
  m.chain->chain().Place(s.mode, s.theta_rad.data(), s.omega_radps.data());
  return m.chain->chain().Energy() - m.rest_energy_j;
}

StackModel::Contacts StackModel::Reactions(const Sample& s, double xg_mps2, double yg_mps2) const {
  Impl& m = *impl_;
  Contacts out;
  if (m.geo) {
    const ContactDemand c =
        ContactReactions(*m.geo, ModeOfConfiguration(s.mode).value_or(Mode::kRest),
                         StateOf(s, m.geo->two_blocks), xg_mps2, yg_mps2, m.equations);
    out.normal_n.push_back(c.reactions.N_ground);
    out.mu.push_back(c.mu_ground);
    if (m.geo->two_blocks) {
      out.normal_n.push_back(c.reactions.N_interface);
      out.mu.push_back(c.mu_interface);
    }
    return out;
  }
  m.chain->Evaluate(s.mode, s.theta_rad.data(), s.omega_radps.data(), xg_mps2, yg_mps2,
                    m.acc.data());
  for (const InterfaceLoad& l : m.chain->loads()) {
    out.normal_n.push_back(l.normal_n);
    out.mu.push_back(RequiredFriction(l.normal_n, l.tangential_n));
  }
  return out;
}

double StackModel::RestFaceMargin(double xg_mps2, double yg_mps2) const {
  Impl& m = *impl_;
  if (m.chain) {
    const StackMargins margins = m.chain->Evaluate(Configuration(m.blocks), m.zeros.data(),
                                                   m.zeros.data(), xg_mps2, yg_mps2, m.acc.data());
    return margins.face;
  }
  return EvaluateContacts(*m.geo, Mode::kRest, State{}, xg_mps2, yg_mps2, m.equations).face;
}

}  // namespace rockbench::reference
