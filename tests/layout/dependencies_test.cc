// Dependencies point one way (README, Layout), checked on the sources: every project #include of
// every code folder against the folder's rule, and the libraries the engines' and the renders'
// CMakeLists.txt link.
#include <dlfcn.h>
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

bool HasOwnRule(const fs::path& dir);

// The first folder of every project include ("scene/mode.h" -> "scene") in the C++ files under
// `folder`, with the file and line that has it.
std::vector<std::pair<std::string, std::string>> IncludedFolders(const std::string& folder) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& e : fs::recursive_directory_iterator(kRoot / folder)) {
    const std::string ext = e.path().extension().string();
    if (!e.is_regular_file() || (ext != ".h" && ext != ".cc")) continue;
    // A subfolder with a rule of its own is checked by that rule.
    if (e.path().parent_path() != kRoot / folder && HasOwnRule(e.path().parent_path())) continue;
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
      // The reference's rooms are named by their first two folders ("reference/thesis").
      std::string room = line.substr(open + 1, slash - open - 1);
      const size_t second = line.find('/', slash + 1);
      if (room == "reference" && second != std::string::npos && second < close) {
        room = line.substr(open + 1, second - open - 1);
      }
      out.push_back({room, fs::relative(e.path(), kRoot).string() + ":" + std::to_string(n)});
    }
  }
  return out;
}

// Every code folder and the folders it may include, bottom to top (README, Layout). util/ is
// the base layer every folder may use; scene/ is the vocabulary; the reference, the engines and
// the renders know the vocabulary and not each other; the harness's folders each know those
// below them; the reports and the CLI know them all.
struct FolderRule {
  const char* folder;  // path from the root
  std::set<std::string> may_include;
};
const std::vector<FolderRule> kRules = {
    {"src/util", {"util"}},
    {"src/scene", {"scene", "util"}},
    {"src/files", {"files", "scene", "util"}},
    {"src/motion", {"motion", "files", "scene", "util"}},
    {"src/engine", {"engine", "motion", "files", "scene", "util"}},
    // The reference's rooms: integration knows nothing else, the thesis's model the scene, the
    // chain and the unilateral model the thesis's impacts; the drivers at the top know them all.
    {"reference/integration", {"reference/integration"}},
    {"reference/thesis", {"reference/thesis", "scene", "util"}},
    {"reference/chain", {"reference/chain", "reference/thesis", "scene", "util"}},
    {"reference/unilateral", {"reference/unilateral", "reference/thesis", "scene", "util"}},
    {"reference/benchmarks", {"reference/benchmarks", "scene", "util"}},
    {"reference/cylinder", {"reference/cylinder", "scene", "util"}},
    {"reference",
     {"reference", "reference/integration", "reference/thesis", "reference/chain",
      "reference/unilateral", "reference/benchmarks", "reference/cylinder", "engine", "motion",
      "files", "scene", "util"}},
    {"engines", {"engines", "engine", "motion", "files", "scene", "util"}},
    {"renders", {"renders", "motion", "files", "scene", "util"}},
    {"src/run", {"run", "reference", "engines", "engine", "motion", "files", "scene", "util"}},
    {"src/statistics", {"statistics"}},
    {"src/compare",
     {"compare", "run", "statistics", "reference", "engines", "engine", "motion", "files", "scene",
      "util"}},
    {"src/stress",
     {"stress", "compare", "run", "reference", "engines", "engine", "motion", "files", "scene",
      "util"}},
    {"src/sweep",
     {"sweep", "compare", "run", "reference", "engines", "engine", "motion", "files", "scene",
      "util"}},
    {"src/study",
     {"study", "compare", "run", "statistics", "reference", "engines", "engine", "motion", "files",
      "scene", "util"}},
    {"src/report",
     {"report", "study", "compare", "run", "statistics", "reference", "renders", "engine", "motion",
      "files", "scene", "util"}},
    {"src/cli",
     {"cli", "report", "study", "sweep", "stress", "compare", "run", "statistics", "reference",
      "engines", "renders", "engine", "motion", "files", "scene", "util"}},
    // The Python module's core: a front end as the CLI is, on the harness's folders.
    {"python",
     {"study", "compare", "run", "statistics", "engine", "motion", "files", "scene", "util"}},
};

// Whether `dir` (absolute) is a folder with a rule of its own.
bool HasOwnRule(const fs::path& dir) {
  const std::string rel = fs::relative(dir, kRoot).string();
  for (const FolderRule& rule : kRules) {
    if (rel == rule.folder) return true;
  }
  return false;
}

TEST(Layout, EveryFolderIncludesOnlyWhatItsRuleAllows) {
  for (const FolderRule& rule : kRules) {
    const auto includes = IncludedFolders(rule.folder);
    EXPECT_FALSE(includes.empty()) << rule.folder << ": no project include found (wrong root?)";
    for (const auto& [included, where] : includes) {
      EXPECT_TRUE(rule.may_include.count(included))
          << where << " includes " << included << "/: " << rule.folder << "/ may not";
    }
  }
}

// A new code folder states its rule here before it holds code: every folder of src/ and every
// top-level folder with C++ sources is in kRules.
TEST(Layout, EveryCodeFolderHasARule) {
  std::set<std::string> ruled;
  for (const FolderRule& rule : kRules) ruled.insert(rule.folder);
  std::vector<fs::path> folders;
  for (const auto& e : fs::directory_iterator(kRoot / "src")) {
    if (e.is_directory()) folders.push_back(e.path());
  }
  for (const char* top : {"reference", "engines", "renders", "python"}) {
    folders.push_back(kRoot / top);
  }
  for (const auto& e : fs::directory_iterator(kRoot / "reference")) {
    if (e.is_directory()) folders.push_back(e.path());
  }
  for (const fs::path& f : folders) {
    bool has_code = false;
    for (const auto& e : fs::recursive_directory_iterator(f)) {
      const std::string ext = e.path().extension().string();
      has_code = has_code || ext == ".cc" || ext == ".h";
    }
    if (!has_code) continue;
    const std::string rel = fs::relative(f, kRoot).string();
    EXPECT_TRUE(ruled.count(rel)) << rel << "/ has code and no rule in kRules";
  }
}

// Rooms stay small enough to be named for what they hold: no folder of code or tests holds more
// than 25 files (a folder that outgrows it is split by what its files hold; a fuzzer's corpus is
// data and not counted).
TEST(Layout, NoFolderHoldsMoreThan25Files) {
  constexpr int kMaxFiles = 25;
  for (const char* top : {"src", "reference", "engines", "renders", "tests", "bench", "python"}) {
    std::vector<fs::path> dirs = {kRoot / top};
    for (const auto& e : fs::recursive_directory_iterator(kRoot / top)) {
      // A fuzzer's corpus is data, one input a file.
      if (e.is_directory() && e.path().string().find("/corpus") == std::string::npos) {
        dirs.push_back(e.path());
      }
    }
    for (const fs::path& d : dirs) {
      int files = 0;
      for (const auto& e : fs::directory_iterator(d)) files += e.is_regular_file() ? 1 : 0;
      EXPECT_LE(files, kMaxFiles) << fs::relative(d, kRoot).string() << "/ holds " << files
                                  << " files";
    }
  }
}

// The rules hold in the libraries too: the engines and the renders never link the reference;
// the reference never links an engine or the renders.
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

// Every program answers cblas_* from GSL's reference CBLAS (CMakeLists.txt pins it first):
// Siconos's contact solver calls it, and OpenBLAS, which the process also loads, gives other
// last bits, so a program that took its CBLAS by link order gave other histories.
TEST(Layout, EveryProgramTakesItsCblasFromGsl) {
  void* ddot = dlsym(RTLD_DEFAULT, "cblas_ddot");
  ASSERT_NE(ddot, nullptr) << "no cblas_ddot in the process";
  Dl_info info{};
  ASSERT_NE(dladdr(ddot, &info), 0);
  EXPECT_NE(std::string(info.dli_fname).find("libgslcblas"), std::string::npos)
      << "cblas_ddot comes from " << info.dli_fname;
}

}  // namespace
