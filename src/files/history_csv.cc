#include "files/history_csv.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "util/format.h"

namespace rockbench {
namespace {

// Fixed formats: 9 decimals for times (ns), 13 significant digits for states and energies.
void AppendTime(std::string& out, double t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9f", t);
  out += buf;
}

void AppendValue(std::string& out, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12e", v);
  out += buf;
}

// Free text in a CSV cell: commas and line breaks would break the row.
std::string CsvCell(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c == ',') c = ';';
    if (c == '\n' || c == '\r') c = ' ';
  }
  return out;
}

std::vector<std::string_view> SplitCommas(std::string_view line) {
  std::vector<std::string_view> out;
  size_t start = 0;
  for (;;) {
    const size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// A CSV number cell ("+" allowed, as written by %e), or nullopt.
std::optional<double> ParseNumberCell(std::string_view c) {
  if (!c.empty() && c.front() == '+') c.remove_prefix(1);
  double v = 0.0;
  const char* end = c.data() + c.size();
  const auto res = std::from_chars(c.data(), end, v);
  if (c.empty() || res.ec != std::errc() || res.ptr != end) return std::nullopt;
  return v;
}

constexpr const char* kEventsCsvHeader =
    "t,kind,mode_before,mode_after,omega1_before,omega2_before,omega1_after,omega2_after,"
    "energy_before_j,energy_after_j,note";

// The header of events.csv for `blocks` blocks: kEventsCsvHeader for one or two planar
// blocks; every body's rate `rate_stem` before and after.
std::string EventsCsvHeader(int blocks, std::string_view rate_stem = "omega") {
  if (blocks <= 2 && rate_stem == "omega") return kEventsCsvHeader;
  std::string out = "t,kind,mode_before,mode_after";
  for (const char* when : {"_before", "_after"}) {
    for (int k = 1; k <= blocks; ++k) {
      out += ',';
      out += BodyColumn(rate_stem, k);
      out += when;
    }
  }
  return out + ",energy_before_j,energy_after_j,note";
}

// The configuration's name (ConfigurationName), without a temporary for one or two blocks.
void AppendConfiguration(std::string& out, const Configuration& c) {
  if (const std::optional<Mode> mode = ModeOfConfiguration(c)) {
    out += ModeName(*mode);
  } else {
    out += ConfigurationName(c);
  }
}

// A configuration of bodies of `kind`: its own contact names for one body, when it has them.
void AppendKindConfiguration(std::string& out, const Configuration& c, const BodyKind& kind) {
  if (c.size() == 1 && !kind.contact_names.empty()) {
    out += kind.contact_names[static_cast<size_t>(c[0])];
    return;
  }
  AppendConfiguration(out, c);
}

// The inverse of AppendKindConfiguration for a stack of `blocks` bodies of `kind`.
std::optional<Configuration> ParseKindConfiguration(std::string_view text, int blocks,
                                                    const BodyKind& kind) {
  if (blocks == 1 && !kind.contact_names.empty()) {
    for (size_t i = 0; i < kind.contact_names.size(); ++i) {
      if (kind.contact_names[i] != text) continue;
      Configuration c(1);
      c.set(0, static_cast<Contact>(i));
      return c;
    }
    return std::nullopt;
  }
  return ParseConfiguration(text, blocks);
}

[[noreturn]] void Inconsistent(const char* what, double t_s, int got, int blocks) {
  throw std::logic_error(std::string(what) + " at t = " + std::to_string(t_s) + " has " +
                         std::to_string(got) + " blocks, its history " + std::to_string(blocks));
}

}  // namespace

namespace {

// Every body's column of each quantity `stems`, quantity by quantity: ",theta1,theta2".
void AppendBodyColumns(std::initializer_list<std::string_view> stems, int blocks,
                       std::string* out) {
  for (std::string_view stem : stems) {
    for (int k = 1; k <= blocks; ++k) {
      *out += ',';
      *out += BodyColumn(stem, k);
    }
  }
}

}  // namespace

std::string HistoryCsvHeader(int blocks, bool slip_and_lift) {
  std::string out = "t";
  AppendBodyColumns({"theta", "omega"}, blocks, &out);
  out += ",mode";
  if (slip_and_lift) AppendBodyColumns({"u", "z"}, blocks, &out);
  return out;
}

std::string KindHistoryCsvHeader(const BodyKind& kind, int blocks) {
  std::string out = "t";
  for (const StateQuantity& q : kind.state) AppendBodyColumns({q.stem}, blocks, &out);
  return out + ",mode";
}

namespace {

// A history of bodies of another kind than the planar block: each quantity of the kind for
// every body, then the configuration.
std::string KindHistoryToCsv(const History& history, const BodyKind& kind) {
  const int n = history.blocks;
  std::string out = KindHistoryCsvHeader(kind, n) + "\n";
  for (const Sample& s : history.samples) {
    if (s.blocks() != n || s.state.size() != kind.state.size()) {
      Inconsistent("history: a sample", s.t_s, s.blocks(), n);
    }
    AppendTime(out, s.t_s);
    for (const BlockValues& v : s.state) {
      if (static_cast<int>(v.size()) != n) Inconsistent("history: a sample", s.t_s, s.blocks(), n);
      for (const double x : v) {
        out += ',';
        AppendValue(out, x);
      }
    }
    out += ',';
    AppendKindConfiguration(out, s.mode, kind);
    out += '\n';
  }
  return out;
}

}  // namespace

std::string HistoryToCsv(const History& history) {
  if (history.shape != PlanarBlockKind().shape) {
    const BodyKind* kind = FindBodyKind(history.shape);
    if (!kind) throw std::invalid_argument("history: unknown body kind '" + history.shape + "'");
    return KindHistoryToCsv(history, *kind);
  }
  const int n = history.blocks;
  const bool slip = history.slip_and_lift;
  std::string out = HistoryCsvHeader(n, slip) + "\n";
  out.reserve(out.size() +
              history.samples.size() * (30 + (slip ? 80 : 40) * static_cast<size_t>(n)));
  for (const Sample& s : history.samples) {
    if (s.blocks() != n || static_cast<int>(s.omega_radps.size()) != n) {
      Inconsistent("history: a sample", s.t_s, s.blocks(), n);
    }
    AppendTime(out, s.t_s);
    for (const BlockValues* v : {&s.theta_rad, &s.omega_radps}) {
      for (const double x : *v) {
        out += ',';
        AppendValue(out, x);
      }
    }
    out += ',';
    AppendConfiguration(out, s.mode);
    if (slip) {
      for (const BlockValues* v : {&s.u_m, &s.z_m}) {
        // A sample without them (an engine that does not report them) writes zeros.
        for (int k = 0; k < n; ++k) {
          out += ',';
          AppendValue(out, static_cast<int>(v->size()) == n ? (*v)[k] : 0.0);
        }
      }
    }
    out += '\n';
  }
  return out;
}

std::string EventsToCsv(const History& history) {
  const int n = history.blocks;
  const BodyKind* kind = FindBodyKind(history.shape);
  if (!kind) throw std::invalid_argument("events: unknown body kind '" + history.shape + "'");
  const bool planar = kind == &PlanarBlockKind();
  std::string out = EventsCsvHeader(n, kind->event_rate_stem) + "\n";
  for (const Event& e : history.events) {
    if (e.blocks() != n || static_cast<int>(e.omega_after_radps.size()) != n) {
      Inconsistent("events: an event", e.t_s, e.blocks(), n);
    }
    AppendTime(out, e.t_s);
    out += ',' + CsvCell(e.kind) + ',';
    AppendKindConfiguration(out, e.mode_before, *kind);
    out += ',';
    AppendKindConfiguration(out, e.mode_after, *kind);
    for (const BlockValues* v : {&e.omega_before_radps, &e.omega_after_radps}) {
      for (const double x : *v) {
        out += ',';
        AppendValue(out, x);
      }
      // One planar block keeps the two-block columns: its omega2 is written as 0.
      if (n == 1 && planar) {
        out += ',';
        AppendValue(out, 0.0);
      }
    }
    for (const double x : {e.energy_before_j, e.energy_after_j}) {
      out += ',';
      AppendValue(out, x);
    }
    out += ',' + CsvCell(e.note) + '\n';
  }
  return out;
}

namespace {

// The kind of body (other than the planar block) and the number of its bodies whose header
// `line` (of `columns` columns) is: header(kind, n), the file's header for n bodies of that kind,
// has `fixed_columns` and per_body(kind) more for each body. Nullopt for none.
template <typename PerBody, typename Header>
std::optional<std::pair<const BodyKind*, int>> KindOfHeader(const std::string& line, size_t columns,
                                                            size_t fixed_columns,
                                                            const PerBody& per_body,
                                                            const Header& header) {
  for (const std::string& shape : BodyShapes()) {
    const BodyKind* kind = FindBodyKind(shape);
    if (shape == PlanarBlockKind().shape || !kind) continue;
    const size_t q = per_body(*kind);
    if (q == 0 || columns < fixed_columns + q || (columns - fixed_columns) % q != 0) continue;
    const int n = static_cast<int>((columns - fixed_columns) / q);
    if (n <= kMaxBlocks && line == header(*kind, n)) return {{kind, n}};
  }
  return std::nullopt;
}

// A history header's kind: "t", each quantity for every body, "mode".
std::optional<std::pair<const BodyKind*, int>> KindOfHistoryHeader(const std::string& line,
                                                                   size_t columns) {
  return KindOfHeader(
      line, columns, 2, [](const BodyKind& kind) { return kind.state.size(); },
      [](const BodyKind& kind, int n) { return KindHistoryCsvHeader(kind, n); });
}

// An events header's kind: "t,kind,mode_before,mode_after", every body's rate before and after,
// "energy_before_j,energy_after_j,note".
std::optional<std::pair<const BodyKind*, int>> KindOfEventsHeader(const std::string& line,
                                                                  size_t columns) {
  return KindOfHeader(
      line, columns, 7, [](const BodyKind&) { return size_t{2}; },
      [](const BodyKind& kind, int n) { return EventsCsvHeader(n, kind.event_rate_stem); });
}

// Cell i of a history row as a number; `fail` (which throws) names the column otherwise.
template <typename Fail>
double NumberCell(const std::vector<std::string_view>& cells, size_t i, const Fail& fail) {
  const std::optional<double> x = ParseNumberCell(cells[i]);
  if (!x) {
    fail("column " + std::to_string(i + 1) + ": expected a number, got '" + std::string(cells[i]) +
         "'");
  }
  return *x;
}

// One row of a history of `kind` bodies: t, each quantity for every body, the configuration.
template <typename Fail>
Sample KindSample(const std::vector<std::string_view>& cells, const BodyKind& kind, int blocks,
                  const Fail& fail) {
  Sample s(blocks, kind);
  const size_t n = static_cast<size_t>(blocks);
  const size_t mode_col = cells.size() - 1;
  for (size_t i = 0; i < mode_col; ++i) {
    const double x = NumberCell(cells, i, fail);
    if (i == 0) {
      s.t_s = x;
    } else {
      s.state[(i - 1) / n][(i - 1) % n] = x;
    }
  }
  const std::optional<Configuration> mode = ParseKindConfiguration(cells[mode_col], blocks, kind);
  if (!mode) {
    fail((kind.contact_names.empty() || blocks != 1
              ? std::string("expected a configuration (one letter f, r or l per body)")
              : "expected a mode (" + QuotedList(kind.contact_names) + ")") +
         ", got '" + std::string(cells[mode_col]) + "'");
  }
  s.mode = *mode;
  return s;
}

}  // namespace

History ReadHistoryCsv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the history file");
  History h;
  std::string line;
  int number = 0;
  bool header_seen = false;
  const auto fail = [&](const std::string& msg) {
    throw std::runtime_error(path.string() + ":" + std::to_string(number) + ": " + msg);
  };
  size_t want = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!header_seen) {
      // "t", N angles, N rates, "mode" (and N slips, N lifts): the columns give N, the header
      // must then be its own.
      const size_t columns = SplitCommas(line).size();
      const int n = columns >= 4 && columns % 2 == 0 ? static_cast<int>((columns - 2) / 2) : 0;
      const int n_slip =
          columns >= 6 && (columns - 2) % 4 == 0 ? static_cast<int>((columns - 2) / 4) : 0;
      if (const auto kind = KindOfHistoryHeader(line, columns)) {
        h.shape = kind->first->shape;
        h.blocks = kind->second;
      } else if (n_slip >= 1 && n_slip <= kMaxBlocks && line == HistoryCsvHeader(n_slip, true)) {
        h.slip_and_lift = true;
        h.blocks = n_slip;
      } else if (n < 1 || n > kMaxBlocks || line != HistoryCsvHeader(n)) {
        fail("expected the header '" + HistoryCsvHeader(2) + "' or '" + HistoryCsvHeader(1) +
             "' (or t,theta1,...,thetaN,omega1,...,omegaN,mode for N blocks, and u1,...,uN,"
             "z1,...,zN after it with slip and lift), got '" +
             line + "'");
      } else {
        h.blocks = n;
      }
      want = columns;
      header_seen = true;
      continue;
    }
    if (line.empty()) continue;
    const std::vector<std::string_view> cells = SplitCommas(line);
    if (cells.size() != want) {
      fail("expected " + std::to_string(want) + " columns, got " + std::to_string(cells.size()));
    }
    if (h.shape != PlanarBlockKind().shape) {
      h.samples.push_back(KindSample(cells, *FindBodyKind(h.shape), h.blocks, fail));
      continue;
    }
    Sample s(h.blocks, h.slip_and_lift);
    const size_t n = static_cast<size_t>(h.blocks);
    // The mode's column: the last one, or before the 2 N slip and lift columns.
    const size_t mode_col = h.slip_and_lift ? 1 + 2 * n : want - 1;
    for (size_t i = 0; i < want; ++i) {
      if (i == mode_col) continue;
      const double x = NumberCell(cells, i, fail);
      if (i == 0) {
        s.t_s = x;
      } else if (i <= n) {
        s.theta_rad[i - 1] = x;
      } else if (i <= 2 * n) {
        s.omega_radps[i - 1 - n] = x;
      } else if (i <= 3 * n + 1) {
        s.u_m[i - 2 - 2 * n] = x;
      } else {
        s.z_m[i - 2 - 3 * n] = x;
      }
    }
    const std::optional<Configuration> mode = ParseConfiguration(cells[mode_col], h.blocks);
    if (!mode) {
      fail(h.blocks <= 2 ? "expected a mode name (rest, 1a, ..., 4b), got '" +
                               std::string(cells[mode_col]) + "'"
                         : "expected a configuration (one letter f, r or l per block), got '" +
                               std::string(cells[mode_col]) + "'");
    }
    s.mode = *mode;
    h.samples.push_back(std::move(s));
  }
  if (in.bad()) throw std::runtime_error(path.string() + ": cannot read the history file");
  if (!header_seen) {
    throw std::runtime_error(path.string() + ":1: empty file (expected a history header)");
  }
  return h;
}

std::vector<Event> ReadEventsCsv(const std::filesystem::path& path, int blocks,
                                 std::string_view shape) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the events file");
  const BodyKind* wanted = shape.empty() ? nullptr : FindBodyKind(shape);
  if (!shape.empty() && !wanted) {
    throw std::invalid_argument("events: unknown body kind '" + std::string(shape) + "'");
  }
  std::vector<Event> events;
  std::string line;
  int number = 0;
  const auto fail = [&](const std::string& msg) {
    throw std::runtime_error(path.string() + ":" + std::to_string(number) + ": " + msg);
  };
  // The header's kind and bodies (1 or 2 planar blocks share one: `blocks`, 2 when unknown), its
  // columns and the rate columns on each side (a planar block's omega2 is written when alone).
  const BodyKind* kind = &PlanarBlockKind();
  int n = 0;
  size_t want = 0;
  int rates = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      const size_t columns = SplitCommas(line).size();
      const auto other = KindOfEventsHeader(line, columns);
      if (line == kEventsCsvHeader && blocks <= 2) {
        n = blocks == 1 ? 1 : 2;
      } else if (columns >= 13 && columns % 2 == 1 && (columns - 7) / 2 <= kMaxBlocks &&
                 line == EventsCsvHeader(static_cast<int>((columns - 7) / 2)) &&
                 (blocks == 0 || blocks == static_cast<int>((columns - 7) / 2))) {
        n = static_cast<int>((columns - 7) / 2);
      } else if (other && (blocks == 0 || blocks == other->second)) {
        kind = other->first;
        n = other->second;
      } else {
        const bool planar = !wanted || wanted == &PlanarBlockKind();
        fail("expected the header '" +
             (planar ? EventsCsvHeader(blocks)
                     : EventsCsvHeader(std::max(blocks, 1), wanted->event_rate_stem)) +
             "', got '" + line + "'");
      }
      if (wanted && kind != wanted) {
        fail("expected the events of " + wanted->shape + " bodies, got the header '" + line +
             "' (" + kind->shape + ")");
      }
      const bool planar = kind == &PlanarBlockKind();
      rates = planar ? std::max(n, 2) : n;
      want = planar && n <= 2 ? 11 : columns;
      continue;
    }
    if (line.empty()) continue;
    const std::vector<std::string_view> cells = SplitCommas(line);
    if (cells.size() != want) {
      fail("expected " + std::to_string(want) + " columns, got " + std::to_string(cells.size()));
    }
    const auto number_at = [&](size_t i, const std::string& what) {
      const std::optional<double> x = ParseNumberCell(cells[i]);
      if (!x || !std::isfinite(*x)) {
        fail(what + ": expected a finite number, got '" + std::string(cells[i]) + "'");
      }
      return *x;
    };
    const auto mode_at = [&](size_t i, const char* what) {
      const std::optional<Configuration> m = ParseKindConfiguration(cells[i], n, *kind);
      if (!m) fail(std::string(what) + ": unknown mode '" + std::string(cells[i]) + "'");
      return *m;
    };
    Event e(n);
    e.t_s = number_at(0, "t");
    e.kind = std::string(cells[1]);
    e.mode_before = mode_at(2, "mode_before");
    e.mode_after = mode_at(3, "mode_after");
    // The rate columns: `rates` before, then as many after.
    for (int side = 0; side < 2; ++side) {
      BlockValues& v = side == 0 ? e.omega_before_radps : e.omega_after_radps;
      for (int k = 0; k < rates; ++k) {
        const double x = number_at(
            4 + static_cast<size_t>(side * rates + k),
            BodyColumn(kind->event_rate_stem, k + 1) + (side == 0 ? "_before" : "_after"));
        if (k < n) v[static_cast<size_t>(k)] = x;
      }
    }
    const size_t tail = 4 + 2 * static_cast<size_t>(rates);
    e.energy_before_j = number_at(tail, "energy_before_j");
    e.energy_after_j = number_at(tail + 1, "energy_after_j");
    e.note = std::string(cells[tail + 2]);
    events.push_back(std::move(e));
  }
  if (in.bad()) throw std::runtime_error(path.string() + ": cannot read the events file");
  if (number == 0) {
    throw std::runtime_error(path.string() + ":1: empty file (expected the events header)");
  }
  return events;
}

}  // namespace rockbench
