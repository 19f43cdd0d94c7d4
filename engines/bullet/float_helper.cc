#include "engines/bullet/float_helper.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "engines/bullet/protocol.h"
#include "util/subprocess.h"

namespace rockbench::bullet {
namespace {

// Removes the temporary files of one call, whatever happens.
struct TempFiles {
  std::filesystem::path in, out;
  ~TempFiles() {
    std::error_code ec;
    if (!in.empty()) std::filesystem::remove(in, ec);
    if (!out.empty()) std::filesystem::remove(out, ec);
  }
};

std::filesystem::path MakeTempFile() {
  std::string tmpl = (std::filesystem::temp_directory_path() / "rockbench-bullet-XXXXXX").string();
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  const int fd = mkstemp(buf.data());
  if (fd < 0) {
    throw std::runtime_error("bullet float helper: cannot create a temporary file in " +
                             std::filesystem::temp_directory_path().string() + ": " +
                             std::strerror(errno));
  }
  close(fd);
  return std::filesystem::path(buf.data());
}

}  // namespace

std::filesystem::path FindFloatHelper() {
  std::vector<std::filesystem::path> tried;
  std::error_code ec;
  if (const char* env = std::getenv("ROCKBENCH_BULLET_FLOAT_HELPER"); env && *env) {
    const std::filesystem::path p(env);
    if (std::filesystem::is_regular_file(p, ec)) return p;
    throw std::runtime_error(std::string("ROCKBENCH_BULLET_FLOAT_HELPER=") + env +
                             ": no such program");
  }
  if (const std::filesystem::path p = BesideSelf("rockbench-bullet-float"); !p.empty()) {
    if (std::filesystem::is_regular_file(p, ec)) return p;
    tried.push_back(p);
  }
#ifdef ROCKBENCH_BULLET_FLOAT_HELPER_PATH
  {
    const std::filesystem::path p(ROCKBENCH_BULLET_FLOAT_HELPER_PATH);
    if (std::filesystem::is_regular_file(p, ec)) return p;
    tried.push_back(p);
  }
#endif
  std::string msg =
      "bullet.precision = \"float\" needs the helper program rockbench-bullet-float; looked at";
  for (const auto& p : tried) {
    msg += ' ';
    msg += p.string();
  }
  msg += " (set ROCKBENCH_BULLET_FLOAT_HELPER to its path)";
  throw std::runtime_error(msg);
}

EngineResult RunFloatHelper(const BulletInput& input) {
  const std::filesystem::path helper = FindFloatHelper();
  TempFiles files;
  files.in = MakeTempFile();
  files.out = MakeTempFile();
  WriteBinaryFile(files.in, SerializeInput(input));

  // The helper's standard streams are ours: its error message, if any, is printed above ours.
  // A name without a '/' is a file of the working folder, not a program on PATH.
  const std::string helper_s = helper.string();
  const std::string program = helper.has_parent_path() ? helper_s : "./" + helper_s;
  Subprocess child({program, "--input", files.in.string(), "--output", files.out.string()},
                   SpawnOptions{});
  if (!child.started()) {
    throw std::runtime_error("bullet float helper: cannot start " + child.start_error());
  }
  const ExitStatus status = child.Wait();
  if (!status.ok()) {
    throw std::runtime_error("bullet float helper " + helper_s + " failed (" + status.Text() +
                             "); its message is above");
  }
  return ParseOutput(ReadBinaryFile(files.out));
}

}  // namespace rockbench::bullet
