#include "report/sweep/sweep_analysis.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "run/engine_registry.h"
#include "scene/body_kind.h"
#include "util/format.h"

namespace rockbench::report {

bool ReachesPeakAgreement(const SweepRecord& r, double peak_tolerance) {
  return r.failure.empty() && MaxPeakRelError(r) <= peak_tolerance && r.overturn_agree;
}

std::vector<std::pair<std::string, std::vector<size_t>>> SweepFamilies(
    const std::vector<SweepRecord>& rows) {
  // Families in the order they first appear among the engines' rows (each engine's own grid
  // order), then reference dopri5, dop853 and RK4; within a family from the coarsest setting.
  std::map<std::string, size_t> first;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (!IsReference(rows[i].engine)) first.emplace(SweepFamily(rows[i]), first.size());
  }
  auto rank = [&](const SweepRecord& r) -> size_t {
    if (!IsReference(r.engine)) return first.at(SweepFamily(r));
    return first.size() + (r.integrator == "dopri5" ? 0 : r.integrator == "dop853" ? 1 : 2);
  };
  std::vector<size_t> order;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].failure.empty()) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const SweepRecord& x = rows[a];
    const SweepRecord& y = rows[b];
    if (rank(x) != rank(y)) return rank(x) < rank(y);
    return SweepSettingValue(x) > SweepSettingValue(y);
  });
  std::vector<std::pair<std::string, std::vector<size_t>>> out;
  for (size_t i : order) {
    const std::string f = SweepFamily(rows[i]);
    if (out.empty() || out.back().first != f) out.push_back({f, {}});
    out.back().second.push_back(i);
  }
  return out;
}

std::optional<double> ObservedOrder(const SweepRecord& coarse, const SweepRecord& fine) {
  const double ec = MaxAngleError(coarse), ef = MaxAngleError(fine);
  const double sc = SweepSettingValue(coarse), sf = SweepSettingValue(fine);
  if (!(ec > 0.0) || !(ef > 0.0) || !(sc > 0.0) || !(sf > 0.0) || sc == sf) return std::nullopt;
  return std::log(ec / ef) / std::log(sc / sf);
}

AgreementCriterion PeakAgreement(double tolerance, int blocks) {
  AgreementCriterion c;
  c.name = Format("%g", tolerance * 100.0) + "% peak-angle agreement";
  const std::string which = blocks >= 3
                                ? " for every block (theta1 to " + BodyColumn("theta", blocks) + ")"
                            : blocks == 2 ? std::string(" for theta1 and theta2")
                                          : std::string(" for theta1");
  c.definition = "|peak relative error| <= " + Format("%g", tolerance * 100.0) + "%" + which +
                 ", and the same overturn outcome as the reference";
  c.reaches = [tolerance](const SweepRecord& r) { return ReachesPeakAgreement(r, tolerance); };
  return c;
}

AgreementCriterion HistoryAgreement(double fraction, const std::vector<double>& peak_theta_rad) {
  AgreementCriterion c;
  // Each body's bound, none for a body after the first whose peak is 0 (one block's body 2 in
  // sweep.json, or a body that does not move: no scale to be within a fraction of).
  std::vector<std::optional<double>> bounds_rad;
  std::string bounds_text;
  for (size_t k = 0; k < peak_theta_rad.size(); ++k) {
    if (k > 0 && !(peak_theta_rad[k] > 0.0)) {
      bounds_rad.push_back(std::nullopt);
      continue;
    }
    bounds_rad.push_back(fraction * peak_theta_rad[k]);
    bounds_text += std::string(k > 0 ? ", " : "") + Format("%.3g", *bounds_rad.back()) +
                   " rad for " + BodyColumn("theta", static_cast<int>(k) + 1);
  }
  c.name = Format("%g", fraction * 100.0) + "% history agreement";
  c.definition = "max |angle error| over the whole run <= " + Format("%g", fraction * 100.0) +
                 "% of the reference's peak angle: " + bounds_text +
                 "; and the same overturn outcome";
  c.reaches = [bounds_rad](const SweepRecord& r) {
    if (!r.failure.empty() || !r.overturn_agree) return false;
    for (size_t k = 0; k < bounds_rad.size() && k < r.bodies.size(); ++k) {
      if (bounds_rad[k] && r.bodies[k].max_abs_error_rad > *bounds_rad[k]) return false;
    }
    return true;
  };
  return c;
}

CheapestSetting FindCheapestSetting(const std::vector<SweepRecord>& rows, double peak_tolerance,
                                    const std::string& engine) {
  // The stack's blocks: the most bodies a row has (0 when every row failed).
  int blocks = 0;
  for (const SweepRecord& r : rows) blocks = std::max(blocks, static_cast<int>(r.bodies.size()));
  return FindCheapestSetting(rows, PeakAgreement(peak_tolerance, blocks), engine);
}

std::vector<std::string> SweepEngines(const std::vector<SweepRecord>& rows) {
  std::vector<std::string> out;
  for (const SweepRecord& r : rows) {
    if (!IsReference(r.engine) && std::find(out.begin(), out.end(), r.engine) == out.end()) {
      out.push_back(r.engine);
    }
  }
  return out;
}

CheapestSetting FindCheapestSetting(const std::vector<SweepRecord>& rows,
                                    const AgreementCriterion& criterion,
                                    const std::string& engine_name) {
  CheapestSetting out;
  const std::vector<std::string> engines = SweepEngines(rows);
  out.engine = !engine_name.empty() ? engine_name : (engines.empty() ? "" : engines.front());
  const std::string& engine = out.engine;
  auto reaches = [&](const SweepRecord& r) { return r.failure.empty() && criterion.reaches(r); };
  for (size_t i = 0; i < rows.size(); ++i) {
    const SweepRecord& r = rows[i];
    if (r.engine != engine || !reaches(r)) continue;
    if (!out.engine_row || r.wall_s < rows[*out.engine_row].wall_s) out.engine_row = i;
  }
  if (!out.engine_row) {
    out.statement = "No " + (engine.empty() ? std::string("engine") : engine) +
                    " setting in this sweep reaches " + criterion.name + " (" +
                    criterion.definition + ").";
    // Say how close the sweep came: the smallest max angle error.
    std::optional<size_t> closest;
    for (size_t i = 0; i < rows.size(); ++i) {
      const SweepRecord& r = rows[i];
      if (r.engine != engine || !r.failure.empty()) continue;
      if (!closest || MaxAngleError(r) < MaxAngleError(rows[*closest])) closest = i;
    }
    if (closest) {
      const SweepRecord& c = rows[*closest];
      out.statement += " The most accurate is " + SweepSettingDescription(c) +
                       ": max angle error " + Format("%.2e", MaxAngleError(c)) +
                       " rad, |peak relative error| " + Format("%.3g", MaxPeakRelError(c) * 100.0) +
                       "%" + (c.overturn_agree ? "" : ", and its overturn outcome differs") + ".";
    }
    return out;
  }
  const SweepRecord& b = rows[*out.engine_row];
  const double bullet_error = MaxAngleError(b);
  for (size_t i = 0; i < rows.size(); ++i) {
    const SweepRecord& r = rows[i];
    if (!IsReference(r.engine) || !reaches(r) || MaxAngleError(r) > bullet_error) continue;
    if (!out.reference || r.wall_s < rows[*out.reference].wall_s) out.reference = i;
  }
  out.statement = "The cheapest " + engine + " setting reaching " + criterion.name + " (" +
                  criterion.definition + ") is " + SweepSettingDescription(b) + ", at " +
                  Format("%.3g", b.wall_s) + " s wall (max angle error " +
                  Format("%.2e", bullet_error) + " rad, |peak relative error| " +
                  Format("%.2g", MaxPeakRelError(b) * 100.0) + "%).";
  if (out.reference) {
    const SweepRecord& r = rows[*out.reference];
    out.statement +=
        " The reference reaches the same or better accuracy (max angle error, the "
        "max |error| over the run" +
        std::string(b.bodies.size() >= 3   ? " (the largest of every block's)"
                    : b.bodies.size() == 2 ? " (the larger of theta1's and theta2's)"
                                           : "") +
        ", <= the " + engine + " run's, and the same criterion) with " +
        SweepSettingDescription(r) + " at " + Format("%.3g", r.wall_s) +
        " s wall (max angle error " + Format("%.2e", MaxAngleError(r)) + " rad), " +
        Format("%.3g", b.wall_s / r.wall_s) + " times cheaper.";
  } else {
    out.statement +=
        " No reference setting in this sweep reaches the same or better accuracy "
        "(max angle error <= the " +
        engine + " run's, and the same criterion).";
  }
  return out;
}

std::optional<FittedOrder> FitOrder(const std::vector<SweepRecord>& rows,
                                    const std::vector<size_t>& family_rows,
                                    const std::string& family) {
  FittedOrder f;
  f.family = family;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i : family_rows) {
    const SweepRecord& r = rows[i];
    const double e = MaxAngleError(r), s = SweepSettingValue(r);
    if (!r.failure.empty() || !(e > 0.0) || !(s > 0.0)) continue;
    const double x = std::log(s), y = std::log(e);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    f.finest = f.points == 0 ? s : std::min(f.finest, s);
    f.coarsest = f.points == 0 ? s : std::max(f.coarsest, s);
    ++f.points;
  }
  const double n = f.points;
  const double den = n * sxx - sx * sx;
  if (f.points < 2 || !(den > 0.0)) return std::nullopt;
  f.order = (n * sxy - sx * sy) / den;
  return f;
}

std::vector<EngineAtLevels> RankAtEqualAccuracy(const std::vector<SweepRecord>& rows,
                                                const std::vector<AgreementCriterion>& levels,
                                                size_t sort_level) {
  std::vector<EngineAtLevels> out;
  const auto families = SweepFamilies(rows);
  for (const std::string& engine : SweepEngines(rows)) {
    if (IsReference(engine)) continue;
    EngineAtLevels e;
    e.engine = engine;
    for (const AgreementCriterion& level : levels) {
      e.cheapest.push_back(FindCheapestSetting(rows, level, engine).engine_row);
    }
    for (size_t i = 0; i < rows.size(); ++i) {
      const SweepRecord& r = rows[i];
      if (r.engine != engine || !r.failure.empty()) continue;
      if (!e.most_accurate || MaxAngleError(r) < MaxAngleError(rows[*e.most_accurate])) {
        e.most_accurate = i;
      }
    }
    // The order of the family of its most accurate run (an engine's first family need not be
    // its defaults: Bullet's is 4 iterations, which stall).
    const std::string best_family = e.most_accurate ? SweepFamily(rows[*e.most_accurate]) : "";
    for (const auto& [family, indices] : families) {
      if (family != best_family) continue;
      e.order = FitOrder(rows, indices, family);
      break;
    }
    out.push_back(std::move(e));
  }
  // Ranks by wall time at each level; ties share the better rank's order of appearance.
  for (size_t k = 0; k < levels.size(); ++k) {
    std::vector<size_t> reached;
    for (size_t i = 0; i < out.size(); ++i) {
      out[i].rank.push_back(0);
      if (out[i].cheapest[k]) reached.push_back(i);
    }
    std::stable_sort(reached.begin(), reached.end(), [&](size_t a, size_t b) {
      return rows[*out[a].cheapest[k]].wall_s < rows[*out[b].cheapest[k]].wall_s;
    });
    for (size_t r = 0; r < reached.size(); ++r) out[reached[r]].rank[k] = static_cast<int>(r) + 1;
  }
  auto error_of = [&](const EngineAtLevels& e) {
    return e.most_accurate ? MaxAngleError(rows[*e.most_accurate]) : INFINITY;
  };
  std::stable_sort(out.begin(), out.end(), [&](const EngineAtLevels& a, const EngineAtLevels& b) {
    if (sort_level < levels.size()) {
      const int ra = a.rank[sort_level], rb = b.rank[sort_level];
      if ((ra > 0) != (rb > 0)) return ra > 0;
      if (ra > 0) return ra < rb;
    }
    return error_of(a) < error_of(b);
  });
  return out;
}

}  // namespace rockbench::report
