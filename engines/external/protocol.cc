#include "engines/external/protocol.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <new>
#include <ostream>
#include <string_view>

#include "scene/rigid_block.h"
#include "scene/stack_pose.h"

namespace rockbench::external {
namespace {

nlohmann::json NumberOrNull(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// The scene's base-motion component as the input states it: its analytic form, or the record
// it was read from.
nlohmann::json MotionJson(const MotionDef& m) {
  nlohmann::json j;
  j["kind"] = std::string(MotionKindName(m.kind));
  j["scale"] = m.scale;
  if (m.kind == MotionKind::kFile || m.kind == MotionKind::kKanaiTajimi) {
    // A record given by its samples has no file: the input's sampled motion is the record.
    if (m.kind == MotionKind::kFile && !m.from_samples()) j["file"] = m.file.filename().string();
    j["analytic"] = false;
    return j;
  }
  j["analytic"] = true;
  j["amplitude_g"] = m.amplitude_g;
  j["frequency_hz"] = m.frequency_hz;
  j["duration_s"] = NumberOrNull(m.duration_s);
  j["start_s"] = m.start_s;
  return j;
}

[[noreturn]] void Fail(const std::string& engine, const std::filesystem::path& file, int64_t line,
                       const std::string& msg) {
  throw ExternalEngineError(engine + ": " + file.string() +
                            (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + msg);
}

// Text of the poses file as a message shows it: printable ASCII as is, any other byte as \xNN
// (a NUL, an escape sequence), at most 60 characters and then how long it was.
std::string Shown(std::string_view text) {
  constexpr size_t kShownChars = 60;
  std::string out;
  for (size_t i = 0; i < text.size() && i < kShownChars; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  if (text.size() > kShownChars) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

// What a path that is not a regular file is, for a message.
std::string FileKind(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

// The whole poses file, read in place (a run of 1e5 rows is 20 MB). The path is opened without
// blocking (a FIFO without a writer would block the open, and its read) and refused unless the
// opened file is a regular file of at most `max_bytes`.
std::string ReadPosesText(const std::string& engine, const std::filesystem::path& file,
                          std::int64_t max_bytes, const std::string& max_why) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int err = errno;
    if (err == ENOENT) {
      Fail(engine, file, 0,
           "no poses file: the engine ended without writing it (it must write the input's "
           "poses_file)");
    }
    struct stat st {};
    if (::stat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
      Fail(engine, file, 0,
           "not a regular file (" + FileKind(st.st_mode) +
               "): the engine must write its poses to the input's poses_file as a regular file");
    }
    Fail(engine, file, 0, std::string("cannot open the poses file: ") + std::strerror(err));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    Fail(engine, file, 0, std::string("cannot read the poses file: ") + std::strerror(errno));
  }
  if (!S_ISREG(st.st_mode)) {
    Fail(engine, file, 0,
         "not a regular file (" + FileKind(st.st_mode) +
             "): the engine must write its poses to the input's poses_file as a regular file");
  }
  if (st.st_size > max_bytes) {
    Fail(engine, file, 0,
         std::to_string(static_cast<long long>(st.st_size)) + " bytes, more than the " +
             std::to_string(max_bytes) + " a poses file of this run can hold (" + max_why + ")");
  }
  // Back to blocking reads: a regular file's never wait.
  std::string text(static_cast<size_t>(st.st_size), '\0');
  size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      Fail(engine, file, 0, std::string("cannot read the poses file: ") + std::strerror(errno));
    }
    if (n == 0) break;  // shorter than its size said: what is there is read
    got += static_cast<size_t>(n);
  }
  text.resize(got);
  return text;
}

// Splits a CSV line on commas (no quoting: the protocol's fields are names and numbers).
void SplitFields(const std::string& line, std::vector<std::string>* out) {
  out->clear();
  size_t start = 0;
  for (;;) {
    const size_t comma = line.find(',', start);
    std::string f =
        line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    while (!f.empty() && (f.back() == ' ' || f.back() == '\r' || f.back() == '\t')) f.pop_back();
    size_t lead = 0;
    while (lead < f.size() && (f[lead] == ' ' || f[lead] == '\t')) ++lead;
    out->push_back(f.substr(lead));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
}

// Parses a row of `columns` comma-separated numbers (spaces around them allowed) into *v.
// False, with *v cleared, for anything else: the caller then finds and names the fault.
bool ParseNumbers(std::string_view row, size_t columns, std::vector<double>* v) {
  v->clear();
  const char* p = row.data();
  const char* end = row.data() + row.size();
  while (true) {
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    if (p < end && *p == '+') ++p;
    double x = 0.0;
    const auto [next, ec] = std::from_chars(p, end, x);
    if (ec != std::errc() || next == p) {
      v->clear();
      return false;
    }
    v->push_back(x);
    p = next;
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    if (p == end) break;
    if (*p != ',') {
      v->clear();
      return false;
    }
    ++p;
  }
  if (v->size() != columns) {
    v->clear();
    return false;
  }
  return true;
}

// The time field of a row as written.
std::string TimeText(std::string_view row, int t_col) {
  std::string line(row);
  std::vector<std::string> fields;
  SplitFields(line, &fields);
  return t_col >= 0 && static_cast<size_t>(t_col) < fields.size()
             ? fields[static_cast<size_t>(t_col)]
             : std::string();
}

// The input of InputJson, once its size is checked.
nlohmann::json InputJsonOf(const std::string& engine, const Scene& scene, const EngineInput& input,
                           const EngineSettings& settings, std::int64_t every,
                           const std::filesystem::path& poses_file,
                           const std::filesystem::path& contacts_file);

}  // namespace

std::int64_t ExpectedRows(std::int64_t steps, std::int64_t every) {
  return steps / every + 1 + (steps % every != 0 ? 1 : 0);
}

std::int64_t MaxPosesBytes(const EngineInput& input, std::int64_t every) {
  const double bytes = static_cast<double>(ExpectedRows(input.steps, every)) *
                           (1.0 + 6.0 * input.block_count()) *
                           static_cast<double>(kMaxPosesFieldBytes) +
                       static_cast<double>(kPosesHeaderBytes);
  return bytes >= 9e18 ? std::numeric_limits<std::int64_t>::max()
                       : static_cast<std::int64_t>(bytes);
}

std::int64_t RowStep(std::int64_t j, std::int64_t steps, std::int64_t every) {
  return std::min(j * every, steps);
}

nlohmann::json InputJson(const std::string& engine, const Scene& scene, const EngineInput& input,
                         const EngineSettings& settings, std::int64_t every,
                         const std::filesystem::path& poses_file,
                         const std::filesystem::path& contacts_file) {
  const bool has_drive = !input.drive.ax_mps2.empty() || !input.drive.ay_mps2.empty() ||
                         !input.drive.ux_m.empty() || !input.drive.uy_m.empty();
  if (has_drive && input.steps > kMaxInputSteps) {
    throw ExternalEngineError(
        engine + ": " + engine + ".time_step: a step of " + ShortestText(input.time_step_s) +
        " s is " + std::to_string(input.steps) +
        " steps, each a row of the input's base motion, more than the " +
        std::to_string(kMaxInputSteps) + " an external engine's input may hold (docs/limits.md)");
  }
  try {
    return InputJsonOf(engine, scene, input, settings, every, poses_file, contacts_file);
  } catch (const std::bad_alloc&) {
  } catch (const std::length_error&) {
  }
  throw ExternalEngineError(engine + ": out of memory building the input file of " +
                            std::to_string(input.steps) + " steps (" + engine + ".time_step " +
                            ShortestText(input.time_step_s) + " s)");
}

namespace {

nlohmann::json InputJsonOf(const std::string& engine, const Scene& scene, const EngineInput& input,
                           const EngineSettings& settings, std::int64_t every,
                           const std::filesystem::path& poses_file,
                           const std::filesystem::path& contacts_file) {
  nlohmann::json j;
  j["protocol"] = "rockbench-external-engine";
  j["protocol_version"] = 1;
  j["engine"] = engine;
  j["poses_file"] = poses_file.string();
  j["contacts_file"] = contacts_file.string();
  j["units"] = "SI: m, kg, s, rad; angles counter-clockwise about +z";
  j["dimensions"] = 2;
  j["gravity_mps2"] = input.run.gravity_mps2;
  j["time_step_s"] = input.time_step_s;
  j["steps"] = input.steps;
  j["duration_s"] = static_cast<double>(input.steps) * input.time_step_s;
  j["output_every_steps"] = every;
  j["output_interval_s"] = static_cast<double>(every) * input.time_step_s;
  j["rows"] = ExpectedRows(input.steps, every);
  j["overturn_rad"] = input.overturn_rad;
  j["ground"] = {{"top_y_m", 0.0}, {"friction", NumberOrNull(input.blocks[0].friction)}};
  const StackPlacement placed = PlaceStack(input.blocks, input.initial);
  nlohmann::json blocks = nlohmann::json::array();
  for (int k = 0; k < input.block_count(); ++k) {
    const BlockDef& b = input.blocks[static_cast<size_t>(k)];
    const BlockProps p = MakeBlockProps(b.width_m, b.height_m, b.mass_kg);
    const PlanarPose& pose = placed.blocks[static_cast<size_t>(k)];
    blocks.push_back({{"width_m", b.width_m},
                      {"height_m", b.height_m},
                      {"depth_m", b.depth_m},
                      {"mass_kg", b.mass_kg},
                      {"inertia_kgm2", p.I_G},
                      {"friction", NumberOrNull(b.friction)},
                      {"x_m", pose.x_m},
                      {"y_m", pose.y_m},
                      {"angle_rad", pose.phi_rad},
                      {"vx_mps", pose.vx_mps},
                      {"vy_mps", pose.vy_mps},
                      {"omega_radps", pose.w_radps}});
  }
  j["blocks"] = std::move(blocks);
  // The pairs that touch: each block on its support, and with two blocks block 2 on the ground
  // once it has fallen off (as every built-in engine has it).
  nlohmann::json pairs = nlohmann::json::array();
  for (int k = 0; k < input.block_count(); ++k) {
    pairs.push_back({{"lower", k},
                     {"upper", k + 1},
                     {"friction", NumberOrNull(input.blocks[static_cast<size_t>(k)].friction)}});
  }
  if (input.block_count() == 2) {
    pairs.push_back(
        {{"lower", 0}, {"upper", 2}, {"friction", NumberOrNull(input.blocks[1].friction)}});
  }
  j["contact_pairs"] = std::move(pairs);
  nlohmann::json drive;
  drive["kind"] = DriveKindName(input.drive_kind);
  if (input.drive_kind == DriveKind::kInertial) {
    drive["ax_mps2"] = input.drive.ax_mps2;
    drive["ay_mps2"] = input.drive.ay_mps2;
  } else {
    drive["ux_m"] = input.drive.ux_m;
    drive["uy_m"] = input.drive.uy_m;
    drive["ux0_mps"] = input.drive.ux0_mps;
    drive["uy0_mps"] = input.drive.uy0_mps;
  }
  j["drive"] = std::move(drive);
  nlohmann::json base = nlohmann::json::object();
  if (scene.horizontal) base["horizontal"] = MotionJson(*scene.horizontal);
  if (scene.vertical) base["vertical"] = MotionJson(*scene.vertical);
  j["base_motion"] = std::move(base);
  j["settings"] = settings.ToJson();
  return j;
}

}  // namespace

void WritePoses(std::ostream& out, const std::vector<StepReadout>& rows) {
  if (rows.empty()) return;
  const size_t blocks = rows.front().blocks.size();
  out << "t_s";
  for (size_t k = 1; k <= blocks; ++k) {
    const std::string i = std::to_string(k);
    out << ",x" << i << "_m,y" << i << "_m,angle" << i << "_rad,vx" << i << "_mps,vy" << i
        << "_mps,omega" << i << "_radps";
  }
  out << '\n';
  for (const StepReadout& r : rows) {
    out << ShortestText(r.t_s);
    for (const BodyReadout& b : r.blocks) {
      out << ',' << ShortestText(b.x_m) << ',' << ShortestText(b.y_m) << ','
          << ShortestText(std::atan2(b.sin_phi, b.cos_phi)) << ',' << ShortestText(b.vx_mps) << ','
          << ShortestText(b.vy_mps) << ',' << ShortestText(b.w_radps);
    }
    out << '\n';
  }
}

EngineInput MonitorInput(const EngineInput& input, std::int64_t every) {
  if (every == 1) return input;
  EngineInput m = input;
  const std::int64_t rows = ExpectedRows(input.steps, every);
  m.time_step_s = input.time_step_s * static_cast<double>(every);
  m.steps = rows - 1;
  if (input.drive_kind == DriveKind::kInertial) {
    // Window j (rows j to j + 1) keeps its largest acceleration: whether the base moved in it.
    auto window_peak = [&](const std::vector<double>& a) {
      std::vector<double> out;
      if (a.empty()) return out;
      for (std::int64_t j = 0; j + 1 < rows; ++j) {
        double peak = 0.0;
        for (std::int64_t n = RowStep(j, input.steps, every);
             n < RowStep(j + 1, input.steps, every); ++n) {
          const double v = a[static_cast<size_t>(n)];
          if (std::abs(v) > std::abs(peak)) peak = v;
        }
        out.push_back(peak);
      }
      return out;
    };
    m.drive.ax_mps2 = window_peak(input.drive.ax_mps2);
    m.drive.ay_mps2 = window_peak(input.drive.ay_mps2);
  } else {
    m.drive.ux_m.clear();
    m.drive.uy_m.clear();
    for (std::int64_t j = 0; j < rows; ++j) {
      const size_t n = static_cast<size_t>(RowStep(j, input.steps, every));
      m.drive.ux_m.push_back(input.drive.ux_m[n]);
      m.drive.uy_m.push_back(input.drive.uy_m[n]);
    }
  }
  return m;
}

namespace {

// The quantities of a block's columns, and their names: x1_m, angle2_rad, omega3_radps.
enum Quantity { kX, kY, kAngle, kVx, kVy, kOmega, kQuantities };
constexpr const char* kSuffix[kQuantities] = {"_m", "_m", "_rad", "_mps", "_mps", "_radps"};
constexpr const char* kStem[kQuantities] = {"x", "y", "angle", "vx", "vy", "omega"};

// Which field of a row holds what (-1: absent), from the header.
struct PoseColumns {
  std::vector<std::array<int, kQuantities>> col;  ///< per block, per quantity
  int t_col = -1;
  bool velocities_given = false;  ///< every block's vx, vy and omega
};

// The header's columns for a stack of `blocks`; fails naming an unknown, repeated or missing
// column, and velocities given for some blocks or quantities only.
PoseColumns ReadHeader(const std::string& engine, const std::filesystem::path& file,
                       std::int64_t line_no, const std::vector<std::string>& fields, int blocks) {
  PoseColumns h;
  h.col.resize(static_cast<size_t>(blocks));
  for (auto& c : h.col) c.fill(-1);
  std::map<std::string, std::pair<int, int>> names;  // column name -> (block, quantity)
  for (int k = 0; k < blocks; ++k) {
    for (int q = 0; q < kQuantities; ++q) {
      names[std::string(kStem[q]) + std::to_string(k + 1) + kSuffix[q]] = {k, q};
    }
  }
  for (size_t i = 0; i < fields.size(); ++i) {
    const std::string& name = fields[i];
    if (name == "t_s") {
      h.t_col = static_cast<int>(i);
      continue;
    }
    auto it = names.find(name);
    if (it == names.end()) {
      Fail(engine, file, line_no,
           "unknown column '" + Shown(name) + "' (expected t_s and, for blocks 1 to " +
               std::to_string(blocks) +
               ", xK_m, yK_m, angleK_rad and optionally vxK_mps, vyK_mps, omegaK_radps)");
    }
    int& c = h.col[static_cast<size_t>(it->second.first)][static_cast<size_t>(it->second.second)];
    if (c >= 0) Fail(engine, file, line_no, "column '" + Shown(name) + "' appears twice");
    c = static_cast<int>(i);
  }
  if (h.t_col < 0) Fail(engine, file, line_no, "missing column 't_s' in the header");
  int with_velocity = 0;
  for (int k = 0; k < blocks; ++k) {
    for (int q = kX; q <= kAngle; ++q) {
      if (h.col[static_cast<size_t>(k)][static_cast<size_t>(q)] < 0) {
        Fail(engine, file, line_no,
             std::string("missing column '") + kStem[q] + std::to_string(k + 1) + kSuffix[q] +
                 "' in the header (the scene has " + std::to_string(blocks) + " blocks)");
      }
    }
    int given = 0;
    for (int q = kVx; q <= kOmega; ++q)
      given += h.col[static_cast<size_t>(k)][static_cast<size_t>(q)] >= 0;
    if (given != 0 && given != 3) {
      Fail(engine, file, line_no,
           "block " + std::to_string(k + 1) +
               " has some of vxK_mps, vyK_mps, omegaK_radps: give all three or none");
    }
    with_velocity += given == 3;
  }
  if (with_velocity != 0 && with_velocity != blocks) {
    Fail(engine, file, line_no, "velocities given for some blocks only: give them for all or none");
  }
  h.velocities_given = with_velocity == blocks;
  return h;
}

// The slow path of a row the fast one refused: its fields as numbers in *v (what strtod reads,
// a hexadecimal float say, is a number too), or a failure naming the row's fault.
void RowNumbers(const std::string& engine, const std::filesystem::path& file, std::int64_t line_no,
                const std::vector<std::string>& fields, size_t columns, std::vector<double>* v) {
  if (fields.size() != columns) {
    Fail(engine, file, line_no,
         std::to_string(fields.size()) + " fields, the header has " + std::to_string(columns) +
             " (a truncated row?)");
  }
  v->assign(columns, 0.0);
  for (size_t i = 0; i < columns; ++i) {
    char* stop = nullptr;
    // The whole field: strtod stops at a NUL byte as at the string's end.
    (*v)[i] = std::strtod(fields[i].c_str(), &stop);
    if (fields[i].empty() || stop != fields[i].c_str() + fields[i].size()) {
      Fail(engine, file, line_no,
           "column " + std::to_string(i + 1) + ": expected a number, got '" + Shown(fields[i]) +
               "'");
    }
  }
}

// A row's readout at t_expected from its numbers v. Without velocities the unwrapped angle
// rides in w_radps until DifferenceVelocities takes the differences.
StepReadout RowReadout(const PoseColumns& h, const std::vector<double>& v, int blocks,
                       double t_expected) {
  StepReadout r(blocks);
  r.t_s = t_expected;
  for (int k = 0; k < blocks; ++k) {
    const auto& c = h.col[static_cast<size_t>(k)];
    BodyReadout& b = r.blocks[static_cast<size_t>(k)];
    b.x_m = v[static_cast<size_t>(c[kX])];
    b.y_m = v[static_cast<size_t>(c[kY])];
    const double phi = v[static_cast<size_t>(c[kAngle])];
    b.cos_phi = std::cos(phi);
    b.sin_phi = std::sin(phi);
    b.w_radps = phi;
    if (h.velocities_given) {
      b.vx_mps = v[static_cast<size_t>(c[kVx])];
      b.vy_mps = v[static_cast<size_t>(c[kVy])];
      b.w_radps = v[static_cast<size_t>(c[kOmega])];
    }
  }
  return r;
}

// The velocities of the first n rows from their poses: central differences (one-sided at the
// ends), the angle as written (unwrapped by the engine or not: a jump of 2 pi is taken out);
// at t = 0 the input's velocities, which the engine started from.
void DifferenceVelocities(const EngineInput& input, size_t n, std::vector<StepReadout>* rows_in) {
  std::vector<StepReadout>& rows = *rows_in;
  const StackPlacement placed = PlaceStack(input.blocks, input.initial);
  std::vector<double> phi(n);
  for (int k = 0; k < input.block_count(); ++k) {
    const size_t kk = static_cast<size_t>(k);
    for (size_t i = 0; i < n; ++i) {
      phi[i] = rows[i].blocks[kk].w_radps;
      if (i > 0) {
        phi[i] -= 2.0 * M_PI * std::round((phi[i] - phi[i - 1]) / (2.0 * M_PI));
      }
    }
    const PlanarPose& p0 = placed.blocks[kk];
    rows[0].blocks[kk].vx_mps = p0.vx_mps;
    rows[0].blocks[kk].vy_mps = p0.vy_mps;
    rows[0].blocks[kk].w_radps = p0.w_radps;
    for (size_t i = 1; i < n; ++i) {
      const size_t a = i - 1, b = i + 1 == n ? i : i + 1;
      const double span = rows[b].t_s - rows[a].t_s;
      BodyReadout& r = rows[i].blocks[kk];
      if (span <= 0.0) {
        r.vx_mps = r.vy_mps = r.w_radps = 0.0;
        continue;
      }
      r.vx_mps = (rows[b].blocks[kk].x_m - rows[a].blocks[kk].x_m) / span;
      r.vy_mps = (rows[b].blocks[kk].y_m - rows[a].blocks[kk].y_m) / span;
      r.w_radps = (phi[b] - phi[a]) / span;
    }
  }
}

}  // namespace

PoseRows ReadPoses(const std::string& engine, const std::filesystem::path& file,
                   const EngineInput& input, std::int64_t every) {
  const int blocks = input.block_count();
  const std::int64_t expected = ExpectedRows(input.steps, every);
  PoseColumns h;
  PoseRows out;
  const std::string text =
      ReadPosesText(engine, file, MaxPosesBytes(input, every),
                    std::to_string(expected) + " rows x " + std::to_string(1 + 6 * blocks) +
                        " fields x " + std::to_string(kMaxPosesFieldBytes) + " bytes, and " +
                        std::to_string(kPosesHeaderBytes) + " for the header and comments");
  out.bytes = static_cast<std::int64_t>(text.size());
  std::string line;
  std::vector<std::string> fields, header_names;
  std::vector<double> v;
  std::int64_t line_no = 0;
  size_t columns = 0;
  bool header = false;
  const double out_dt = input.time_step_s * static_cast<double>(every);
  std::vector<StepReadout> rows;
  std::vector<std::int64_t> row_lines;  // the file line of each row
  double t_prev = -std::numeric_limits<double>::infinity();
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    std::string_view row(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!row.empty() && row.back() == '\r') row.remove_suffix(1);
    if (row.empty() || row[0] == '#') continue;
    if (header && ParseNumbers(row, columns, &v)) {
      // The fast path: every field a number (checked below for being finite).
    } else {
      line.assign(row);
      SplitFields(line, &fields);
    }
    if (!header) {
      header = true;
      columns = fields.size();
      header_names = fields;
      h = ReadHeader(engine, file, line_no, fields, blocks);
      out.velocities_given = h.velocities_given;
      rows.reserve(static_cast<size_t>(expected));
      continue;
    }
    const std::int64_t j = static_cast<std::int64_t>(rows.size());
    if (j >= expected) {
      Fail(engine, file, line_no,
           "more rows than the " + std::to_string(expected) + " promised (t = 0 to " +
               std::to_string(static_cast<double>(input.steps) * input.time_step_s) + " s)");
    }
    // The slow path found the fault: a row of another length, or a field that is no number.
    if (v.size() != columns) RowNumbers(engine, file, line_no, fields, columns, &v);
    const double t_expected =
        static_cast<double>(RowStep(j, input.steps, every)) * input.time_step_s;
    // A value that is not finite: the engine's state blew up. The row ends the run (its
    // readout carries the fault: the monitor stops there, status non_finite).
    std::string fault;
    for (size_t i = 0; i < columns && fault.empty(); ++i) {
      if (!std::isfinite(v[i])) {
        line.assign(row);
        SplitFields(line, &fields);
        fault = engine + ": " + file.string() + ":" + std::to_string(line_no) + ": column " +
                std::to_string(i + 1) + " (" + Shown(header_names[i]) + ") is '" +
                Shown(fields[i]) + "'";
      }
    }
    if (!fault.empty()) {
      StepReadout r = rows.empty() ? StepReadout(blocks) : rows.back();
      r.t_s = t_expected;
      r.engine_fault = fault;
      rows.push_back(std::move(r));
      out.stopped_at_line = line_no;
      break;
    }
    const double t = v[static_cast<size_t>(h.t_col)];
    if (t <= t_prev) {
      Fail(engine, file, line_no,
           "time " + Shown(TimeText(row, h.t_col)) + " s goes backwards (the row before is at " +
               std::to_string(t_prev) + " s)");
    }
    if (std::abs(t - t_expected) > 1e-3 * out_dt) {
      Fail(engine, file, line_no,
           "row " + std::to_string(j) + " is at t = " + Shown(TimeText(row, h.t_col)) +
               " s, expected " + std::to_string(t_expected) +
               " s (rows at every output_every_steps-th step from 0, then the last step)");
    }
    t_prev = t;
    rows.push_back(RowReadout(h, v, blocks, t_expected));
    row_lines.push_back(line_no);
  }
  if (!header) Fail(engine, file, line_no, "empty poses file: expected a header line");
  if (out.stopped_at_line == 0 && static_cast<std::int64_t>(rows.size()) < expected) {
    Fail(engine, file, line_no,
         std::to_string(rows.size()) + " rows, fewer than the " + std::to_string(expected) +
             " promised (t = 0 to " +
             std::to_string(static_cast<double>(input.steps) * input.time_step_s) + " s every " +
             std::to_string(out_dt) + " s)" +
             (rows.empty() ? std::string()
                           : "; the last is at t = " + std::to_string(rows.back().t_s) + " s"));
  }
  // The finite rows (a last row with a fault is not read by the monitor).
  const size_t finite = rows.size() - (out.stopped_at_line != 0 ? 1 : 0);
  if (!out.velocities_given && finite > 0) {
    DifferenceVelocities(input, finite, &rows);
    // Finite poses can still difference to a velocity that is not (positions near 1e308 m): the
    // first such row ends the run as a value that is not finite would.
    for (size_t i = 0; i < finite; ++i) {
      bool bad = false;
      for (const BodyReadout& b : rows[i].blocks) {
        bad = bad || !std::isfinite(b.vx_mps) || !std::isfinite(b.vy_mps) ||
              !std::isfinite(b.w_radps);
      }
      if (!bad) continue;
      rows.resize(i + 1);
      rows[i].engine_fault = engine + ": " + file.string() + ":" + std::to_string(row_lines[i]) +
                             ": the velocity differenced from the poses is not finite";
      out.stopped_at_line = row_lines[i];
      break;
    }
  }
  out.rows = std::move(rows);
  return out;
}

}  // namespace rockbench::external
