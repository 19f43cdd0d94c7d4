// Fuzz target record_plain: the plain column record reader, rockbench::ParsePlain
// (src/scene/ground_motion.h), then the record as the program builds and uses it
// (record_check.h). Input: a plain file's text, read twice: as a scene without dt reads it
// (two columns t, a) and with dt = 0.01 s (one column). Any answer but a record or a SceneError
// is a finding.
#include "tests/fuzz/record_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = rockbench::fuzz::Text(data, size);
  for (const double dt_s : {0.0, 0.01}) {
    rockbench::fuzz::ExpectOnlySceneErrors("record_plain", [&] {
      rockbench::RecordData rec = rockbench::ParsePlain(text, "fuzz.txt", dt_s);
      rockbench::fuzz::UseRecord("record_plain", std::move(rec), rockbench::AccelUnits::kG);
    });
  }
  return 0;
}
