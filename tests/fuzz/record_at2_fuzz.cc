// Fuzz target record_at2: the PEER AT2 record reader, rockbench::ParseAt2
// (src/scene/ground_motion.h), then the record as the program builds and uses it
// (record_check.h). Input: an AT2 file's text. Any answer but a record or a SceneError is a
// finding.
#include "tests/fuzz/record_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = rockbench::fuzz::Text(data, size);
  rockbench::fuzz::ExpectOnlySceneErrors("record_at2", [&] {
    rockbench::RecordData rec = rockbench::ParseAt2(text, "fuzz.AT2");
    // A header without units is PEER's g; other units are read when the scene says so.
    const rockbench::AccelUnits units = rec.header_units.value_or(rockbench::AccelUnits::kG);
    rockbench::fuzz::UseRecord("record_at2", std::move(rec), units);
  });
  return 0;
}
