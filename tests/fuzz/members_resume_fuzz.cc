// Fuzz target members_resume: `rockbench ensemble --resume` reading a study folder's
// members.csv (rockbench::MembersJournal, src/study/study_runner.h). Input: the file's text after
// its header (a fixed two-axis study of scenes/studies/pulse_block.toml, engines "reference" and
// "bullet"). The contract (issue 38): the journal opens, or refuses with a SceneError; a refusal
// leaves the file byte for byte as it was; an opening keeps the file but for a last line without
// its end (and only when that line is a row's beginning), keeps no more rows than the file has
// lines, and then appends a row whole. Anything else is a finding.
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "study/study.h"
#include "study/study_member.h"
#include "study/study_runner.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const rockbench::StudyDef& TheStudy() {
  static const rockbench::StudyDef study = rockbench::ParseStudy(
      "scene = \"pulse_block.toml\"\nengines = [\"reference\", \"bullet\"]\n"
      "[[axis]]\nkey = \"block1.density\"\nvalues = [2000, 2500, 3000]\n"
      "[[axis]]\nkey = \"block1.width\"\nvalues = [0.8, 1.0]\n",
      rockbench::fuzz::SourceDir() / "scenes" / "studies" / "fuzz.toml");
  return study;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const rockbench::StudyDef& study = TheStudy();
  static const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                           ("rockbench_fuzz_members_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string text = rockbench::MembersCsvHeader(study) + rockbench::fuzz::Text(data, size);
  std::ofstream(dir / "members.csv", std::ios::binary | std::ios::trunc) << text;
  std::ofstream(dir / "members.study", std::ios::binary | std::ios::trunc)
      << rockbench::StudyInputsText(study);
  size_t lines = 0;
  for (const char c : text) lines += c == '\n';
  bool opened = false;
  try {
    rockbench::MembersJournal journal(study, dir, /*resume=*/true);
    opened = true;
    const std::string kept = ReadAll(dir / "members.csv");
    // Only a last line without its end may go.
    const size_t last_end = text.rfind('\n') + 1;
    if (kept != text && kept != text.substr(0, last_end)) {
      rockbench::fuzz::Finding("members_resume: the file was cut to " +
                               std::to_string(kept.size()) + " of " + std::to_string(text.size()) +
                               " bytes (the last line ends at " + std::to_string(last_end) + ")");
    }
    if (journal.rows_at_open() < 0 || static_cast<size_t>(journal.rows_at_open()) + 1 > lines) {
      rockbench::fuzz::Finding("members_resume: more rows kept than the file has lines");
    }
    // A row appended after the opening is whole, on a line of its own.
    const rockbench::MemberRow row = rockbench::FailedRow(1, "bullet", "error", "fuzz");
    journal.Append(row);
    const std::string line = rockbench::MembersCsvLine(study, row);
    const std::string after = ReadAll(dir / "members.csv");
    if (after != kept + line)
      rockbench::fuzz::Finding("members_resume: an appended row is not whole");
  } catch (const rockbench::SceneError&) {
    if (!opened && ReadAll(dir / "members.csv") != text) {
      rockbench::fuzz::Finding("members_resume: a refused journal changed the file");
    }
  } catch (const std::exception& e) {
    rockbench::fuzz::Finding(std::string("members_resume: an exception other than SceneError "
                                         "escaped: ") +
                             std::string(e.what()).substr(0, 2000));
  }
  return 0;
}
