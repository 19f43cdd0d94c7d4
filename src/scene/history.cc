#include "scene/history.h"

#include <stdexcept>

namespace rockbench {

Sample::Sample(int blocks, const BodyKind& kind)
    : mode(blocks), state(kind.state.size(), BlockValues(static_cast<size_t>(blocks))) {}

double StateValue(const History& history, const Sample& sample, std::string_view stem,
                  int body) {
  const size_t k = static_cast<size_t>(body - 1);
  if (history.shape == PlanarBlockKind().shape) {
    if (stem == "theta") return sample.theta_rad[k];
    if (stem == "omega") return sample.omega_radps[k];
    if (stem == "u" && history.slip_and_lift) return sample.u_m[k];
    if (stem == "z" && history.slip_and_lift) return sample.z_m[k];
  } else if (const BodyKind* kind = FindBodyKind(history.shape)) {
    for (size_t q = 0; q < kind->state.size(); ++q) {
      if (kind->state[q].stem == stem) return sample.state[q][k];
    }
  }
  throw std::invalid_argument("a history of '" + history.shape + "' bodies has no quantity '" +
                              std::string(stem) + "'");
}

}  // namespace rockbench
