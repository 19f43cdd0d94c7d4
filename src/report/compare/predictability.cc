#include "report/compare/predictability.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "files/atomic_file.h"
#include "report/common/json_keys.h"
#include "scene/body_kind.h"
#include "scene/history.h"
#include "scene/limits.h"
#include "scene/mode.h"
#include "util/format.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<std::string> SplitCsvLine(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

double ParseCell(const std::string& cell, const fs::path& csv, int line, const std::string& col) {
  const char* begin = cell.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (cell.empty() || end != begin + cell.size() || errno == ERANGE) {
    throw std::runtime_error(csv.string() + ": line " + std::to_string(line) + ": column '" + col +
                             "' is not a number: '" + Excerpt(cell) + "'");
  }
  return v;
}

}  // namespace

std::optional<Predictability> ReadPredictability(const json& comparison, const fs::path& file,
                                                 int blocks) {
  const json* p = Find(comparison, "predictability");
  if (p == nullptr || p->is_null()) return std::nullopt;
  if (!p->is_object()) {
    throw std::runtime_error(file.string() + ": key 'predictability' must be an object or null");
  }
  Predictability out;
  const double members = OptNumber(*p, "members", file);
  if (std::isnan(members) || members <= 0) return std::nullopt;
  out.members = static_cast<int>(members);
  out.amplitude_rel = OptNumber(*p, "perturbation.amplitude_rel", file);
  out.sample_precision = OptNumber(*p, "perturbation.sample_precision", file);
  out.initial_rel = OptNumber(*p, "perturbation.initial_rel", file);
  out.seed = OptNumber(*p, "perturbation.seed", file);
  out.rule = OptString(*p, "perturbation.rule", file);
  const int nb = std::max(blocks, 1);
  out.horizon_s.assign(std::max(nb, 2), std::nullopt);
  out.tolerance_rad.assign(std::max(nb, 2), Predictability::kNaN);
  out.spread_rad.assign(std::max(nb, 2), Predictability::kNaN);
  // A cylinder's horizon and spread are of its tilt vector ("tilt1").
  const json* cylinder = Find(*p, "horizon_s.tilt1");
  const std::string stem = cylinder != nullptr ? "tilt" : "theta";
  for (int b = 0; b < nb; ++b) {
    const std::string th = BodyColumn(stem, b + 1);
    const double h = OptNumber(*p, "horizon_s." + th, file);
    if (!std::isnan(h)) out.horizon_s[b] = h;
    out.tolerance_rad[b] = OptNumber(*p, "tolerance_rad." + th, file);
    out.spread_rad[b] = OptNumber(*p, "spread_rad." + th, file);
  }
  if (const json* st = Find(*p, "statuses"); st != nullptr && st->is_object()) {
    for (auto it = st->begin(); it != st->end(); ++it) {
      out.statuses.emplace_back(it.key(), static_cast<int>(OptNumber(*st, it.key(), file)));
    }
  }
  out.wall_s = OptNumber(*p, "wall_s", file);
  return out;
}

std::optional<EnsembleBand> ReadEnsembleBand(const fs::path& csv) {
  if (!fs::exists(csv)) return std::nullopt;
  std::stringstream text(ReadTextFile(csv));
  std::string line;
  if (!std::getline(text, line)) throw std::runtime_error(csv.string() + ": empty file");
  const std::vector<std::string> header = SplitCsvLine(line);
  const auto column = [&](const std::string& name) {
    for (size_t k = 0; k < header.size(); ++k) {
      if (header[k] == name) return static_cast<int>(k);
    }
    return -1;
  };
  EnsembleBand band;
  // Blocks 1, 2, ... as long as their columns are there (theta1's are required).
  std::vector<std::string> names = {"t"};
  std::vector<std::vector<double>*> targets = {&band.t_s};
  // A cylinder's band is of its tilt (tilt1_lo, ...).
  const std::string stem = column("tilt1_lo") >= 0 ? "tilt" : "theta";
  int nb = 0;
  while (nb < kMaxBlocks && (nb == 0 || column(BodyColumn(stem, nb + 1) + "_lo") >= 0)) ++nb;
  band.blocks = nb;
  band.lo_rad.resize(std::max(nb, 2));
  band.hi_rad.resize(std::max(nb, 2));
  band.spread_rad.resize(std::max(nb, 2));
  for (int b = 0; b < nb; ++b) {
    const std::string th = BodyColumn(stem, b + 1);
    for (const char* tail : {"_lo", "_hi", "_spread"}) names.push_back(th + tail);
    targets.push_back(&band.lo_rad[b]);
    targets.push_back(&band.hi_rad[b]);
    targets.push_back(&band.spread_rad[b]);
  }
  std::vector<int> cols(names.size());
  for (size_t k = 0; k < names.size(); ++k) {
    cols[k] = column(names[k]);
    if (cols[k] < 0) {
      throw std::runtime_error(csv.string() + ": line 1: no column '" + names[k] +
                               "' (expected t,theta1_lo,theta1_hi,theta1_spread[,theta2_lo,"
                               "theta2_hi,theta2_spread], or a cylinder's t,tilt1_lo,tilt1_hi,"
                               "tilt1_spread)");
    }
  }
  for (int n = 2; std::getline(text, line); ++n) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = SplitCsvLine(line);
    if (cells.size() != header.size()) {
      throw std::runtime_error(csv.string() + ": line " + std::to_string(n) + ": " +
                               std::to_string(cells.size()) + " cells, the header has " +
                               std::to_string(header.size()));
    }
    for (size_t k = 0; k < names.size(); ++k) {
      targets[k]->push_back(ParseCell(cells[cols[k]], csv, n, names[k]));
    }
  }
  return band;
}

}  // namespace rockbench::report
