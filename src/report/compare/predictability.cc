#include "report/compare/predictability.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "report/common/json_keys.h"
#include "scene/history.h"

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
                             "' is not a number: '" + cell + "'");
  }
  return v;
}

}  // namespace

std::optional<Predictability> ReadPredictability(const json& comparison, const fs::path& file,
                                                 bool two_blocks) {
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
  for (int b = 0; b < (two_blocks ? 2 : 1); ++b) {
    const std::string th = "theta" + std::to_string(b + 1);
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
  band.two_blocks = column("theta2_lo") >= 0;
  int cols[7] = {column("t")};
  const char* names[7] = {"t",         "theta1_lo", "theta1_hi",    "theta1_spread",
                          "theta2_lo", "theta2_hi", "theta2_spread"};
  const int needed = band.two_blocks ? 7 : 4;
  for (int k = 0; k < needed; ++k) {
    cols[k] = column(names[k]);
    if (cols[k] < 0) {
      throw std::runtime_error(csv.string() + ": line 1: no column '" + names[k] +
                               "' (expected t,theta1_lo,theta1_hi,theta1_spread[,theta2_lo,"
                               "theta2_hi,theta2_spread])");
    }
  }
  std::vector<double>* targets[7] = {&band.t_s,           &band.lo_rad[0], &band.hi_rad[0],
                                     &band.spread_rad[0], &band.lo_rad[1], &band.hi_rad[1],
                                     &band.spread_rad[1]};
  for (int n = 2; std::getline(text, line); ++n) {
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = SplitCsvLine(line);
    if (cells.size() != header.size()) {
      throw std::runtime_error(csv.string() + ": line " + std::to_string(n) + ": " +
                               std::to_string(cells.size()) + " cells, the header has " +
                               std::to_string(header.size()));
    }
    for (int k = 0; k < needed; ++k) {
      targets[k]->push_back(ParseCell(cells[cols[k]], csv, n, names[k]));
    }
  }
  return band;
}

}  // namespace rockbench::report
