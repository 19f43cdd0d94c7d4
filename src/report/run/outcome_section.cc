#include "report/run/outcome_section.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/outcome.h"
#include "report/common/json_keys.h"
#include "report/common/number_text.h"
#include "report/compare/verdict_section.h"
#include "report/run/run_figures.h"

namespace rockbench::report {
namespace {

using nlohmann::json;

// An engine's warnings, checked against the scene's model: sliding is a warning only where the
// reference cannot slide (every friction infinite), lift-off only where the reference's stack
// never lifted off (with a finite friction or a vertical motion the reference follows both with
// its unilateral model, docs/sliding.md, and the comparison judges u and z instead).
std::string EngineWarnings(const RunData& run, const EngineData& e, std::vector<std::string>& out) {
  const json* v = Find(e.summary, "violations");
  std::string status = e.summary.value("status", std::string("unknown"));
  if (v == nullptr || !v->is_object()) return status;
  const auto flag = [&](const char* k) {
    return v->contains(k) && (*v)[k].is_boolean() && (*v)[k].get<bool>();
  };
  const auto num = [&](const char* k) {
    return v->contains(k) && (*v)[k].is_number() ? (*v)[k].get<double>() : kNaN;
  };
  const std::string who = "The " + e.name + " run";
  // The monitor's contacts: "ground" and "interface" for one and two blocks (as the page has
  // always named them), "ground", "interface2" ... "interfaceN" for N >= 3 blocks.
  // Each contact's key and its words.
  const int blocks = e.history.blocks;
  std::vector<std::pair<std::string, std::string>> contacts = {{"ground", "the ground"},
                                                               {"interface", "the interface"}};
  if (blocks >= 3) {
    contacts.resize(1);
    for (int k = 1; k < blocks; ++k) {
      const std::string upper = std::to_string(k + 1), lower = std::to_string(k);
      contacts.push_back({InterfaceName(k, blocks), std::string("interface ") + upper + " (block " +
                                                        upper + " on block " + lower + ")"});
    }
  }
  const auto key = [](const std::string& what, const std::string& contact,
                      const std::string& tail) { return what + "_" + contact + tail; };
  const bool reference_slides = run.scene.has_finite_friction();
  const double reference_lift_offs =
      OptNumber(run.summary, "unilateral.lift_offs", run.summary_path);
  const bool reference_lifts = reference_lift_offs > 0;
  if (flag("sliding") && !reference_slides) {
    std::string where;
    for (size_t k = 0; k < contacts.size(); ++k) {
      where += std::string(k == 0                     ? ""
                           : k + 1 == contacts.size() ? " and "
                                                      : ", ") +
               Num(1e3 * num(key("slip", contacts[k].first, "_m").c_str()), 3) + " mm at " +
               contacts[k].second;
    }
    out.push_back(who + " slid: the blocks slipped " + where +
                  ". The scene gives no friction coefficient (infinite friction), so the "
                  "reference's blocks cannot slide: the two are not simulating the same system.");
  }
  if (flag("uplift") && !reference_lifts) {
    std::string where;
    for (const auto& [c, words] : contacts) {
      const double n = num(key("uplift", c, "_episodes").c_str());
      if (!(n > 0)) continue;
      where += std::string(where.empty() ? "" : " and ") + Num(n) + " time(s) at " + words +
               " (up to " + Num(1e3 * num(key("uplift", c, "_max_m").c_str()), 3) + " mm)";
    }
    out.push_back(who + " lifted off" + (where.empty() ? "" : ": " + where) +
                  ". The reference's blocks never lift off in this run: their pivots stay in "
                  "contact (no bouncing or jumping).");
  }
  if (flag("penetration")) {
    double depth = num(key("penetration", contacts[0].first, "_max_m").c_str());
    for (size_t k = 1; k < contacts.size(); ++k) {
      depth = std::max(depth, num(key("penetration", contacts[k].first, "_max_m").c_str()));
    }
    out.push_back(who + " let the blocks sink into each other or the ground by up to " +
                  Num(1e3 * depth, 3) + " mm: its contacts are soft at this time step.");
  }
  if (flag("energy_growth")) {
    out.push_back(who + " gained energy without input: up to " + Num(num("energy_gain_max_j")) +
                  " J (" + Num(100.0 * num("energy_gain_rel"), 3) +
                  " % of the energy needed to tip the stack) at t = " +
                  Num(num("energy_gain_t_s"), 4) + " s.");
  }
  if (status == "non_finite") {
    out.push_back(who + " FAILED: its state stopped being finite (" +
                  e.summary.value("status_detail", std::string("non_finite")) +
                  "). Its results end at its last finite state.");
  } else if (flag("blow_up")) {
    out.push_back(who +
                  " blew up (non-finite state, runaway rate or energy) and stopped early; "
                  "its results after that are meaningless.");
  }
  return status;
}

}  // namespace

std::string AssumptionViolatedOutcome(const RunData& run, std::vector<std::string>& warnings) {
  std::string when;
  for (const Event& ev : run.engines.front().events) {
    if (ev.kind == "assumption_violated") when = Fixed(ev.t_s, 4);
  }
  warnings.push_back("The reference model's assumptions were violated" +
                     (when.empty() ? std::string() : " at t = " + when + " s") + ": " +
                     OptString(run.summary, "status_detail", run.summary_path) +
                     ". The run stopped there; nothing after that time is simulated.");
  return "The reference model stopped: an assumption was violated.";
}

std::string ReferenceOutcome(const RunData& run, std::vector<std::string>& warnings) {
  const EngineData& ref = run.engines.front();
  std::string outcome;
  const std::string status = OptString(run.summary, "status", run.summary_path);
  if (status == "overturned") {
    outcome =
        "The reference model: block " +
        Num(OptNumber(run.summary, "overturn.block", run.summary_path)) +
        " overturned at t = " + Fixed(OptNumber(run.summary, "overturn.t_s", run.summary_path), 4) +
        " s.";
  } else if (status == "left_support") {
    outcome = "The reference model: block " +
              Num(OptNumber(run.summary, "left_support.block", run.summary_path)) +
              " left its support (slid off it) at t = " +
              Fixed(OptNumber(run.summary, "left_support.t_s", run.summary_path), 4) +
              " s; the model ends there.";
  } else if (status == "at_rest") {
    outcome = "The reference model: the blocks came to rest (run to " +
              Fixed(ref.history.samples.back().t_s, 3) + " s).";
  } else if (status == "non_finite") {
    outcome = "The reference model FAILED: its solution stopped being finite.";
    warnings.push_back("The reference model's solution is not finite: " +
                       OptString(run.summary, "status_detail", run.summary_path) +
                       ". Its history, peaks and counts are those of the part before that; "
                       "nothing after it was computed, and no verdict rests on it.");
  } else if (status == "assumption_violated") {
    outcome = AssumptionViolatedOutcome(run, warnings);
  } else {
    outcome = "The reference model ran to t = " + Fixed(ref.history.samples.back().t_s, 3) +
              " s (" + status + ").";
  }
  const double inadmissible = OptNumber(run.summary, "impacts.inadmissible", run.summary_path);
  if (inadmissible > 0) {
    warnings.push_back(
        Num(inadmissible) +
        " impact(s) of the reference had no admissible outcome (every "
        "candidate needs a pulling impulse or moves a body into another); the thesis's velocity "
        "check chose the outcome (notes in reference/events.csv).");
  }
  const double gain = OptNumber(run.summary, "impacts.energy_gain", run.summary_path);
  if (gain > 0) {
    warnings.push_back(Num(gain) + " impact(s) of the reference added energy.");
  }
  // Where the model stopped deciding the motion (an impact or a contact state with no
  // admissible outcome, or several): from there the history is one choice of its rule.
  const double undetermined = OptNumber(run.summary, "undetermined.t_s", run.summary_path);
  if (!std::isnan(undetermined)) {
    const std::string when = Fixed(undetermined, 4);
    outcome += " The model stopped deciding the motion at t = " + when +
               " s: the history after that instant is the outcome its rule chose.";
    warnings.push_back("The reference model does not decide the motion from t = " + when +
                       " s on (" + OptString(run.summary, "undetermined.detail", run.summary_path) +
                       "): after that instant its history is one admissible outcome that the "
                       "model's rule chose, and no comparison rests on it.");
  }
  return outcome;
}

std::string EnginesOutcome(const RunData& run, std::vector<std::string>& warnings) {
  std::string text;
  std::vector<std::string> engine_status;
  for (size_t i = 1; i < run.engines.size(); ++i) {
    const std::string st = EngineWarnings(run, run.engines[i], warnings);
    std::string line = run.engines[i].name + ": " + st;
    const double ot = OptNumber(run.engines[i].summary, "overturn.t_s", run.summary_path);
    if (!std::isnan(ot)) {
      line += ", block " +
              Num(OptNumber(run.engines[i].summary, "overturn.block", run.summary_path)) +
              " overturned at t = " + Fixed(ot, 4) + " s";
    }
    const double lt = OptNumber(run.engines[i].summary, "left_support.t_s", run.summary_path);
    if (!std::isnan(lt)) {
      line += ", block " +
              Num(OptNumber(run.engines[i].summary, "left_support.block", run.summary_path)) +
              " left its support (slid off it) at t = " + Fixed(lt, 4) + " s";
    }
    engine_status.push_back(line);
  }
  if (run.engines.size() > 1) {
    text += " Engines compared:";
    for (size_t i = 0; i < engine_status.size(); ++i) {
      text += (i ? "; " : " ") + engine_status[i];
    }
    text += ".";
  } else {
    text += " No engine was compared with it.";
  }
  return text;
}

void VerdictSection(const RunData& run, Page& page, RunReportResult& result) {
  VerdictInput in;
  in.comparison = run.comparison ? &*run.comparison : nullptr;
  in.comparison_path = run.comparison_path;
  in.summary = &run.summary;
  in.summary_path = run.summary_path;
  for (size_t i = 1; i < run.engines.size(); ++i) in.engines.push_back(run.engines[i].name);
  in.blocks = run.scene.block_count();
  in.predictability = run.predictability;
  for (std::string& w : WriteVerdictSection(in, page)) result.warnings.push_back(std::move(w));
}

}  // namespace rockbench::report
