#include "scene/history.h"

#include <stdexcept>

namespace rockbench {

Sample::Sample(int blocks, const BodyKind& kind)
    : mode(blocks), state(kind.state.size(), BlockValues(static_cast<size_t>(blocks))) {}

StateQuantityReader::StateQuantityReader(const History& history, std::string_view stem) {
  if (history.shape == PlanarBlockKind().shape) {
    const bool slip = history.slip_and_lift;
    if (stem == "theta") return;
    if (stem == "omega") {
      field_ = Field::kOmega;
      return;
    }
    if (stem == "u" && slip) {
      field_ = Field::kSlip;
      return;
    }
    if (stem == "z" && slip) {
      field_ = Field::kLift;
      return;
    }
  } else if (const BodyKind* kind = FindBodyKind(history.shape)) {
    for (size_t q = 0; q < kind->state.size(); ++q) {
      if (kind->state[q].stem != stem) continue;
      field_ = Field::kState;
      state_index_ = q;
      return;
    }
  }
  throw std::invalid_argument("a history of '" + history.shape + "' bodies has no quantity '" +
                              std::string(stem) + "'");
}

double StateQuantityReader::operator()(const Sample& sample, int body) const {
  const size_t k = static_cast<size_t>(body - 1);
  switch (field_) {
    case Field::kTheta:
      return sample.theta_rad[k];
    case Field::kOmega:
      return sample.omega_radps[k];
    case Field::kSlip:
      return sample.u_m[k];
    case Field::kLift:
      return sample.z_m[k];
    case Field::kState:
      break;
  }
  return sample.state[state_index_][k];
}

}  // namespace rockbench
