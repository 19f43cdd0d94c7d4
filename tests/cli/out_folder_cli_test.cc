// --out naming a file, or a path under one (issue 38: a bare "filesystem error: cannot create
// directories: Not a directory"): every command that writes a folder says which name is a file,
// exits 2 (bad input) and leaves the file as it was.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/shell_test.h"

namespace rockbench {
namespace {

namespace fs = std::filesystem;
using testing_util::ReadFile;
using testing_util::Rockbench;
using testing_util::ShellRun;

const std::string kScene = std::string(ROCKBENCH_SOURCE_DIR) + "/scenes/housner_free_rocking.toml";

TEST(OutFolder, AFileNamedAsTheOutputFolderIsSaidSoAndKept) {
  const fs::path dir =
      fs::temp_directory_path() / ("rockbench_out_folder_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "results.txt";
  std::ofstream(file) << "the user's notes\n";
  for (const std::string& command :
       {"run " + kScene, "compare " + kScene + " --quick --engines reference", "sweep " + kScene}) {
    for (const fs::path& out : {file, file / "run1"}) {
      const ShellRun r = Rockbench(command + " --out " + out.string());
      EXPECT_EQ(r.exit_code, 2) << command << ": " << r.output;
      EXPECT_EQ(r.output, "rockbench: error: --out " + out.string() + ": " + file.string() +
                              " exists and is not a folder: give the name of a folder (it is "
                              "created when missing)\n")
          << command;
    }
  }
  EXPECT_EQ(ReadFile(file), "the user's notes\n");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rockbench
