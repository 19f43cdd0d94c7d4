#include "reference/thesis/transitions.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "reference/thesis/modes.h"
#include "reference/thesis/observables.h"

namespace rockbench::reference {

namespace {

ContactMargins MarginsOf(const Geometry& geo, Mode mode, const ContactDemand& demand) {
  ContactMargins cm;
  cm.reactions = demand.reactions;
  cm.mu_ground = demand.mu_ground;
  cm.mu_interface = demand.mu_interface;
  const Reactions& r = cm.reactions;
  const double W = geo.M * geo.g;
  const Contacts c = ContactsOf(mode);
  if (c.ground == Contact::kFace) {
    cm.face = std::min(r.ground_left, r.ground_right) / W;
  } else {
    cm.point = r.N_ground / W;
  }
  if (geo.two_blocks) {
    if (c.interface == Contact::kFace) {
      cm.face = std::min(cm.face, std::min(r.interface_left, r.interface_right) / W);
    } else {
      cm.point = std::min(cm.point, r.N_interface / W);
    }
  }
  return cm;
}

}  // namespace

ContactMargins EvaluateContacts(const Geometry& geo, Mode mode, const State& s, double xg,
                                double yg, Equations equations) {
  return MarginsOf(geo, mode, ContactReactions(geo, mode, s, xg, yg, equations));
}

ContactMargins EvaluateContacts(const Geometry& geo, Mode mode, const State& s,
                                const std::array<double, 2>& acc, double xg, double yg) {
  return EvaluateContacts(geo, mode, s, TiltsOf(s), acc, xg, yg);
}

ContactMargins EvaluateContacts(const Geometry& geo, Mode mode, const State& s, const Tilts& tilts,
                                const std::array<double, 2>& acc, double xg, double yg) {
  return MarginsOf(geo, mode, ContactReactions(geo, mode, s, tilts, acc, xg, yg));
}

ModeSelection SelectMode(const Geometry& geo, const State& s, double xg, double yg,
                         Equations equations) {
  const bool ground_closed = s.theta1 == 0.0 && s.omega1 == 0.0;
  const bool interface_closed = s.theta2 == s.theta1 && s.omega2 == s.omega1;
  auto side = [](double gap, double rate) {
    const double v = gap != 0.0 ? gap : rate;
    return v > 0 ? Contact::kRight : Contact::kLeft;
  };
  // The options of each contact (at most three each, so no allocation).
  constexpr std::array<Contact, 3> kAll = {Contact::kFace, Contact::kRight, Contact::kLeft};
  std::array<Contact, 3> g_opts = kAll, i_opts = kAll;
  int n_g = 3, n_i = 3;
  if (!ground_closed) {
    g_opts[0] = side(s.theta1, s.omega1);
    n_g = 1;
  }
  if (!geo.two_blocks) {
    i_opts[0] = Contact::kFace;
    n_i = 1;
  } else if (!interface_closed) {
    i_opts[0] = side(s.theta2 - s.theta1, s.omega2 - s.omega1);
    n_i = 1;
  }
  // Candidates ordered by the number of contacts that open (the blocks do not start to move
  // unless they must); among equals, the ground opening first (the thesis checks 4.1 before 4.3).
  struct Candidate {
    Contact gc, ic;
    int opening;
  };
  std::array<Candidate, 9> cands;
  int n = 0;
  for (int a = 0; a < n_g; ++a) {
    for (int b = 0; b < n_i; ++b) {
      const Contact gc = g_opts[a], ic = i_opts[b];
      const int opening = (ground_closed && gc != Contact::kFace) +
                          (geo.two_blocks && interface_closed && ic != Contact::kFace);
      cands[n++] = {gc, ic, opening};
    }
  }
  // Stable insertion sort (std::stable_sort would allocate a buffer at every call).
  auto before = [](const Candidate& a, const Candidate& b) {
    if (a.opening != b.opening) return a.opening < b.opening;
    return (a.gc != Contact::kFace) > (b.gc != Contact::kFace);
  };
  for (int k = 1; k < n; ++k) {
    const Candidate c = cands[k];
    int j = k;
    for (; j > 0 && before(c, cands[j - 1]); --j) cands[j] = cands[j - 1];
    cands[j] = c;
  }
  for (int k = 0; k < n; ++k) {
    const Candidate& cand = cands[k];
    const Mode mode = ModeOf({cand.gc, cand.ic}, geo.two_blocks);
    if (ModeConsistent(geo, mode, s, xg, yg, equations)) return {mode, true};
  }
  return {Mode::kRest, false};
}

bool ModeConsistent(const Geometry& geo, Mode mode, const State& s, double xg, double yg,
                    Equations equations) {
  const bool ground_closed = s.theta1 == 0.0 && s.omega1 == 0.0;
  const bool interface_closed = s.theta2 == s.theta1 && s.omega2 == s.omega1;
  const Contacts c = ContactsOf(mode);
  const auto acc = ModeAccelerations(geo, mode, s, xg, yg, equations);
  // An opening contact must open: its gap must accelerate away from zero.
  if (ground_closed && c.ground != Contact::kFace) {
    if (!((c.ground == Contact::kRight ? acc[0] : -acc[0]) > 0.0)) return false;
  }
  if (geo.two_blocks && interface_closed && c.interface != Contact::kFace) {
    const double rel = acc[1] - acc[0];
    if (!((c.interface == Contact::kRight ? rel : -rel) > 0.0)) return false;
  }
  const ContactMargins cm = EvaluateContacts(geo, mode, s, acc, xg, yg);
  return cm.face >= 0.0 && cm.point >= 0.0;
}

Mode ThesisInitiation(const Geometry& geo, double xg, double yg) {
  const double g = geo.g;
  const double b1 = geo.block1.b, h = geo.h_stack;
  if (-h * xg - b1 * yg > b1 * g) return Mode::k3a;  // (4.1)
  if (h * xg - b1 * yg > b1 * g) return Mode::k3b;   // (4.2)
  if (geo.two_blocks) {
    const double b2 = geo.block2.b, h2 = geo.block2.h;
    if (-h2 * xg - b2 * yg > b2 * g) return Mode::k4a;  // (4.3)
    if (h2 * xg - b2 * yg > b2 * g) return Mode::k4b;   // (4.4), the mirror of 4.3
  }
  return Mode::kRest;
}

}  // namespace rockbench::reference
