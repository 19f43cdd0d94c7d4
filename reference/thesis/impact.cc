#include "reference/thesis/impact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "reference/thesis/observables.h"

namespace rockbench::reference {
namespace {

// Generalized rates of a mode -> full state rates.
State WithRates(const State& s, Mode mode, double u0, double u1) {
  State out = s;
  const Contacts c = ContactsOf(mode);
  const bool g = c.ground != Contact::kFace, i = c.interface != Contact::kFace;
  if (g && i) {
    out.omega1 = u0;
    out.omega2 = u1;
  } else if (g) {
    out.omega1 = out.omega2 = u0;
  } else if (i) {
    out.omega1 = 0.0;
    out.omega2 = u0;
  } else {
    out.omega1 = out.omega2 = 0.0;
  }
  return out;
}

}  // namespace

std::vector<Mode> ImpactCandidates(Mode before, ImpactKind kind, bool two_blocks) {
  if (!two_blocks) {
    // Housner: the block rocks on about the other corner, or stops.
    return {before == Mode::k3a ? Mode::k3b : Mode::k3a, Mode::kRest};
  }
  const Contacts c = ContactsOf(before);
  std::vector<Contacts> list;
  if (kind == ImpactKind::kGround) {
    const Contact other = c.ground == Contact::kRight ? Contact::kLeft : Contact::kRight;
    if (c.interface == Contact::kFace) {
      // Thesis 5.27-5.31: 3a -> 1b, else 3b.
      list = {{other, other},          {other, Contact::kFace},
              {other, c.ground},       {Contact::kFace, Contact::kFace},
              {Contact::kFace, other}, {Contact::kFace, c.ground}};
    } else {
      // Thesis 5.12-5.14, 5.20-5.22: the ground pivot switches, block 2 keeps its pivot.
      list = {{other, c.interface}, {Contact::kFace, c.interface}};
    }
  } else {
    const Contact other = c.interface == Contact::kRight ? Contact::kLeft : Contact::kRight;
    if (c.ground == Contact::kFace) {
      // Thesis 5.32-5.36: 4a -> 1b, else 4b.
      list = {{other, other},          {Contact::kFace, other}, {Contact::kFace, Contact::kFace},
              {other, Contact::kFace}, {c.interface, other},    {c.interface, Contact::kFace}};
    } else {
      // Thesis 5.15-5.19, 5.23-5.26: 1a -> 2a, else 3a; 2a -> 1a, else 3a.
      list = {{c.ground, other}, {c.ground, Contact::kFace}};
    }
  }
  std::vector<Mode> modes;
  for (const Contacts& k : list) modes.push_back(ModeOf(k, true));
  return modes;
}

namespace {

// The rates after the impact from the mass-centre and angular velocities v before it, with the
// state's tilts (an impact changes rates, not angles).
State PostImpactState(const Geometry& geo, const BodyVelocities& v, const State& pre,
                      const Tilts& tilts, Mode after) {
  const Chain ch = EvaluateChain(geo, after, pre, tilts);
  const double m[2] = {geo.block1.m, geo.block2.m};
  const double IG[2] = {geo.block1.I_G, geo.block2.I_G};
  double M[2][2] = {{0, 0}, {0, 0}}, p[2] = {0, 0};
  for (int b = 0; b < (geo.two_blocks ? 2 : 1); ++b) {
    for (int i = 0; i < ch.ndof; ++i) {
      p[i] += m[b] * Dot(ch.JG[b][i], v.vG[b]) + IG[b] * ch.Jphi[b][i] * v.w[b];
      for (int j = 0; j < ch.ndof; ++j) {
        M[i][j] += m[b] * Dot(ch.JG[b][i], ch.JG[b][j]) + IG[b] * ch.Jphi[b][i] * ch.Jphi[b][j];
      }
    }
  }
  double u0 = 0.0, u1 = 0.0;
  if (ch.ndof == 1) {
    u0 = p[0] / M[0][0];
  } else if (ch.ndof == 2) {
    const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    u0 = (p[0] * M[1][1] - M[0][1] * p[1]) / det;
    u1 = (M[0][0] * p[1] - M[1][0] * p[0]) / det;
  }
  return WithRates(pre, after, u0, u1);
}

}  // namespace

State PostImpactState(const Geometry& geo, Mode before, const State& pre, Mode after) {
  const Tilts tilts = TiltsOf(pre);
  return PostImpactState(geo, Velocities(EvaluateChain(geo, before, pre, tilts)), pre, tilts,
                         after);
}

namespace {

// One candidate outcome, from the tilts of the impact state and the velocities vm before it.
ImpactOutcome Evaluate(const Geometry& geo, const State& pre, const Tilts& tilts,
                       const BodyVelocities& vm, Mode after) {
  ImpactOutcome out;
  out.mode = after;
  out.state = PostImpactState(geo, vm, pre, tilts, after);
  const Contacts c = ContactsOf(after);
  // Velocity check: a contact that opens from a closed gap must open, not close.
  const double rate_scale = std::abs(pre.omega1) + std::abs(pre.omega2) + 1e-300;
  const double vtol = 1e-12 * rate_scale;
  bool ok = true;
  if (c.ground != Contact::kFace && pre.theta1 == 0.0) {
    const double sgn = c.ground == Contact::kRight ? 1.0 : -1.0;
    ok = ok && sgn * out.state.omega1 >= -vtol;
  }
  if (geo.two_blocks && c.interface != Contact::kFace && pre.theta2 == pre.theta1) {
    const double sgn = c.interface == Contact::kRight ? 1.0 : -1.0;
    ok = ok && sgn * (out.state.omega2 - out.state.omega1) >= -vtol;
  }
  out.velocity_admissible = ok;
  // Impulse check: velocity jumps give the impulses; normal components must push.
  const Chain after_chain = EvaluateChain(geo, after, out.state, tilts);
  const BodyVelocities vp = Velocities(after_chain);
  std::array<Vec2, 2> dv{vp.vG[0] - vm.vG[0], vp.vG[1] - vm.vG[1]};
  std::array<double, 2> dw{vp.w[0] - vm.w[0], vp.w[1] - vm.w[1]};
  const Reactions imp = ContactLoads(geo, after, tilts, dv, dw, Vec2{});
  double min_imp =
      c.ground == Contact::kFace ? std::min(imp.ground_left, imp.ground_right) : imp.N_ground;
  if (geo.two_blocks) {
    min_imp = std::min(min_imp, c.interface == Contact::kFace
                                    ? std::min(imp.interface_left, imp.interface_right)
                                    : imp.N_interface);
  }
  out.min_normal_impulse = min_imp;
  // Impulse scale: the momentum of the system before the impact.
  const double pscale = geo.block1.m * std::hypot(vm.vG[0].x, vm.vG[0].y) +
                        geo.block2.m * std::hypot(vm.vG[1].x, vm.vG[1].y) + 1e-300;
  out.impulse_admissible = min_imp >= -1e-9 * pscale;
  out.energy_after_j = StateEnergy(geo, after_chain).total_j;
  return out;
}

// The mode with the contacts that would open too slowly kept closed.
Mode Settle(const Geometry& geo, Mode mode, const State& pre, const State& post,
            double rest_rate_rel) {
  Contacts c = ContactsOf(mode);
  if (c.ground != Contact::kFace && pre.theta1 == 0.0 &&
      std::abs(post.omega1) < RestRate(geo, ImpactKind::kGround, rest_rate_rel)) {
    c.ground = Contact::kFace;
  }
  if (geo.two_blocks && c.interface != Contact::kFace && pre.theta2 == pre.theta1 &&
      std::abs(post.omega2 - post.omega1) < RestRate(geo, ImpactKind::kInterface, rest_rate_rel)) {
    c.interface = Contact::kFace;
  }
  return ModeOf(c, geo.two_blocks);
}

}  // namespace

double RestRate(const Geometry& geo, ImpactKind contact, double rest_rate_rel) {
  const double R = contact == ImpactKind::kInterface && geo.two_blocks ? geo.block2.r : geo.R;
  return rest_rate_rel * std::sqrt(geo.g / R);
}

ImpactResult ResolveImpact(const Geometry& geo, Mode before, const State& pre, ImpactKind kind,
                           double rest_rate_rel) {
  ImpactResult res;
  // An impact changes rates, not angles: one set of tilts serves every candidate.
  const Tilts tilts = TiltsOf(pre);
  const Chain before_chain = EvaluateChain(geo, before, pre, tilts);
  const BodyVelocities vm = Velocities(before_chain);
  res.energy_before_j = StateEnergy(geo, before_chain).total_j;
  const std::vector<Mode> modes = ImpactCandidates(before, kind, geo.two_blocks);
  res.candidates.reserve(modes.size() + 1);
  for (Mode m : modes) res.candidates.push_back(Evaluate(geo, pre, tilts, vm, m));
  const ImpactOutcome* pick = nullptr;
  for (const auto& c : res.candidates) {
    if (c.velocity_admissible && c.impulse_admissible) {
      pick = &c;
      break;
    }
  }
  // The note is built only when there is something to say (most impacts have none).
  std::string note;
  if (pick) {
    // The different motions the admissible candidates leave, each after the rest rule (most
    // impacts have one admissible candidate: nothing to compare).
    int admissible = 0;
    for (const auto& c : res.candidates)
      admissible += c.velocity_admissible && c.impulse_admissible;
    res.admissible_outcomes = admissible;
    if (admissible > 1) {
      const double rate_scale = std::abs(pre.omega1) + std::abs(pre.omega2) + 1e-300;
      // (At most one candidate per mode: nine.)
      std::array<std::array<double, 2>, 9> motions;
      std::array<Mode, 9> modes;
      size_t count = 0;
      for (const auto& c : res.candidates) {
        if (!c.velocity_admissible || !c.impulse_admissible) continue;
        const Mode m = Settle(geo, c.mode, pre, c.state, rest_rate_rel);
        const State after = m == c.mode ? c.state : Evaluate(geo, pre, tilts, vm, m).state;
        const std::array<double, 2> w{after.omega1, after.omega2};
        bool same = false;
        for (size_t i = 0; i < count && !same; ++i) {
          same = SameImpactMotion(motions[i].data(), w.data(), 2, rate_scale);
        }
        if (same || count == motions.size()) continue;
        modes[count] = c.mode;
        motions[count++] = w;
      }
      res.admissible_outcomes = static_cast<int>(count);
      if (count > 1) {
        std::string names;
        for (size_t i = 0; i < count; ++i) {
          if (i > 0) names += ' ';
          names += ModeName(modes[i]);
        }
        note = "ambiguous: " + std::to_string(count) + " admissible outcomes (" + names +
               "); chose " + std::string(ModeName(pick->mode));
      }
    }
  }
  if (!pick) {
    res.admissible = false;
    for (const auto& c : res.candidates) {
      if (c.velocity_admissible) {
        pick = &c;
        break;
      }
    }
    note = "inadmissible: no outcome both separates and pushes;";
    for (const auto& c : res.candidates) {
      note += " ";
      note += ModeName(c.mode);
      if (!c.velocity_admissible) note += " moves-into";
      if (!c.impulse_admissible) note += " pulls";
    }
  }
  if (!pick) {
    // Nothing separates: the impacting contact closes fully (the blocks stop relative motion).
    pick = &res.candidates.back();
    for (const auto& c : res.candidates) {
      if (DofCount(c.mode, geo.two_blocks) < DofCount(pick->mode, geo.two_blocks)) pick = &c;
    }
  }
  res.chosen = *pick;
  // Rest rule: a contact that would open with a rate below its RestRate stays closed.
  const Mode settled = Settle(geo, res.chosen.mode, pre, res.chosen.state, rest_rate_rel);
  if (settled != res.chosen.mode) {
    res.settled = true;
    res.chosen = Evaluate(geo, pre, tilts, vm, settled);
    note += note.empty() ? "settled (rest rule)" : " settled (rest rule)";
  }
  res.note = std::move(note);
  return res;
}

}  // namespace rockbench::reference
