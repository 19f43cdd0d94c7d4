#pragma once
/// Histories and events: what every engine (the reference included) returns (their files:
/// files/history_csv.h).
#include <string>
#include <string_view>
#include <vector>

#include "scene/block_values.h"
#include "scene/body_kind.h"
#include "scene/mode.h"

namespace rockbench {

/// One sample of the state of a stack of N blocks: block k's absolute angle and rate at index
/// k - 1 (bottom first), and the contact configuration. Built for a number of blocks
/// (Sample(N)), so that its vectors always hold one entry per block.
struct Sample {
  double t_s = 0.0;
  BlockValues theta_rad;    ///< rad, one per block
  BlockValues omega_radps;  ///< rad/s, one per block
  Configuration mode;       ///< one contact per interface (block)
  /// Slip and lift (docs/sliding.md), one per block when the history tracks them (History::
  /// slip_and_lift), else empty: block k's base-centre slip relative to its support, m (> 0:
  /// to the right), and the height of its lowest base corner above its support's top, m (0 in
  /// contact).
  BlockValues u_m, z_m;
  /// The state of bodies of another kind than the planar block (History::shape,
  /// scene/body_kind.h): one entry per quantity of the kind's state, in its order, each with one
  /// value per body. Empty for planar blocks, whose state is theta_rad and omega_radps (those
  /// are empty for another kind).
  std::vector<BlockValues> state;

  /// A sample of `blocks` planar blocks at t = 0, at rest (with slip and lift: `slip_and_lift`).
  explicit Sample(int blocks, bool slip_and_lift = false)
      : theta_rad(static_cast<size_t>(blocks)),
        omega_radps(static_cast<size_t>(blocks)),
        mode(blocks),
        u_m(slip_and_lift ? static_cast<size_t>(blocks) : 0),
        z_m(slip_and_lift ? static_cast<size_t>(blocks) : 0) {}
  /// A sample of `blocks` bodies of `kind` at t = 0, every quantity zero.
  Sample(int blocks, const BodyKind& kind);
  /// The number of bodies (one contact configuration entry each).
  int blocks() const { return mode.size(); }
};

/// An event: impact, transition, initiation, rest, overturn, assumption violated, ... The rates
/// hold one entry per block (Event(N)).
struct Event {
  double t_s = 0.0;
  std::string kind;  ///< "ground_impact", "interface_impact", "initiation", "transition", "rest",
                     ///< "overturn", "assumption_violated"
  Configuration mode_before, mode_after;
  BlockValues omega_before_radps, omega_after_radps;   ///< rad/s, one per block
  double energy_before_j = 0.0, energy_after_j = 0.0;  ///< kinetic + potential, J
  std::string note;  ///< free text (no commas), e.g. "inadmissible: ..." or a criterion name

  /// An event of a stack of `blocks` blocks: at rest before and after, every rate zero.
  explicit Event(int blocks)
      : mode_before(blocks),
        mode_after(blocks),
        omega_before_radps(static_cast<size_t>(blocks)),
        omega_after_radps(static_cast<size_t>(blocks)) {}
  int blocks() const { return static_cast<int>(omega_before_radps.size()); }
};

struct History {
  int blocks = 2;  ///< blocks of the stack: every sample and event has this many
  std::vector<Sample> samples;
  std::vector<Event> events;
  /// Whether samples carry slip and lift (u1..uN, z1..zN after the mode column): a scene with
  /// a finite friction or a vertical motion (Scene::tracks_slip_and_lift).
  bool slip_and_lift = false;
  /// The kind of the stack's bodies (scene/body_kind.h): "block", the planar rigid block, or
  /// another registered kind, whose samples hold its state in Sample::state.
  std::string shape = "block";
};

/// A quantity of a history's bodies (theta, omega, u and z of a planar block, or a quantity of
/// the history's body kind), its kind looked up once: reading a sample is then an index.
class StateQuantityReader {
 public:
  /// Throws std::invalid_argument when the kind of `history`'s bodies has no quantity `stem`.
  StateQuantityReader(const History& history, std::string_view stem);
  /// Body `body`'s (1-based) value in `sample`.
  double operator()(const Sample& sample, int body) const;

 private:
  enum class Field { kTheta, kOmega, kSlip, kLift, kState };
  Field field_ = Field::kTheta;
  size_t state_index_ = 0;  // the kind's quantity, for kState
};

}  // namespace rockbench
