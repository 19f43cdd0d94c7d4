#include "util/wall_limit.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace rockbench {

void StartWallLimit(double seconds, const std::filesystem::path& out_dir,
                    const std::string& command) {
  if (!(seconds > 0.0) || !std::isfinite(seconds)) return;
  std::thread([seconds, out_dir, command] {
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    // This process's temporary files: "<name>.tmp.<pid>" (WriteFileAtomic) and ".<name>.tmp<pid>"
    // (the renders' animations).
    const std::string pid = std::to_string(::getpid());
    std::error_code ec;
    // Other threads may still be writing: remove, wait for a write in flight to land, and
    // remove again (three passes, 50 ms apart), then end the process at once.
    for (int pass = 0; pass < 3; ++pass) {
      if (pass > 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
      std::vector<std::filesystem::path> temps;
      if (!out_dir.empty() && std::filesystem::is_directory(out_dir, ec)) {
        std::filesystem::recursive_directory_iterator it(out_dir, ec), end;
        for (; !ec && it != end; it.increment(ec)) {
          const std::string name = it->path().filename().string();
          if (name.find(".tmp." + pid) != std::string::npos ||
              name.find(".tmp" + pid) != std::string::npos) {
            temps.push_back(it->path());
          }
        }
      }
      for (const auto& p : temps) std::filesystem::remove_all(p, ec);
    }
    char limit[32];
    std::snprintf(limit, sizeof limit, "%g", seconds);
    const std::string msg = "rockbench " + command + ": error: wall-clock limit of " + limit +
                            " s reached (--wall-limit); no output written for what was "
                            "unfinished\n";
    (void)!::write(STDERR_FILENO, msg.data(), msg.size());
    ::_exit(kExitWallLimit);
  }).detach();
}

}  // namespace rockbench
