// Readers of ground-motion record files: PEER AT2 (every header variant of records/SOURCES.md)
// and plain one- or two-column text files.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "motion/ground_motion.h"
#include "scene/limits.h"

namespace rockbench {
namespace {

// A line of the file: its 1-based number and its text with CR characters removed.
struct Line {
  int number = 0;
  std::string text;
};

std::string ReadRecordText(const std::filesystem::path& path) {
  if (const std::string problem = InputFileProblem(path, "record file"); !problem.empty()) {
    throw SceneError(problem);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path.string() + ": cannot open the record file");
  std::ostringstream buf;
  buf << in.rdbuf();
  if (in.bad()) throw SceneError(path.string() + ": cannot read the record file");
  return buf.str();
}

std::vector<Line> SplitLines(const std::filesystem::path& path, const std::string& text) {
  // A CR that ends a line without an LF (old Mac OS line endings) would make the whole file one
  // line: refused, at the line it ends.
  for (size_t at = text.find('\r'); at != std::string::npos; at = text.find('\r', at + 1)) {
    size_t next = at + 1;
    while (next < text.size() && text[next] == '\r') ++next;
    if (next < text.size() && text[next] != '\n') {
      const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
      throw SceneError(path.string() + ":" + std::to_string(line) +
                       ": a line ends with a carriage return (CR) alone; expected LF or CR LF "
                       "line endings (convert the file, e.g. with tr '\\r' '\\n')");
    }
    at = next - 1;
  }
  std::vector<Line> lines;
  int number = 1;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    // Stray CRs (CR LF, CR CR LF) are dropped.
    line.erase(std::remove(line.begin(), line.end(), '\r'), line.end());
    if (end < text.size() || !line.empty()) lines.push_back({number, std::move(line)});
    ++number;
    start = end + 1;
  }
  return lines;
}

// Splits on whitespace, and on commas when `commas` is set.
std::vector<std::string_view> Tokens(std::string_view s, bool commas) {
  std::vector<std::string_view> out;
  size_t i = 0;
  const auto is_sep = [&](char c) {
    return c == ' ' || c == '\t' || c == '\v' || c == '\f' || (commas && c == ',');
  };
  while (i < s.size()) {
    while (i < s.size() && is_sep(s[i])) ++i;
    size_t j = i;
    while (j < s.size() && !is_sep(s[j])) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

// Parses a whole token as a number (a leading '+' is allowed); nan/inf parse but are non-finite.
bool ParseNumber(std::string_view tok, double& out) {
  if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
  if (tok.empty()) return false;
  const char* end = tok.data() + tok.size();
  auto res = std::from_chars(tok.data(), end, out);
  return res.ec == std::errc() && res.ptr == end;
}

std::string Where(const std::filesystem::path& path, int line) {
  return path.string() + ":" + std::to_string(line);
}

// Why `dt_s` cannot be a record's sample interval, or "": records are sampled at 1 Hz to 1 MHz
// (strong-motion records at 50 to 1000 Hz).
std::string SampleIntervalProblem(double dt_s) {
  if (dt_s >= 1e-6 && dt_s <= 1.0) return "";
  return "expected a sample interval from 1e-06 to 1 s (records are sampled at 50 to 1000 Hz; "
         "docs/limits.md)";
}

// Reads one value token, with an error naming file and line.
double Value(const std::filesystem::path& path, int line, std::string_view tok) {
  double v = 0.0;
  if (!ParseNumber(tok, v)) {
    throw SceneError(Where(path, line) + ": expected a number, got '" + Excerpt(tok) + "'");
  }
  if (!std::isfinite(v)) {
    throw SceneError(Where(path, line) + ": expected a finite number, got '" + Excerpt(tok) + "'");
  }
  return v;
}

// The printed resolution of a value token already read by Value (one unit of its last digit).
double Resolution(const std::filesystem::path& path, int line, std::string_view tok) {
  const double r = PrintedResolution(tok);
  if (!(r >= 0.0)) {
    throw SceneError(Where(path, line) + ": expected a decimal number (e.g. -.1234567E-02), got '" +
                     Excerpt(tok) + "'");
  }
  return r;
}

std::string Upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string Trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t\v\f");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\v\f") + 1 - a);
}

// The dimension of a units spelling in an AT2 header.
enum class Dimension { kAcceleration, kVelocity, kLength };

struct UnitsSpelling {
  const char* spelling;  // normalised: upper case, SEC -> S, ** -> ^
  Dimension dimension;
  std::optional<AccelUnits> accel;  // the acceleration units rockbench reads it as
};

constexpr std::string_view kKnownAccelUnits =
    "G, CM/S/S (or CM/SEC/SEC, CM/S^2, CM/S2, GAL) or M/S/S (or M/S^2, M/S2)";

const std::vector<UnitsSpelling>& Spellings() {
  static const std::vector<UnitsSpelling> kSpellings = {
      {"G", Dimension::kAcceleration, AccelUnits::kG},
      {"CM/S/S", Dimension::kAcceleration, AccelUnits::kCmps2},
      {"CM/S^2", Dimension::kAcceleration, AccelUnits::kCmps2},
      {"CM/S2", Dimension::kAcceleration, AccelUnits::kCmps2},
      {"GAL", Dimension::kAcceleration, AccelUnits::kCmps2},
      {"GALS", Dimension::kAcceleration, AccelUnits::kCmps2},
      {"M/S/S", Dimension::kAcceleration, AccelUnits::kMps2},
      {"M/S^2", Dimension::kAcceleration, AccelUnits::kMps2},
      {"M/S2", Dimension::kAcceleration, AccelUnits::kMps2},
      {"MM/S/S", Dimension::kAcceleration, std::nullopt},
      {"MM/S^2", Dimension::kAcceleration, std::nullopt},
      {"MM/S2", Dimension::kAcceleration, std::nullopt},
      {"IN/S/S", Dimension::kAcceleration, std::nullopt},
      {"IN/S^2", Dimension::kAcceleration, std::nullopt},
      {"IN/S2", Dimension::kAcceleration, std::nullopt},
      {"FT/S/S", Dimension::kAcceleration, std::nullopt},
      {"FT/S^2", Dimension::kAcceleration, std::nullopt},
      {"FT/S2", Dimension::kAcceleration, std::nullopt},
      {"CM/S", Dimension::kVelocity, std::nullopt},
      {"M/S", Dimension::kVelocity, std::nullopt},
      {"MM/S", Dimension::kVelocity, std::nullopt},
      {"IN/S", Dimension::kVelocity, std::nullopt},
      {"FT/S", Dimension::kVelocity, std::nullopt},
      {"CM", Dimension::kLength, std::nullopt},
      {"M", Dimension::kLength, std::nullopt},
      {"MM", Dimension::kLength, std::nullopt},
      {"IN", Dimension::kLength, std::nullopt},
      {"FT", Dimension::kLength, std::nullopt},
  };
  return kSpellings;
}

// Upper case, SEC -> S, ** -> ^: "cm/sec**2" -> "CM/S^2".
std::string NormaliseUnits(std::string u) {
  u = Upper(std::move(u));
  for (size_t at = u.find("SEC"); at != std::string::npos; at = u.find("SEC", at)) {
    u.replace(at, 3, "S");
  }
  for (size_t at = u.find("**"); at != std::string::npos; at = u.find("**", at)) {
    u.replace(at, 2, "^");
  }
  return u;
}

// Reads the header line of an AT2 file that declares the quantity and units, if any, into
// rec; refuses velocity, displacement and units it does not know.
void ReadUnitsLine(const std::filesystem::path& path, const Line& line, RecordData& rec,
                   bool& found) {
  const auto icase = std::regex::ECMAScript | std::regex::icase;
  static const std::regex kQuantity(R"(\b(ACCELERATION|ACCEL|VELOCITY|DISPLACEMENT)\b)", icase);
  static const std::regex kUnitsOf(R"(\bUNITS\s+OF\s+(\S+))", icase);
  static const std::regex kIn(R"(\b(?:ACCELERATION|ACCEL|VELOCITY|DISPLACEMENT)\b.*?\bIN\s+(\S+))",
                              icase);
  static const std::regex kSeries(
      R"(\b(VELOCITY|DISPLACEMENT)\s+(TIME\s+(SERIES|HISTORY)|RECORD|TRACE)\b)", icase);
  const std::string& text = line.text;
  const std::string quoted = "\"" + Excerpt(Trim(text), 100) + "\"";
  std::smatch quantity_m, units_m;
  const bool has_quantity = std::regex_search(text, quantity_m, kQuantity);
  const std::string quantity = has_quantity ? Upper(quantity_m[1]) : "";
  const bool has_units = std::regex_search(text, units_m, kUnitsOf) ||
                         (has_quantity && std::regex_search(text, units_m, kIn));
  const std::string refuse =
      "; rockbench reads acceleration (expected an acceleration record, PEER's .AT2, not the "
      ".VT2 velocity or .DT2 displacement file)";
  if (!has_units) {
    // "VELOCITY TIME SERIES" without units still says what the file holds.
    if (std::regex_search(text, kSeries)) {
      throw SceneError(Where(path, line.number) + ": the header says " + quoted + refuse);
    }
    return;
  }
  found = true;
  if (quantity == "VELOCITY" || quantity == "DISPLACEMENT") {
    throw SceneError(Where(path, line.number) + ": the header says " + quoted + refuse);
  }
  std::string written = units_m[1];
  // Punctuation around the units: "UNITS OF G. FILTER POINTS: ...", "UNITS OF G,", "(G)".
  while (!written.empty() && std::string_view(".,;:)").find(written.back()) != std::string::npos) {
    written.pop_back();
  }
  if (!written.empty() && written.front() == '(') written.erase(0, 1);
  const std::string units = NormaliseUnits(written);
  const UnitsSpelling* spelling = nullptr;
  for (const UnitsSpelling& s : Spellings()) {
    if (units == s.spelling) spelling = &s;
  }
  const std::string expected =
      std::string(" (expected acceleration in ") + std::string(kKnownAccelUnits) + ")";
  if (spelling == nullptr) {
    throw SceneError(Where(path, line.number) + ": the header says " + quoted +
                     ": unknown units \"" + Excerpt(written) + "\"" + expected);
  }
  if (spelling->dimension == Dimension::kVelocity) {
    throw SceneError(Where(path, line.number) + ": the header says " + quoted + ": \"" + written +
                     "\" is a velocity unit" + refuse);
  }
  if (spelling->dimension == Dimension::kLength) {
    throw SceneError(Where(path, line.number) + ": the header says " + quoted + ": \"" + written +
                     "\" is a length (displacement) unit" + refuse);
  }
  if (!spelling->accel) {
    throw SceneError(Where(path, line.number) + ": the header says " + quoted +
                     ": rockbench does not read acceleration in \"" + written + "\"" + expected);
  }
  rec.header_units = spelling->accel;
  rec.units_line = line.number;
  rec.units_text = Trim(text);
}

}  // namespace

double PrintedResolution(std::string_view tok) {
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  size_t i = 0;
  const size_t n = tok.size();
  const auto digit = [&](size_t k) { return k < n && tok[k] >= '0' && tok[k] <= '9'; };
  if (i < n && (tok[i] == '+' || tok[i] == '-')) ++i;
  long digits = 0, decimals = 0;
  while (digit(i)) ++i, ++digits;
  if (i < n && tok[i] == '.') {
    ++i;
    while (digit(i)) ++i, ++decimals;
  }
  if (digits + decimals == 0) return kNan;
  long exponent = 0;
  if (i < n && (tok[i] == 'e' || tok[i] == 'E')) {
    ++i;
    bool negative = false;
    if (i < n && (tok[i] == '+' || tok[i] == '-')) negative = tok[i++] == '-';
    if (!digit(i)) return kNan;
    const auto res = std::from_chars(tok.data() + i, tok.data() + n, exponent);
    if (res.ec != std::errc()) return kNan;
    i = static_cast<size_t>(res.ptr - tok.data());
    if (negative) exponent = -exponent;
  }
  if (i != n) return kNan;
  // The nearest double to 10^k, as the decimal literal "1e<k>" reads.
  const long k = exponent - decimals;
  const std::string power = "1e" + std::to_string(k);
  double r = 0.0;
  const auto res = std::from_chars(power.data(), power.data() + power.size(), r);
  if (res.ec == std::errc::result_out_of_range) {
    return k < 0 ? 0.0 : std::numeric_limits<double>::infinity();
  }
  return r;
}

RecordData ReadAt2(const std::filesystem::path& path) {
  return ParseAt2(ReadRecordText(path), path);
}

RecordData ParseAt2(const std::string& text, const std::filesystem::path& path) {
  const std::vector<Line> lines = SplitLines(path, text);
  // The NPTS/DT line is among the first lines (3 header lines in PEER files, 6 in some).
  constexpr int kHeaderSearchLines = 12;
  size_t header = lines.size();
  for (size_t i = 0; i < lines.size() && lines[i].number <= kHeaderSearchLines; ++i) {
    std::string upper = lines[i].text;
    for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (upper.find("NPTS") != std::string::npos) {
      header = i;
      break;
    }
  }
  if (header == lines.size()) {
    throw SceneError(path.string() + ": no NPTS/DT header line in the first " +
                     std::to_string(kHeaderSearchLines) +
                     " lines (expected e.g. 'NPTS=  4000, DT= .01000 SEC' or "
                     "'3930 0.00500 NPTS, DT')");
  }
  // Header lines are matched with std::regex, whose executor recurses once per character:
  // a header line of tens of kB overflowed the stack. PEER's are under 100 characters.
  constexpr size_t kMaxHeaderLine = 1024;
  for (size_t i = 0; i <= header; ++i) {
    if (lines[i].text.size() > kMaxHeaderLine) {
      throw SceneError(Where(path, lines[i].number) + ": header line of " +
                       std::to_string(lines[i].text.size()) + " characters ('" +
                       Excerpt(lines[i].text) + "'); expected at most " +
                       std::to_string(kMaxHeaderLine) + " (PEER's are under 100)");
    }
  }
  const Line& h = lines[header];
  const auto icase = std::regex::ECMAScript | std::regex::icase;
  static const std::regex kNpts(R"(NPTS\s*=\s*([-+0-9.Ee]+))", icase);
  static const std::regex kDt(R"(\bDT\s*=\s*([-+0-9.Ee]+))", icase);
  static const std::regex kTrailer(R"(^\s*([-+0-9.Ee]+)\s+([-+0-9.Ee]+)\s+NPTS\s*,\s*DT)", icase);
  std::smatch npts_m, dt_m;
  std::string npts_text, dt_text;
  if (std::regex_search(h.text, npts_m, kNpts) && std::regex_search(h.text, dt_m, kDt)) {
    npts_text = npts_m[1];
    dt_text = dt_m[1];
  } else if (std::regex_search(h.text, npts_m, kTrailer)) {
    npts_text = npts_m[1];
    dt_text = npts_m[2];
  } else {
    throw SceneError(Where(path, h.number) + ": cannot read NPTS and DT from '" +
                     Excerpt(h.text, 100) +
                     "' (expected 'NPTS= n, DT= dt SEC' or 'n dt NPTS, DT')");
  }
  RecordData rec;
  rec.format = "AT2";
  long long npts = 0;
  {
    const char* end = npts_text.data() + npts_text.size();
    auto res = std::from_chars(npts_text.data(), end, npts);
    if (res.ec != std::errc() || res.ptr != end || npts <= 0) {
      throw SceneError(Where(path, h.number) + ": expected NPTS as a positive whole number, got '" +
                       Excerpt(npts_text) + "'");
    }
    // Every value takes at least two bytes (a digit and a separator): a larger NPTS cannot be
    // in the file, and would only reserve memory.
    const auto room = static_cast<long long>(text.size() / 2 + 1);
    if (npts > room) {
      throw SceneError(Where(path, h.number) + ": NPTS = " + std::to_string(npts) +
                       " values cannot fit in the file's " + std::to_string(text.size()) +
                       " bytes (expected the number of samples that follow)");
    }
  }
  if (!ParseNumber(dt_text, rec.dt_s) || !std::isfinite(rec.dt_s) || rec.dt_s <= 0.0) {
    throw SceneError(Where(path, h.number) + ": expected a positive DT (s), got '" +
                     Excerpt(dt_text) + "'");
  }
  if (const std::string problem = SampleIntervalProblem(rec.dt_s); !problem.empty()) {
    throw SceneError(Where(path, h.number) + ": DT = " + Excerpt(dt_text) + " s: " + problem);
  }
  if (static_cast<double>(npts - 1) * rec.dt_s > limits::kMaxDuration_s) {
    throw SceneError(Where(path, h.number) + ": NPTS = " + std::to_string(npts) +
                     " at DT = " + Excerpt(dt_text) + " s lasts more than a day (" +
                     ShortestText(limits::kMaxDuration_s) + " s; docs/limits.md)");
  }
  // The first header line (up to the NPTS line) that declares the units.
  bool units_found = false;
  for (size_t i = 0; i <= header && !units_found; ++i) {
    ReadUnitsLine(path, lines[i], rec, units_found);
  }
  // Every numeric token after the header line, whatever the count per line.
  rec.values.reserve(static_cast<size_t>(npts));
  rec.resolution.reserve(static_cast<size_t>(npts));
  rec.lines.reserve(static_cast<size_t>(npts));
  int last_line = h.number;
  for (size_t i = header + 1; i < lines.size(); ++i) {
    for (std::string_view tok : Tokens(lines[i].text, false)) {
      if (static_cast<long long>(rec.values.size()) == npts) {
        throw SceneError(Where(path, lines[i].number) + ": more values than NPTS = " +
                         std::to_string(npts) + " (header line " + std::to_string(h.number) +
                         "): value " + std::to_string(npts + 1) + " is '" + Excerpt(tok) + "'");
      }
      rec.values.push_back(Value(path, lines[i].number, tok));
      rec.lines.push_back(lines[i].number);
      rec.resolution.push_back(Resolution(path, lines[i].number, tok));
    }
    last_line = lines[i].number;
  }
  if (static_cast<long long>(rec.values.size()) != npts) {
    throw SceneError(Where(path, last_line) + ": read " + std::to_string(rec.values.size()) +
                     " values but the header (line " + std::to_string(h.number) +
                     ") says NPTS = " + std::to_string(npts) + "; the file ends here");
  }
  return rec;
}

RecordData ReadPlain(const std::filesystem::path& path, double dt_s) {
  return ParsePlain(ReadRecordText(path), path, dt_s);
}

namespace {

// The rows of a plain record: its samples (and their resolution and lines) in `rec`, the time
// column's values in `times` when it has one, the file line of each sample; returns the number
// of columns (1: a, 2: t, a).
size_t ReadPlainRows(const std::string& text, const std::filesystem::path& path, RecordData* out,
                     std::vector<double>* times_out, std::vector<int>* lines_out) {
  RecordData& rec = *out;
  std::vector<double>& times = *times_out;
  std::vector<int>& line_of = *lines_out;
  const std::vector<Line> lines = SplitLines(path, text);
  size_t columns = 0;
  int first_data_line = 0;
  for (const Line& line : lines) {
    const std::vector<std::string_view> toks = Tokens(line.text, true);
    if (toks.empty()) continue;
    if (columns == 0) {
      // Header lines (any non-numeric token) are allowed until the first numeric line.
      bool numeric = true;
      for (std::string_view tok : toks) {
        double v = 0.0;
        numeric = numeric && ParseNumber(tok, v);
      }
      if (!numeric) continue;
      columns = toks.size();
      first_data_line = line.number;
      if (columns != 1 && columns != 2) {
        throw SceneError(Where(path, line.number) +
                         ": expected 1 column (a) or 2 columns (t, a), got " +
                         std::to_string(columns));
      }
    }
    // Numbers first (a stray text line says so), then the column count.
    std::vector<double> row;
    for (std::string_view tok : toks) row.push_back(Value(path, line.number, tok));
    if (row.size() != columns) {
      throw SceneError(Where(path, line.number) + ": expected " + std::to_string(columns) +
                       " column(s) like line " + std::to_string(first_data_line) + ", got " +
                       std::to_string(row.size()));
    }
    if (columns == 2) times.push_back(row[0]);
    rec.values.push_back(row.back());
    rec.resolution.push_back(Resolution(path, line.number, toks.back()));
    line_of.push_back(line.number);
    rec.lines.push_back(line.number);
  }
  if (rec.values.empty()) throw SceneError(path.string() + ": no numeric data found");
  return columns;
}

// A one-column record: the scene gives its sample interval dt.
RecordData OneColumnRecord(RecordData rec, const std::filesystem::path& path, double dt_s) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw SceneError(path.string() +
                     ": a one-column file needs the sample interval: set dt = ... (s) in the "
                     "scene's [base.*] table");
  }
  if (const std::string problem = SampleIntervalProblem(dt_s); !problem.empty()) {
    throw SceneError(path.string() + ": dt = " + ShortestText(dt_s) + " s: " + problem);
  }
  if (static_cast<double>(rec.values.size() - 1) * dt_s > limits::kMaxDuration_s) {
    throw SceneError(path.string() + ": " + std::to_string(rec.values.size()) +
                     " samples at dt = " + ShortestText(dt_s) + " s last more than a day (" +
                     ShortestText(limits::kMaxDuration_s) + " s; docs/limits.md)");
  }
  rec.format = "plain-1col";
  rec.dt_s = dt_s;
  return rec;
}

// A two-column record (t, a): the interval is the time column's, uniform to 0.1% of it.
RecordData TimeColumnRecord(RecordData rec, const std::vector<double>& times,
                            const std::vector<int>& line_of, const std::filesystem::path& path,
                            double dt_s) {
  rec.format = "plain-2col";
  if (dt_s > 0.0) {
    throw SceneError(path.string() +
                     ": the file has a time column (t, a), so dt must not be given in the scene");
  }
  const size_t n = times.size();
  if (n < 2) {
    throw SceneError(Where(path, line_of[0]) +
                     ": a two-column file needs at least 2 rows to define the time step");
  }
  // Every time within a day of zero, and the step a sample interval a record can have.
  for (size_t i = 0; i < n; ++i) {
    if (std::abs(times[i]) > limits::kMaxDuration_s) {
      throw SceneError(Where(path, line_of[i]) + ": time " + ShortestText(times[i]) +
                       " s; expected a time with magnitude at most " +
                       ShortestText(limits::kMaxDuration_s) + " s (a day; docs/limits.md)");
    }
  }
  rec.t0_s = times.front();
  // Uniform spacing: every step within 0.1% of the first step, and every time within 0.1% of dt
  // of the uniform grid through the first and last times. Times printed to 4 or more
  // significant digits of dt pass exactly; 0.1% of dt moves a sample by far less than the
  // interpolation error of a record.
  const double first_step = times[1] - times[0];
  for (size_t i = 1; i < n; ++i) {
    const double step = times[i] - times[i - 1];
    if (!(step > 0.0)) {
      std::ostringstream msg;
      msg.precision(10);
      msg << Where(path, line_of[i]) << ": the time column does not increase: t = " << times[i]
          << " after t = " << times[i - 1];
      throw SceneError(msg.str());
    }
    if (std::abs(step - first_step) > 1e-3 * first_step) {
      std::ostringstream msg;
      msg.precision(10);
      msg << Where(path, line_of[i])
          << ": the time column is not uniformly spaced: t = " << times[i]
          << " after t = " << times[i - 1] << " is a step of " << step
          << " s, but the first step (line " << line_of[1] << ") is " << first_step << " s";
      throw SceneError(msg.str());
    }
  }
  if (const std::string problem = SampleIntervalProblem(times[1] - times[0]); !problem.empty()) {
    throw SceneError(Where(path, line_of[1]) + ": the time step " +
                     ShortestText(times[1] - times[0]) + " s: " + problem);
  }
  rec.dt_s = (times.back() - times.front()) / static_cast<double>(n - 1);
  for (size_t i = 1; i < n; ++i) {
    const double grid = rec.t0_s + static_cast<double>(i) * rec.dt_s;
    if (std::abs(times[i] - grid) > 1e-3 * rec.dt_s) {
      std::ostringstream msg;
      msg.precision(10);
      msg << Where(path, line_of[i])
          << ": the time column is not uniformly spaced: t = " << times[i]
          << " is off the uniform grid (t = " << grid << ", dt = " << rec.dt_s
          << " s from the first and last times)";
      throw SceneError(msg.str());
    }
  }
  return rec;
}

}  // namespace

RecordData ParsePlain(const std::string& text, const std::filesystem::path& path, double dt_s) {
  RecordData rec;
  std::vector<double> times;
  std::vector<int> line_of;  // file line of each sample
  const size_t columns = ReadPlainRows(text, path, &rec, &times, &line_of);
  if (columns == 1) return OneColumnRecord(std::move(rec), path, dt_s);
  return TimeColumnRecord(std::move(rec), times, line_of, path, dt_s);
}

RecordData SampledRecord(const std::vector<double>& values, double dt_s, const std::string& key) {
  if (values.size() < 2) {
    throw SceneError(key +
                     ".samples: expected at least 2 samples (a record lasts from its first "
                     "sample to its last), got " +
                     std::to_string(values.size()));
  }
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw SceneError(key + ".dt: samples need their sample interval: a positive number (s), got " +
                     ShortestText(dt_s));
  }
  if (const std::string problem = SampleIntervalProblem(dt_s); !problem.empty()) {
    throw SceneError(key + ".dt: dt = " + ShortestText(dt_s) + " s: " + problem);
  }
  if (static_cast<double>(values.size() - 1) * dt_s > limits::kMaxDuration_s) {
    throw SceneError(key + ".samples: " + std::to_string(values.size()) +
                     " samples at dt = " + ShortestText(dt_s) + " s last more than a day (" +
                     ShortestText(limits::kMaxDuration_s) + " s; docs/limits.md)");
  }
  RecordData rec;
  rec.format = "samples";
  rec.dt_s = dt_s;
  rec.values.reserve(values.size());
  rec.resolution.reserve(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw SceneError(key + ".samples[" + std::to_string(i) + "]: expected a finite number, got " +
                       ShortestText(values[i]));
    }
    // The resolution a one-column file of the shortest texts has: the same reading of a token.
    rec.values.push_back(values[i]);
    rec.resolution.push_back(PrintedResolution(ShortestText(values[i])));
  }
  return rec;
}

}  // namespace rockbench
