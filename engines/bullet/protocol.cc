#include "engines/bullet/protocol.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "engines/common/monitor.h"

namespace rockbench::bullet {
namespace {

constexpr char kInputMagic[8] = {'R', 'B', 'B', 'I', 'N', 'P', 'U', 'T'};
constexpr char kOutputMagic[8] = {'R', 'B', 'B', 'O', 'U', 'T', 'P', 'T'};
// 3: each flag with its onset time; 4: the history, events and outcome of N blocks (rates and
// configurations per block); 5: the input's N blocks (every block, angle and rate); 6: each
// block's friction, and slip and lift (the input's flag, the samples' u and z).
constexpr std::uint32_t kVersion = 6;
constexpr std::uint64_t kViolationFlagCount = std::size(kViolationFlags);

class Writer {
 public:
  template <typename T>
  void Put(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&v);
    out_.append(p, sizeof(T));
  }
  void PutBool(bool v) { Put<std::uint8_t>(v ? 1 : 0); }
  void PutStr(const std::string& s) {
    Put<std::uint64_t>(s.size());
    out_.append(s);
  }
  void PutVec(const std::vector<double>& v) {
    Put<std::uint64_t>(v.size());
    if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
  }
  void PutRaw(const char* p, size_t n) { out_.append(p, n); }
  std::string Take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  T Get() {
    T v;
    Need(sizeof(T));
    std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  bool GetBool() { return Get<std::uint8_t>() != 0; }
  std::string GetStr() {
    const auto n = Get<std::uint64_t>();
    Need(n);
    std::string s = bytes_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::vector<double> GetVec() {
    const auto n = Get<std::uint64_t>();
    if (n > (bytes_.size() - pos_) / sizeof(double)) Fail();
    std::vector<double> v(n);
    if (n) std::memcpy(v.data(), bytes_.data() + pos_, n * sizeof(double));
    pos_ += n * sizeof(double);
    return v;
  }
  void Expect(const char (&magic)[8]) {
    Need(8);
    if (std::memcmp(bytes_.data() + pos_, magic, 8) != 0) {
      throw std::runtime_error("bullet helper protocol: wrong file type");
    }
    pos_ += 8;
    const auto version = Get<std::uint32_t>();
    if (version != kVersion) {
      throw std::runtime_error("bullet helper protocol: version " + std::to_string(version) +
                               ", expected " + std::to_string(kVersion) +
                               " (rebuild rockbench and rockbench-bullet-float together)");
    }
  }
  void ExpectEnd() const {
    if (pos_ != bytes_.size()) throw std::runtime_error("bullet helper protocol: trailing data");
  }

 private:
  void Need(size_t n) const {
    if (n > bytes_.size() - pos_) Fail();
  }
  [[noreturn]] static void Fail() {
    throw std::runtime_error("bullet helper protocol: truncated data");
  }
  const std::string& bytes_;
  size_t pos_ = 0;
};

void PutBlock(Writer& w, const BlockDef& b) {
  w.Put(b.width_m);
  w.Put(b.height_m);
  w.Put(b.depth_m);
  w.Put(b.mass_kg);
  w.Put(b.density_kgpm3);
  w.Put(b.friction);
}
BlockDef GetBlock(Reader& r) {
  BlockDef b;
  b.width_m = r.Get<double>();
  b.height_m = r.Get<double>();
  b.depth_m = r.Get<double>();
  b.mass_kg = r.Get<double>();
  b.density_kgpm3 = r.Get<double>();
  b.friction = r.Get<double>();
  return b;
}

}  // namespace

std::string SerializeInput(const BulletInput& in) {
  Writer w;
  w.PutRaw(kInputMagic, 8);
  w.Put(kVersion);
  const int blocks = in.block_count();
  w.Put<std::int32_t>(blocks);
  for (const BlockDef& b : in.blocks) PutBlock(w, b);
  for (int k = 0; k < blocks; ++k) w.Put(in.initial.theta_rad[k]);
  for (int k = 0; k < blocks; ++k) w.Put(in.initial.omega_radps[k]);
  w.Put(in.run.duration_s);
  w.Put(in.run.output_interval_s);
  w.Put(in.run.gravity_mps2);
  const BulletConfig& c = in.config;
  w.Put(in.time_step_s);
  w.Put<std::int32_t>(c.solver_iterations);
  w.Put<std::int32_t>(static_cast<std::int32_t>(c.precision));
  w.Put<std::int32_t>(static_cast<std::int32_t>(in.drive_kind));
  w.Put(c.erp);
  w.Put(c.erp2);
  w.PutBool(c.split_impulse);
  w.Put(c.split_impulse_threshold);
  w.Put(c.restitution);
  w.Put(c.friction);
  w.Put(c.rolling_friction);
  w.Put(c.restitution_velocity_threshold);
  w.Put(c.margin_m);
  w.Put(c.ground_depth_m);
  w.Put(in.kinematic_highpass_hz);
  w.Put(in.overturn_rad);
  w.Put<std::int64_t>(in.steps);
  w.Put(in.motion_end_s);
  w.Put(in.stop_at_rest_after_s);
  w.PutBool(in.slip_and_lift);
  const DriveSamples& d = in.drive;
  w.PutVec(d.ax_mps2);
  w.PutVec(d.ay_mps2);
  w.PutVec(d.ux_m);
  w.PutVec(d.uy_m);
  w.Put(d.ux0_mps);
  w.Put(d.uy0_mps);
  w.Put(d.correction_max_x_mps2);
  w.Put(d.correction_max_y_mps2);
  w.Put(d.raw_peak_x_m);
  w.Put(d.raw_peak_y_m);
  w.Put(d.peak_x_m);
  w.Put(d.peak_y_m);
  return w.Take();
}

BulletInput ParseInput(const std::string& bytes) {
  Reader r(bytes);
  r.Expect(kInputMagic);
  BulletInput in;
  const int blocks = r.Get<std::int32_t>();
  if (blocks < 1 || blocks > kMaxBlocks) {
    throw std::runtime_error("bullet helper protocol: bad block count");
  }
  for (int k = 0; k < blocks; ++k) in.blocks.push_back(GetBlock(r));
  for (int k = 0; k < blocks; ++k) in.initial.theta_rad[k] = r.Get<double>();
  for (int k = 0; k < blocks; ++k) in.initial.omega_radps[k] = r.Get<double>();
  in.run.duration_s = r.Get<double>();
  in.run.output_interval_s = r.Get<double>();
  in.run.gravity_mps2 = r.Get<double>();
  BulletConfig& c = in.config;
  in.time_step_s = r.Get<double>();
  c.solver_iterations = r.Get<std::int32_t>();
  c.precision = static_cast<BulletPrecision>(r.Get<std::int32_t>());
  in.drive_kind = static_cast<DriveKind>(r.Get<std::int32_t>());
  c.erp = r.Get<double>();
  c.erp2 = r.Get<double>();
  c.split_impulse = r.GetBool();
  c.split_impulse_threshold = r.Get<double>();
  c.restitution = r.Get<double>();
  c.friction = r.Get<double>();
  c.rolling_friction = r.Get<double>();
  c.restitution_velocity_threshold = r.Get<double>();
  c.margin_m = r.Get<double>();
  c.ground_depth_m = r.Get<double>();
  in.kinematic_highpass_hz = r.Get<double>();
  in.overturn_rad = r.Get<double>();
  in.steps = r.Get<std::int64_t>();
  in.motion_end_s = r.Get<double>();
  in.stop_at_rest_after_s = r.Get<double>();
  in.slip_and_lift = r.GetBool();
  DriveSamples& d = in.drive;
  d.ax_mps2 = r.GetVec();
  d.ay_mps2 = r.GetVec();
  d.ux_m = r.GetVec();
  d.uy_m = r.GetVec();
  d.ux0_mps = r.Get<double>();
  d.uy0_mps = r.Get<double>();
  d.correction_max_x_mps2 = r.Get<double>();
  d.correction_max_y_mps2 = r.Get<double>();
  d.raw_peak_x_m = r.Get<double>();
  d.raw_peak_y_m = r.Get<double>();
  d.peak_x_m = r.Get<double>();
  d.peak_y_m = r.Get<double>();
  r.ExpectEnd();
  return in;
}

std::string SerializeOutput(const EngineResult& out) {
  Writer w;
  w.PutRaw(kOutputMagic, 8);
  w.Put(kVersion);
  const int blocks = out.history.blocks;
  w.Put<std::int32_t>(blocks);
  // Every per-block vector of the history and the outcome has `blocks` entries.
  const auto put_values = [&](const auto& v) {
    for (int k = 0; k < blocks; ++k) w.Put(k < static_cast<int>(v.size()) ? v[k] : 0.0);
  };
  const auto put_configuration = [&](const Configuration& c) {
    for (int k = 0; k < blocks; ++k) {
      w.Put<std::int32_t>(k < c.size() ? static_cast<std::int32_t>(c[k]) : 0);
    }
  };
  const bool slip_and_lift = out.history.slip_and_lift;
  w.PutBool(slip_and_lift);
  w.Put<std::uint64_t>(out.history.samples.size());
  for (const Sample& s : out.history.samples) {
    w.Put(s.t_s);
    put_values(s.theta_rad);
    put_values(s.omega_radps);
    put_configuration(s.mode);
    if (slip_and_lift) {
      put_values(s.u_m);
      put_values(s.z_m);
    }
  }
  w.Put<std::uint64_t>(out.history.events.size());
  for (const Event& e : out.history.events) {
    w.Put(e.t_s);
    w.PutStr(e.kind);
    put_configuration(e.mode_before);
    put_configuration(e.mode_after);
    put_values(e.omega_before_radps);
    put_values(e.omega_after_radps);
    w.Put(e.energy_before_j);
    w.Put(e.energy_after_j);
    w.PutStr(e.note);
  }
  const RunOutcome& o = out.outcome;
  w.PutStr(StatusText(o.status));
  w.Put<std::int32_t>(o.overturned_block);
  w.Put(o.overturn_t_s);
  w.Put(o.end_t_s);
  put_values(o.peak_theta_rad);
  put_values(o.peak_theta_t_s);
  for (int k = 0; k < blocks; ++k) {
    w.Put<std::int32_t>(k < static_cast<int>(o.impacts_at.size()) ? o.impacts_at[k] : 0);
  }
  // Each flag with its onset (the run's end for an onset the outcome does not carry).
  auto put_flags = [&](const std::vector<std::string>& flags, const std::vector<double>& onsets) {
    w.Put<std::uint64_t>(flags.size());
    for (size_t i = 0; i < flags.size(); ++i) {
      w.PutStr(flags[i]);
      w.Put(i < onsets.size() ? onsets[i] : o.end_t_s);
    }
  };
  put_flags(o.violations, o.violation_onsets_t_s);
  put_flags(o.significant_violations, o.significant_onsets_t_s);
  w.PutStr(out.summary.dump());
  w.Put(out.wall_s);
  return w.Take();
}

EngineResult ParseOutput(const std::string& bytes) {
  Reader r(bytes);
  r.Expect(kOutputMagic);
  EngineResult out;
  const int blocks = r.Get<std::int32_t>();
  if (blocks < 1 || blocks > kMaxBlocks) {
    throw std::runtime_error("bullet helper protocol: bad block count");
  }
  out.history.blocks = blocks;
  const auto get_values = [&](auto* v) {
    v->assign(static_cast<size_t>(blocks), 0.0);
    for (double& x : *v) x = r.Get<double>();
  };
  const auto get_configuration = [&](Configuration* c) {
    *c = Configuration(blocks);
    for (int k = 0; k < blocks; ++k) {
      const auto contact = r.Get<std::int32_t>();
      if (contact < 0 || contact > 2) throw std::runtime_error("bullet helper protocol: bad mode");
      c->set(k, static_cast<Contact>(contact));
    }
  };
  const bool slip_and_lift = r.GetBool();
  out.history.slip_and_lift = slip_and_lift;
  const auto ns = r.Get<std::uint64_t>();
  if (ns > bytes.size()) throw std::runtime_error("bullet helper protocol: bad sample count");
  out.history.samples.reserve(ns);
  for (std::uint64_t i = 0; i < ns; ++i) {
    Sample s(blocks, slip_and_lift);
    s.t_s = r.Get<double>();
    get_values(&s.theta_rad);
    get_values(&s.omega_radps);
    get_configuration(&s.mode);
    if (slip_and_lift) {
      get_values(&s.u_m);
      get_values(&s.z_m);
    }
    out.history.samples.push_back(std::move(s));
  }
  const auto ne = r.Get<std::uint64_t>();
  if (ne > bytes.size()) throw std::runtime_error("bullet helper protocol: bad event count");
  out.history.events.reserve(ne);
  for (std::uint64_t i = 0; i < ne; ++i) {
    Event& e = out.history.events.emplace_back(blocks);
    e.t_s = r.Get<double>();
    e.kind = r.GetStr();
    get_configuration(&e.mode_before);
    get_configuration(&e.mode_after);
    get_values(&e.omega_before_radps);
    get_values(&e.omega_after_radps);
    e.energy_before_j = r.Get<double>();
    e.energy_after_j = r.Get<double>();
    e.note = r.GetStr();
  }
  RunOutcome& o = out.outcome;
  o = RunOutcome(blocks);
  const std::optional<RunStatus> status = ParseRunStatus(r.GetStr());
  if (!status) throw std::runtime_error("bullet helper protocol: bad status");
  o.status = *status;
  o.overturned_block = r.Get<std::int32_t>();
  o.overturn_t_s = r.Get<double>();
  o.end_t_s = r.Get<double>();
  get_values(&o.peak_theta_rad);
  get_values(&o.peak_theta_t_s);
  for (int& n : o.impacts_at) n = r.Get<std::int32_t>();
  auto get_flags = [&r](std::vector<std::string>* flags, std::vector<double>* onsets) {
    const auto n = r.Get<std::uint64_t>();
    if (n > kViolationFlagCount) throw std::runtime_error("bullet helper protocol: bad flags");
    for (std::uint64_t i = 0; i < n; ++i) {
      flags->push_back(r.GetStr());
      onsets->push_back(r.Get<double>());
    }
  };
  get_flags(&o.violations, &o.violation_onsets_t_s);
  get_flags(&o.significant_violations, &o.significant_onsets_t_s);
  out.summary = nlohmann::json::parse(r.GetStr());
  out.wall_s = r.Get<double>();
  r.ExpectEnd();
  return out;
}

std::string ReadBinaryFile(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error(path.string() + ": cannot open for reading");
  std::ostringstream ss;
  ss << f.rdbuf();
  if (!f.good() && !f.eof()) throw std::runtime_error(path.string() + ": read error");
  return ss.str();
}

void WriteBinaryFile(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw std::runtime_error(path.string() + ": cannot open for writing");
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  f.close();
  if (!f) throw std::runtime_error(path.string() + ": write error");
}

}  // namespace rockbench::bullet
