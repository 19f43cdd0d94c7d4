// Dependencies point one way (README, Layout): the reference model, the engines and the renders
// know the scene vocabulary (src/scene/) and not each other; the harness, the reports and the
// CLI know them all. Checked on the sources: every #include of the three folders, and the
// libraries their CMakeLists.txt link.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path kRoot = ROCKBENCH_SOURCE_DIR;

std::string Read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first folder of every project include ("scene/mode.h" -> "scene") in the C++ files under
// `folder`, with the file and line that has it.
std::vector<std::pair<std::string, std::string>> IncludedFolders(const std::string& folder) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& e : fs::recursive_directory_iterator(kRoot / folder)) {
    const std::string ext = e.path().extension().string();
    if (!e.is_regular_file() || (ext != ".h" && ext != ".cc")) continue;
    std::istringstream lines(Read(e.path()));
    int n = 0;
    for (std::string line; std::getline(lines, line);) {
      ++n;
      // #include "folder/file.h" (system and same-folder includes have no quoted folder).
      const size_t hash = line.find_first_not_of(" \t");
      if (hash == std::string::npos || line[hash] != '#') continue;
      const size_t word = line.find_first_not_of(" \t", hash + 1);
      if (word == std::string::npos || line.compare(word, 7, "include") != 0) continue;
      const size_t open = line.find('"', word);
      if (open == std::string::npos) continue;
      const size_t close = line.find('"', open + 1);
      const size_t slash = line.find('/', open + 1);
      if (close == std::string::npos || slash == std::string::npos || slash > close) continue;
      out.push_back({line.substr(open + 1, slash - open - 1),
                     fs::relative(e.path(), kRoot).string() + ":" + std::to_string(n)});
    }
  }
  return out;
}

void ExpectOnly(const std::string& folder, const std::set<std::string>& allowed) {
  const auto includes = IncludedFolders(folder);
  EXPECT_FALSE(includes.empty()) << folder << ": no project include found (wrong root?)";
  for (const auto& [included, where] : includes) {
    EXPECT_TRUE(allowed.count(included)) << where << " includes " << included << "/: " << folder
                                         << "/ may include only its own folder and scene/";
  }
}

TEST(Layout, ReferenceEnginesAndRendersKnowOnlyTheScene) {
  ExpectOnly("reference", {"reference", "scene"});
  ExpectOnly("engines", {"engines", "scene"});
  ExpectOnly("renders", {"renders", "scene"});
}

TEST(Layout, EnginesAndRendersDoNotLinkTheReference) {
  for (const std::string folder : {"engines", "renders"}) {
    for (const auto& e : fs::recursive_directory_iterator(kRoot / folder)) {
      if (e.path().filename() != "CMakeLists.txt") continue;
      const std::string text = Read(e.path());
      EXPECT_EQ(text.find("rockbench_reference"), std::string::npos)
          << fs::relative(e.path(), kRoot).string() << " links the reference";
    }
  }
}

}  // namespace
