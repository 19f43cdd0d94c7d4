#include "engines/bullet/float_helper.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "engines/bullet/protocol.h"

extern char** environ;

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
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path p = self.parent_path() / "rockbench-bullet-float";
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

  const std::string helper_s = helper.string(), in_s = files.in.string(),
                    out_s = files.out.string();
  std::vector<char*> argv = {const_cast<char*>(helper_s.c_str()), const_cast<char*>("--input"),
                             const_cast<char*>(in_s.c_str()),     const_cast<char*>("--output"),
                             const_cast<char*>(out_s.c_str()),    nullptr};
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, helper_s.c_str(), nullptr, nullptr, argv.data(), environ);
  if (rc != 0) {
    throw std::runtime_error("bullet float helper: cannot start " + helper_s + ": " +
                             std::strerror(rc));
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      throw std::runtime_error(std::string("bullet float helper: waitpid: ") +
                               std::strerror(errno));
    }
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const std::string how = WIFEXITED(status) ? "exit status " + std::to_string(WEXITSTATUS(status))
                                              : "signal " + std::to_string(WTERMSIG(status));
    throw std::runtime_error("bullet float helper " + helper_s + " failed (" + how +
                             "); its message is above");
  }
  return ParseOutput(ReadBinaryFile(files.out));
}

}  // namespace rockbench::bullet
