// The replay driver: a fuzz target built without libFuzzer (the normal g++ build and the
// sanitizer build) runs LLVMFuzzerTestOneInput once on the empty input and on every file given,
// or found directly in a folder given, in name order: the seed corpus, the committed corpus and
// the regression inputs (tests/fuzz/CMakeLists.txt). A finding aborts, after the input's path
// was printed; the run fails when no input file was found (a replay that ran nothing is no test).
//   <target>_replay [--glob SUFFIX] PATH...   (--glob .AT2: only folder files ending so)
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Files of a folder: its regular files, not its README.md (which says what the folder holds).
std::vector<std::filesystem::path> FolderFiles(const std::filesystem::path& dir,
                                               const std::string& suffix) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || name == "README.md" || name.front() == '.') continue;
    if (!suffix.empty() && !EndsWith(name, suffix)) continue;
    files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> inputs;
  std::string suffix;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--glob" && i + 1 < argc) {
      suffix = argv[++i];
      continue;
    }
    std::error_code ec;
    if (std::filesystem::is_directory(arg, ec)) {
      const auto files = FolderFiles(arg, suffix);
      inputs.insert(inputs.end(), files.begin(), files.end());
    } else if (std::filesystem::is_regular_file(arg, ec)) {
      inputs.emplace_back(arg);
    } else {
      std::fprintf(stderr, "replay: %s: no such file or folder\n", arg.c_str());
      return 2;
    }
  }
  if (inputs.empty()) {
    std::fprintf(stderr, "replay: no input files found in the paths given\n");
    return 2;
  }
  std::fprintf(stderr, "replay: (empty input)\n");
  static const uint8_t kNothing = 0;
  LLVMFuzzerTestOneInput(&kNothing, 0);
  for (const auto& path : inputs) {
    std::fprintf(stderr, "replay: %s\n", path.string().c_str());
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "replay: %s: cannot read\n", path.string().c_str());
      return 2;
    }
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("replay: %zu inputs, no finding\n", inputs.size() + 1);
  return 0;
}
