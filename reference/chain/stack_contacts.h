#pragma once
/// The contact conditions of an N-block stack (issue 23): which configuration a state moves in
/// (transitions without impact, by complementarity over the closed interfaces), and what an
/// impact leaves (impulse-momentum with the admissibility checks of the two-block model,
/// generalised). The N-block counterpart of transitions.h and impact.h, on the pivot chain of
/// stack_chain.h; for two blocks it makes the same choices (tests/reference/stack_contacts_test).
///
/// A closed interface (zero relative angle and rate) holds while the normal forces at both
/// corners of its face are compressive; when one turns tensile the face opens about the other
/// corner. A configuration is consistent with a state when its faces carry compressive corner
/// forces, its pivots compressive normal forces, and every interface that is closed in the
/// state but open in the configuration accelerates open. The contact problem has a positive
/// definite mass matrix, so at most one configuration is consistent; the search tries them in
/// the order of the number of interfaces that open (the stack does not move unless it must),
/// then from the bottom, right before left, as the two-block model does.
///
/// Impacts are perfectly plastic at the corner that lands (stack_chain.h ImpactRates). An
/// outcome is admissible when no interface that was closed at the impact closes further (its
/// blocks separate or stay) and every contact of the outcome takes a compressive impulse.
/// At most one motion is admissible (impact.h, "Uniqueness"): the search stops at the first
/// admissible outcome, and set_exhaustive(true) makes it go on to check that no other is.
#include <string>
#include <vector>

#include "reference/chain/stack_chain.h"
#include "scene/mode.h"

namespace rockbench::reference {

/// The contact margins of a configuration at a state, normalised by the total weight M g.
struct StackMargins {
  double face = 1.0;   ///< smallest face-corner force / (M g); 1 when no interface is closed
  double point = 1.0;  ///< smallest pivot normal force / (M g); 1 when none is open
  // (Not capped at 1: the driver's probes of the margins follow their values.)
};

/// The configuration a state must move in, and whether any is consistent.
struct StackSelection {
  Configuration config;
  bool consistent = true;
  /// True when the search stopped at kMaxCandidates without an answer (consistent is false).
  bool search_capped = false;
};

/// One outcome of an impact.
struct StackImpactOutcome {
  Configuration config;
  std::vector<double> omega_radps;   ///< the rates after (absolute, rad/s)
  bool velocity_admissible = false;  ///< no interface closed at the impact closes further
  bool impulse_admissible = false;   ///< every contact of `config` pushes
  double min_normal_impulse = 0.0;   ///< smallest normal (corner) impulse, N s
  double energy_after_j = 0.0;
};

struct StackImpact {
  StackImpactOutcome chosen;
  bool admissible = true;  ///< false: no outcome passed both checks (see note)
  bool settled = false;    ///< the rest rule closed an interface
  int candidates_tried = 0;
  /// Different motions among the admissible outcomes found, each after the rest rule (two that
  /// leave the same rates are one). More than one: the impact is ambiguous, the model does not
  /// say which follows; the first in the order is chosen and the note says so.
  int admissible_outcomes = 0;
  /// True when the search went through every candidate after the first admissible one
  /// (StackContacts::set_exhaustive and within kMaxCandidates).
  bool uniqueness_checked = false;
  double energy_before_j = 0.0;
  std::string note;  ///< empty unless something needs saying (no commas)
};

/// The contact problem of one stack: its chain and the buffers the searches use. Every call
/// allocates nothing after construction, except an impact's outcome (its rates).
class StackContacts {
 public:
  /// Most candidate configurations one search evaluates (3^10: every combination of ten
  /// closed interfaces); beyond it the search reports that it stopped.
  static constexpr int kMaxCandidates = 59049;

  explicit StackContacts(StackGeometry geometry);

  StackChain& chain() { return chain_; }
  const StackGeometry& geometry() const { return chain_.geometry(); }
  int size() const { return chain_.size(); }

  /// The accelerations of configuration c at (theta, omega) under (xg'', yg''), into theta_dd,
  /// and its margins; loads() then holds every interface's load.
  StackMargins Evaluate(const Configuration& c, const double* theta_rad, const double* omega_radps,
                        double xg_mps2, double yg_mps2, double* theta_dd);
  /// The margins of the loads already in loads() (after Evaluate, or after the chain's own
  /// Accelerations with loads()).
  StackMargins MarginsOfLoads(const Configuration& c) const;
  /// The loads of the last Evaluate, one per interface.
  const std::vector<InterfaceLoad>& loads() const { return loads_; }
  std::vector<InterfaceLoad>& loads() { return loads_; }

  /// Whether interface k is closed in the state: zero relative angle and rate (exactly).
  static bool Closed(const double* theta_rad, const double* omega_radps, int k);
  /// Whether c is consistent with the state (see the header's comment).
  bool Consistent(const Configuration& c, const double* theta_rad, const double* omega_radps,
                  double xg_mps2, double yg_mps2);
  /// The consistent configuration of the state: its open interfaces keep their side; the
  /// closed ones stay closed or open, in the order of the header's comment.
  StackSelection Select(const double* theta_rad, const double* omega_radps, double xg_mps2,
                        double yg_mps2);

  /// The rest rule's rate at interface k, rad/s: rest_rate_rel sqrt(g / R_k), R_k the distance
  /// from block k's base corner to the mass centre of the blocks from k up, at rest (for two
  /// blocks: the stack's R at the ground, block 2's r at the interface, as impact.h RestRate).
  double RestRate(int k, double rest_rate_rel) const;
  /// R_k of RestRate, m.
  double rest_radius_m(int k) const { return rest_radius_[k]; }

  /// Resolves an impact at interface k (its relative angle exactly zero) of a stack moving in
  /// `before` at (theta, omega_minus). Candidates: interface k rocks on its other corner or
  /// closes; every interface closed in `before` stays closed or opens; the open ones keep their
  /// side. Tried in the order: fewest changes from "k rebounds, the rest as before" first. The
  /// first admissible one is chosen; if none is, the first admissible in velocities (admissible
  /// = false); if none is even that, the one with the fewest open interfaces. Then the rest
  /// rule: an interface that opens from a zero gap slower than RestRate stays closed. With
  /// set_exhaustive(true), the search goes on after the first admissible outcome and counts the
  /// different admissible motions (StackImpact::admissible_outcomes; the note says when there
  /// are several). The choice is the same either way.
  StackImpact ResolveImpact(const Configuration& before, const double* theta_rad,
                            const double* omega_minus, int k, double rest_rate_rel);
  /// Whether ResolveImpact evaluates every candidate (tests of uniqueness; up to 15 times the
  /// cost of an impact on a six-drum column) or stops at the first admissible one (default).
  void set_exhaustive(bool exhaustive) { exhaustive_ = exhaustive; }

 private:
  struct ImpactSearch;  // one impact's search over candidates (stack_contacts.cc)

  // The rest rule applied to outcome o at theta: an interface that opens from a zero gap
  // slower than RestRate stays closed.
  Configuration Settled(const StackImpactOutcome& o, const double* theta_rad,
                        double rest_rate_rel) const;
  StackImpactOutcome EvaluateImpact(const Configuration& before, const Configuration& after,
                                    const double* theta_rad, const double* omega_minus);

  StackChain chain_;
  double weight_n_ = 0.0;
  std::vector<double> rest_radius_;  // R_k of RestRate
  std::vector<InterfaceLoad> loads_;
  std::vector<double> acc_, omega_;
  std::vector<int> free_;  // the interfaces a search may change
  bool exhaustive_ = false;
};

}  // namespace rockbench::reference
