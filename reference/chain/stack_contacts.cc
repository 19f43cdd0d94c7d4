#include "reference/chain/stack_contacts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <utility>

#include "reference/thesis/impact.h"

namespace rockbench::reference {
namespace {

double SideSign(Contact c) {
  return c == Contact::kLeft ? -1.0 : 1.0;
}

Contact Other(Contact c) {
  return c == Contact::kRight ? Contact::kLeft : Contact::kRight;
}

// The relative angle and rate of interface k (block k on its support; the ground's are zero).
double RelativeAngle(const double* theta, int k) {
  return k == 0 ? theta[0] : theta[k] - theta[k - 1];
}
double RelativeRate(const double* omega, int k) {
  return k == 0 ? omega[0] : omega[k] - omega[k - 1];
}

}  // namespace

StackContacts::StackContacts(StackGeometry geometry) : chain_(std::move(geometry)) {
  const StackGeometry& geo = chain_.geometry();
  const int n = geo.size();
  double mass = 0.0;
  for (const BlockProps& p : geo.blocks) mass += p.m;
  weight_n_ = mass * geo.g;
  // R_k: block k's base corner to the mass centre of the blocks from k up, at rest.
  rest_radius_ = RestRadii_m(n, [&](int k) {
    const BlockProps& p = geo.blocks[k];
    return std::array<double, 3>{p.b, p.h, p.m};
  });
  loads_.assign(n, InterfaceLoad{});
  acc_.assign(n, 0.0);
  omega_.assign(n, 0.0);
  free_.reserve(n);
}

StackMargins StackContacts::MarginsOfLoads(const Configuration& c) const {
  // The smallest over the faces and over the pivots; 1 for a kind the configuration lacks.
  double face = INFINITY, point = INFINITY;
  for (int k = 0; k < size(); ++k) {
    const InterfaceLoad& L = loads_[k];
    if (c[k] == Contact::kFace) {
      face = std::min(face, std::min(L.left_n, L.right_n) / weight_n_);
    } else {
      point = std::min(point, L.normal_n / weight_n_);
    }
  }
  return {face == INFINITY ? 1.0 : face, point == INFINITY ? 1.0 : point};
}

StackMargins StackContacts::Evaluate(const Configuration& c, const double* theta,
                                     const double* omega, double xg, double yg, double* theta_dd) {
  chain_.Place(c, theta, omega);
  chain_.Accelerations(xg, yg, theta_dd, loads_.data());
  return MarginsOfLoads(c);
}

bool StackContacts::Closed(const double* theta, const double* omega, int k) {
  return k == 0 ? theta[0] == 0.0 && omega[0] == 0.0
                : theta[k] == theta[k - 1] && omega[k] == omega[k - 1];
}

bool StackContacts::Consistent(const Configuration& c, const double* theta, const double* omega,
                               double xg, double yg) {
  const StackMargins m = Evaluate(c, theta, omega, xg, yg, acc_.data());
  // An interface that opens from closed must accelerate open.
  for (int k = 0; k < size(); ++k) {
    if (c[k] == Contact::kFace || !Closed(theta, omega, k)) continue;
    if (!(SideSign(c[k]) * RelativeAngle(acc_.data(), k) > 0.0)) return false;
  }
  return m.face >= 0.0 && m.point >= 0.0;
}

StackSelection StackContacts::Select(const double* theta, const double* omega, double xg,
                                     double yg) {
  const int n = size();
  Configuration c(n);
  free_.clear();
  for (int k = 0; k < n; ++k) {
    if (Closed(theta, omega, k)) {
      free_.push_back(k);
      continue;
    }
    // An open interface keeps the side of its gap, or of its rate when the gap is zero.
    const double gap = RelativeAngle(theta, k);
    const double v = gap != 0.0 ? gap : RelativeRate(omega, k);
    c.set(k, v > 0.0 ? Contact::kRight : Contact::kLeft);
  }
  const int nfree = static_cast<int>(free_.size());
  int tried = 0;
  bool capped = false;
  // Depth-first over the free interfaces with `open` of them still to open: right, left, then
  // closed, from the bottom.
  std::function<bool(int, int)> search = [&](int pos, int open) -> bool {
    if (pos == nfree) {
      if (open != 0) return false;
      if (++tried > kMaxCandidates) {
        capped = true;
        return false;
      }
      return Consistent(c, theta, omega, xg, yg);
    }
    const int k = free_[pos];
    if (open > 0) {
      for (const Contact side : {Contact::kRight, Contact::kLeft}) {
        c.set(k, side);
        if (search(pos + 1, open - 1) || capped) return !capped;
      }
    }
    if (nfree - pos > open) {
      c.set(k, Contact::kFace);
      if (search(pos + 1, open) || capped) return !capped;
    }
    return false;
  };
  for (int open = 0; open <= nfree; ++open) {
    if (search(0, open)) return {c, true, false};
    if (capped) break;
  }
  return {Configuration(n), false, capped};
}

double StackContacts::RestRate(int k, double rest_rate_rel) const {
  return rest_rate_rel * std::sqrt(geometry().g / rest_radius_[k]);
}

StackImpactOutcome StackContacts::EvaluateImpact(const Configuration& before,
                                                 const Configuration& after, const double* theta,
                                                 const double* omega_minus) {
  const int n = size();
  StackImpactOutcome out;
  out.config = after;
  out.omega_radps.assign(n, 0.0);
  chain_.Place(before, theta, omega_minus);
  double p_scale = 1e-300, rate_scale = 1e-300;
  for (int i = 0; i < n; ++i) {
    const BodyMotion b = chain_.Body(i);
    p_scale += geometry().blocks[i].m * std::hypot(b.vG.x, b.vG.y);
    rate_scale += std::abs(omega_minus[i]);
  }
  chain_.ImpactRates(after, out.omega_radps.data(), loads_.data());
  const double* w = out.omega_radps.data();
  // Velocities: an interface that opens from a zero gap must open, not close.
  bool ok = true;
  for (int k = 0; k < n && ok; ++k) {
    if (after[k] == Contact::kFace || RelativeAngle(theta, k) != 0.0) continue;
    ok = SideSign(after[k]) * RelativeRate(w, k) >= -1e-12 * rate_scale;
  }
  out.velocity_admissible = ok;
  // Impulses: every contact of `after` pushes.
  double min_imp = INFINITY;
  for (int k = 0; k < n; ++k) {
    const InterfaceLoad& L = loads_[k];
    min_imp =
        std::min(min_imp, after[k] == Contact::kFace ? std::min(L.left_n, L.right_n) : L.normal_n);
  }
  out.min_normal_impulse = min_imp;
  out.impulse_admissible = min_imp >= -1e-9 * p_scale;
  out.energy_after_j = chain_.Energy();
  return out;
}

Configuration StackContacts::Settled(const StackImpactOutcome& o, const double* theta,
                                     double rest_rate_rel) const {
  const int n = size();
  Configuration settled = o.config;
  for (int k = 0; k < n; ++k) {
    if (settled[k] == Contact::kFace || RelativeAngle(theta, k) != 0.0) continue;
    if (std::abs(RelativeRate(o.omega_radps.data(), k)) < RestRate(k, rest_rate_rel)) {
      settled.set(k, Contact::kFace);
    }
  }
  return settled;
}

/// One impact's search over the candidate configurations (ResolveImpact): the candidates in
/// its order, what it has found so far (the pick, the first admissible in velocities, the
/// fallback) and, when exhaustive, the different admissible motions.
struct StackContacts::ImpactSearch {
  StackContacts& contacts;
  const Configuration& before;
  const double* theta;
  const double* omega_minus;
  int k_impact;
  double rest_rate_rel;
  StackImpact& res;
  int n = 0;
  // The baseline: the landing interface rebounds onto its other corner, the rest as before.
  Configuration base;
  Contact rebound = Contact::kRight;
  int nfree = 0;
  Configuration c;  // the candidate being built
  bool capped = false;
  bool have_pick = false, have_velocity = false, have_fallback = false;
  StackImpactOutcome pick, first_velocity, fallback;
  // The different motions (rates after the rest rule) of the admissible outcomes found, when
  // the search is exhaustive, and their configurations' names.
  double rate_scale = 1e-300;
  std::vector<std::vector<double>> motions;
  std::string names;

  ImpactSearch(StackContacts& owner, const Configuration& before_mode, const double* theta_rad,
               const double* omega, int k, double rest_rel, StackImpact& result)
      : contacts(owner),
        before(before_mode),
        theta(theta_rad),
        omega_minus(omega),
        k_impact(k),
        rest_rate_rel(rest_rel),
        res(result),
        n(owner.size()) {
    base = before;
    rebound = Other(before[k_impact]);
    base.set(k_impact, rebound);
    contacts.free_.clear();
    for (int j = 0; j < n; ++j) {
      if (j == k_impact || before[j] == Contact::kFace) contacts.free_.push_back(j);
    }
    nfree = static_cast<int>(contacts.free_.size());
    for (int i = 0; i < n; ++i) rate_scale += std::abs(omega_minus[i]);
    c = base;
  }

  // Each free interface's other options: the landing one closes; a closed one opens, on the
  // rebound's side first.
  int Changes(int k, Contact* opts) const {
    if (k == k_impact) {
      opts[0] = Contact::kFace;
      return 1;
    }
    opts[0] = rebound;
    opts[1] = Other(rebound);
    return 2;
  }

  // Counts the motion of an admissible outcome (after the rest rule) unless one found already
  // leaves the same rates.
  void AddMotion(const StackImpactOutcome& o) {
    const Configuration s = contacts.Settled(o, theta, rest_rate_rel);
    const std::vector<double> w =
        s == o.config ? o.omega_radps
                      : contacts.EvaluateImpact(before, s, theta, omega_minus).omega_radps;
    for (const auto& m : motions) {
      if (SameImpactMotion(m.data(), w.data(), n, rate_scale)) return;
    }
    motions.push_back(w);
    if (!names.empty()) names += ' ';
    names += ConfigurationName(o.config);
  }

  // Evaluates the complete candidate c. Returns true to stop: the search's cap without an
  // admissible outcome, or the uniqueness check's budget after one.
  bool TryCandidate() {
    if (++res.candidates_tried > kMaxCandidates) {
      // Without an outcome the search is capped; with one, its uniqueness check stops.
      if (have_pick) {
        res.uniqueness_checked = false;
      } else {
        capped = true;
      }
      return true;
    }
    StackImpactOutcome o = contacts.EvaluateImpact(before, c, theta, omega_minus);
    if (o.velocity_admissible && o.impulse_admissible) {
      if (contacts.exhaustive_) AddMotion(o);
      if (!have_pick) {
        pick = std::move(o);
        have_pick = true;
        // At most one motion is admissible (StackContacts::set_exhaustive).
        res.uniqueness_checked = contacts.exhaustive_;
        return !contacts.exhaustive_;
      }
      return false;
    }
    if (have_pick) return false;
    if (o.velocity_admissible && !have_velocity) {
      first_velocity = o;
      have_velocity = true;
    }
    // Nothing separates: the fewest open interfaces (the last such in the order).
    if (!have_fallback || o.config.open_count() <= fallback.config.open_count()) {
      fallback = std::move(o);
      have_fallback = true;
    }
    return false;
  }

  // The candidates that change `left` more of the free interfaces from pos on. Returns true to
  // stop (TryCandidate).
  bool Search(int pos, int left) {
    if (pos == nfree) {
      if (left != 0) return false;
      return TryCandidate();
    }
    const int k = contacts.free_[pos];
    if (left > 0) {
      Contact opts[2];
      const int m = Changes(k, opts);
      for (int i = 0; i < m; ++i) {
        c.set(k, opts[i]);
        if (Search(pos + 1, left - 1)) return true;
      }
    }
    if (nfree - pos > left) {
      c.set(k, base[k]);
      if (Search(pos + 1, left)) return true;
    }
    return false;
  }

  // Fewest changes from the baseline first.
  void Run() {
    for (int d = 0; d <= nfree; ++d) {
      if (Search(0, d)) break;
    }
  }

  // What the search needs said: no admissible outcome, several, or a uniqueness check cut
  // short. Sets res.admissible_outcomes and res.admissible, and the pick when none was found.
  std::string Note() {
    std::string note;
    res.admissible_outcomes = contacts.exhaustive_ ? static_cast<int>(motions.size())
                              : have_pick          ? 1
                                                   : 0;
    if (!have_pick) {
      res.admissible = false;
      note = capped ? "inadmissible: no admissible outcome among the first " +
                          std::to_string(kMaxCandidates) + " (search stopped)"
                    : "inadmissible: no outcome both separates and pushes";
      pick = have_velocity ? first_velocity : fallback;
    } else if (motions.size() > 1) {
      note = "ambiguous: " + std::to_string(motions.size()) + " admissible outcomes (" + names +
             "); chose " + ConfigurationName(pick.config);
    }
    if (contacts.exhaustive_ && have_pick && !res.uniqueness_checked) {
      note += std::string(note.empty() ? "" : "; ") + "uniqueness checked on the first " +
              std::to_string(kMaxCandidates) + " candidates only";
    }
    return note;
  }
};

StackImpact StackContacts::ResolveImpact(const Configuration& before, const double* theta,
                                         const double* omega_minus, int k_impact,
                                         double rest_rate_rel) {
  StackImpact res;
  chain_.Place(before, theta, omega_minus);
  res.energy_before_j = chain_.Energy();
  ImpactSearch search(*this, before, theta, omega_minus, k_impact, rest_rate_rel, res);
  search.Run();
  std::string note = search.Note();
  res.chosen = std::move(search.pick);
  // The rest rule: an interface that opens from a zero gap too slowly stays closed.
  const Configuration settled = Settled(res.chosen, theta, rest_rate_rel);
  if (settled != res.chosen.config) {
    res.settled = true;
    res.chosen = EvaluateImpact(before, settled, theta, omega_minus);
    note += note.empty() ? "settled (rest rule)" : " settled (rest rule)";
  }
  res.note = std::move(note);
  return res;
}

}  // namespace rockbench::reference
