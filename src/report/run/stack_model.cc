#include "report/run/stack_model.h"

#include "reference/mechanics.h"
#include "reference/thesis/observables.h"

namespace rockbench::report {

StackModel::StackModel(const Scene& scene)
    : blocks_(scene.block_count()), equations_(scene.model.equations) {
  if (blocks_ <= 2) {
    geo_ = reference::MakeGeometry(scene);
    weight_n_ = geo_->M * geo_->g;
    return;
  }
  chain_.emplace(reference::StackGeometryOf(scene));
  acc_.assign(static_cast<size_t>(blocks_), 0.0);
  double mass_kg = 0.0;
  for (const BlockDef& b : scene.blocks) mass_kg += b.mass_kg;
  weight_n_ = mass_kg * scene.run.gravity_mps2;
  const std::vector<double> zeros(static_cast<size_t>(blocks_), 0.0);
  chain_->chain().Place(Configuration(blocks_), zeros.data(), zeros.data());
  rest_energy_j_ = chain_->chain().Energy();
}

double StackModel::EnergyAboveRest_j(const Sample& s) const {
  if (geo_) return reference::EnergyAboveRest_j(*geo_, reference::StateOf(s, geo_->two_blocks));
  chain_->chain().Place(s.mode, s.theta_rad.data(), s.omega_radps.data());
  return chain_->chain().Energy() - rest_energy_j_;
}

StackModel::Contacts StackModel::Reactions(const Sample& s, double xg_mps2, double yg_mps2) const {
  Contacts out;
  if (geo_) {
    const reference::ContactDemand c = reference::ContactReactions(
        *geo_, ModeOfConfiguration(s.mode).value_or(Mode::kRest),
        reference::StateOf(s, geo_->two_blocks), xg_mps2, yg_mps2, equations_);
    out.normal_n.push_back(c.reactions.N_ground);
    out.mu.push_back(c.mu_ground);
    if (geo_->two_blocks) {
      out.normal_n.push_back(c.reactions.N_interface);
      out.mu.push_back(c.mu_interface);
    }
    return out;
  }
  chain_->Evaluate(s.mode, s.theta_rad.data(), s.omega_radps.data(), xg_mps2, yg_mps2, acc_.data());
  for (const reference::InterfaceLoad& l : chain_->loads()) {
    out.normal_n.push_back(l.normal_n);
    out.mu.push_back(reference::RequiredFriction(l.normal_n, l.tangential_n));
  }
  return out;
}

}  // namespace rockbench::report
