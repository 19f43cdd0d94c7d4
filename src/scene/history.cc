#include "scene/history.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

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

}  // namespace

std::string HistoryCsvHeader(bool two_blocks) {
  return two_blocks ? "t,theta1,theta2,omega1,omega2,mode" : "t,theta1,omega1,mode";
}

std::string HistoryToCsv(const History& history) {
  std::string out = HistoryCsvHeader(history.two_blocks) + "\n";
  out.reserve(out.size() + history.samples.size() * 90);
  for (const Sample& s : history.samples) {
    AppendTime(out, s.t_s);
    out += ',';
    AppendValue(out, s.theta1_rad);
    out += ',';
    if (history.two_blocks) {
      AppendValue(out, s.theta2_rad);
      out += ',';
    }
    AppendValue(out, s.omega1_radps);
    out += ',';
    if (history.two_blocks) {
      AppendValue(out, s.omega2_radps);
      out += ',';
    }
    out += ModeName(s.mode);
    out += '\n';
  }
  return out;
}

std::string EventsToCsv(const History& history) {
  std::string out = std::string(kEventsCsvHeader) + "\n";
  for (const Event& e : history.events) {
    AppendTime(out, e.t_s);
    out += ',' + CsvCell(e.kind) + ',';
    out += ModeName(e.mode_before);
    out += ',';
    out += ModeName(e.mode_after);
    for (double v : {e.omega1_before, e.omega2_before, e.omega1_after, e.omega2_after,
                     e.energy_before_j, e.energy_after_j}) {
      out += ',';
      AppendValue(out, v);
    }
    out += ',' + CsvCell(e.note) + '\n';
  }
  return out;
}

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
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!header_seen) {
      if (line == HistoryCsvHeader(true)) {
        h.two_blocks = true;
      } else if (line == HistoryCsvHeader(false)) {
        h.two_blocks = false;
      } else {
        fail("expected the header '" + HistoryCsvHeader(true) + "' or '" + HistoryCsvHeader(false) +
             "', got '" + line + "'");
      }
      header_seen = true;
      continue;
    }
    if (line.empty()) continue;
    const std::vector<std::string_view> cells = SplitCommas(line);
    const size_t want = h.two_blocks ? 6 : 4;
    if (cells.size() != want) {
      fail("expected " + std::to_string(want) + " columns, got " + std::to_string(cells.size()));
    }
    double v[5] = {0, 0, 0, 0, 0};
    for (size_t i = 0; i + 1 < want; ++i) {
      const std::optional<double> x = ParseNumberCell(cells[i]);
      if (!x) {
        fail("column " + std::to_string(i + 1) + ": expected a number, got '" +
             std::string(cells[i]) + "'");
      }
      v[i] = *x;
    }
    const auto mode = ParseMode(cells[want - 1]);
    if (!mode)
      fail("expected a mode name (rest, 1a, ..., 4b), got '" + std::string(cells[want - 1]) + "'");
    Sample s;
    s.t_s = v[0];
    s.theta1_rad = v[1];
    if (h.two_blocks) {
      s.theta2_rad = v[2];
      s.omega1_radps = v[3];
      s.omega2_radps = v[4];
    } else {
      s.omega1_radps = v[2];
    }
    s.mode = *mode;
    h.samples.push_back(s);
  }
  if (in.bad()) throw std::runtime_error(path.string() + ": cannot read the history file");
  if (!header_seen) {
    throw std::runtime_error(path.string() + ":1: empty file (expected a history header)");
  }
  return h;
}

std::vector<Event> ReadEventsCsv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the events file");
  std::vector<Event> events;
  std::string line;
  int number = 0;
  const auto fail = [&](const std::string& msg) {
    throw std::runtime_error(path.string() + ":" + std::to_string(number) + ": " + msg);
  };
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != kEventsCsvHeader) {
        fail(std::string("expected the header '") + kEventsCsvHeader + "', got '" + line + "'");
      }
      continue;
    }
    if (line.empty()) continue;
    const std::vector<std::string_view> cells = SplitCommas(line);
    if (cells.size() != 11) {
      fail("expected 11 columns, got " + std::to_string(cells.size()));
    }
    const auto number_at = [&](size_t i, const char* what) {
      const std::optional<double> x = ParseNumberCell(cells[i]);
      if (!x || !std::isfinite(*x)) {
        fail(std::string(what) + ": expected a finite number, got '" + std::string(cells[i]) + "'");
      }
      return *x;
    };
    const auto mode_at = [&](size_t i, const char* what) {
      const auto m = ParseMode(cells[i]);
      if (!m) fail(std::string(what) + ": unknown mode '" + std::string(cells[i]) + "'");
      return *m;
    };
    Event e;
    e.t_s = number_at(0, "t");
    e.kind = std::string(cells[1]);
    e.mode_before = mode_at(2, "mode_before");
    e.mode_after = mode_at(3, "mode_after");
    e.omega1_before = number_at(4, "omega1_before");
    e.omega2_before = number_at(5, "omega2_before");
    e.omega1_after = number_at(6, "omega1_after");
    e.omega2_after = number_at(7, "omega2_after");
    e.energy_before_j = number_at(8, "energy_before_j");
    e.energy_after_j = number_at(9, "energy_after_j");
    e.note = std::string(cells[10]);
    events.push_back(std::move(e));
  }
  if (in.bad()) throw std::runtime_error(path.string() + ": cannot read the events file");
  if (number == 0) {
    throw std::runtime_error(path.string() + ":1: empty file (expected the events header)");
  }
  return events;
}

std::string ReadTextFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read (not found?)");
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw std::runtime_error(path.string() + ": cannot be read");
  return ss.str();
}

void WriteFileAtomic(const std::filesystem::path& path, const std::string& text) {
  const auto fail = [&](const std::string& what, int err) {
    throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(err));
  };
  const std::filesystem::path parent = path.parent_path();
  if (!parent.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec) throw std::runtime_error(parent.string() + ": cannot create folder: " + ec.message());
  }
  const std::string tmp = path.string() + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot create " + tmp, errno);
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      ::unlink(tmp.c_str());
      fail("cannot write " + tmp, err);
    }
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    fail("cannot sync " + tmp, err);
  }
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail("cannot close " + tmp, err);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail("cannot rename " + tmp, err);
  }
}

}  // namespace rockbench
