// Fuzz target study_reader: the study file reader, rockbench::ParseStudy (src/study/study.h),
// then the first and last member's scene (rockbench::MemberScene), as `rockbench ensemble`
// builds them. Input: a study file's text; it is given a path in scenes/studies/, so that the
// shipped studies' relative scene and record paths resolve. Any answer but a study (and member
// scenes) or a SceneError is a finding.
#include "study/study.h"
#include "tests/fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = rockbench::fuzz::Text(data, size);
  static const std::filesystem::path path =
      rockbench::fuzz::SourceDir() / "scenes" / "studies" / "fuzz.toml";
  rockbench::fuzz::ExpectOnlySceneErrors("study_reader", [&] {
    const rockbench::StudyDef study = rockbench::ParseStudy(text, path);
    const int64_t members = study.member_count();
    if (members <= 0) rockbench::fuzz::Finding("study_reader: a study was read with no member");
    for (const int64_t m : {int64_t{0}, members - 1}) {
      const std::vector<int> idx = study.ValueIndices(m);
      if (idx.size() != study.axes.size()) {
        rockbench::fuzz::Finding("study_reader: ValueIndices gives no index for every axis");
      }
      for (size_t k = 0; k < idx.size(); ++k) {
        if (idx[k] < 0 || static_cast<size_t>(idx[k]) >= study.axes[k].values.size()) {
          rockbench::fuzz::Finding("study_reader: member " + std::to_string(m) +
                                   " has a value index outside axis " + study.axes[k].key);
        }
      }
      // A member whose scene is invalid is a member row that says so: a SceneError.
      rockbench::fuzz::ExpectOnlySceneErrors("study_reader (MemberScene)",
                                             [&] { (void)rockbench::MemberScene(study, m); });
    }
  });
  return 0;
}
