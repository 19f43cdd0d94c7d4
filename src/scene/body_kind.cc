#include "scene/body_kind.h"

#include <deque>
#include <mutex>
#include <stdexcept>

namespace rockbench {
namespace {

// The registry, "block" first: a deque, so that a kind found stays where it is when another is
// added.
struct Registry {
  std::mutex mutex;
  std::deque<BodyKind> kinds;
};

Registry& TheRegistry() {
  static Registry* r = [] {
    auto* reg = new Registry;
    reg->kinds.push_back({"block", {{"theta", "rad", true}, {"omega", "rad/s", false}}, {}, "omega"});
    reg->kinds.push_back({std::string(kCylinderShape),
                          {{"tilt", "rad", false},
                           {"azimuth", "rad", false},
                           {"spin", "rad", false},
                           {"tilt_x", "rad", true},
                           {"tilt_y", "rad", true},
                           {"tilt_rate", "rad/s", false},
                           {"azimuth_rate", "rad/s", false},
                           {"spin_rate", "rad/s", false}},
                          {"rest", "rim", "rim"},
                          "tilt_rate"});
    return reg;
  }();
  return *r;
}

}  // namespace

const BodyKind& PlanarBlockKind() {
  static const BodyKind& planar = *FindBodyKind("block");
  return planar;
}

const BodyKind& CylinderKind() {
  static const BodyKind& cylinder = *FindBodyKind(kCylinderShape);
  return cylinder;
}

std::string BodyColumn(std::string_view stem, int body) {
  // Appended: GCC 12 warns, wrongly, on std::string + std::string here (-Wrestrict).
  std::string out(stem);
  out += std::to_string(body);
  return out;
}

void RegisterBodyKind(const BodyKind& kind) {
  if (kind.shape.empty()) throw std::invalid_argument("a body kind needs a shape");
  if (kind.state.empty()) {
    throw std::invalid_argument("body kind '" + kind.shape + "' has no state quantity");
  }
  for (size_t i = 0; i < kind.state.size(); ++i) {
    if (kind.state[i].stem.empty()) {
      throw std::invalid_argument("body kind '" + kind.shape + "' has an empty stem");
    }
    for (size_t j = 0; j < i; ++j) {
      if (kind.state[i].stem == kind.state[j].stem) {
        throw std::invalid_argument("body kind '" + kind.shape + "' names '" + kind.state[i].stem +
                                    "' twice");
      }
    }
  }
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const BodyKind& k : r.kinds) {
    if (k.shape == kind.shape) {
      throw std::invalid_argument("body kind '" + kind.shape + "' is already registered");
    }
  }
  r.kinds.push_back(kind);
}

const BodyKind* FindBodyKind(std::string_view shape) {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const BodyKind& k : r.kinds) {
    if (k.shape == shape) return &k;
  }
  return nullptr;
}

std::vector<std::string> BodyShapes() {
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> out;
  for (const BodyKind& k : r.kinds) out.push_back(k.shape);
  return out;
}

}  // namespace rockbench
