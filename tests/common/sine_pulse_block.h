#pragma once
// The study tests' scene: one 0.4 x 1.2 m block (2000 kg/m^3) under a 0.3 g, 2 Hz sine pulse.
// Small pulse amplitudes leave it at rest, middle ones rock it, large ones overturn it.
#include <string>

namespace rockbench::testing_util {

/// The scene file's text: the block, the pulse and `duration` ("0.5": the [run] table's
/// duration, s, as written), then `extra` (engine tables, "[bullet]\ntime_step = 2e-4\n").
inline std::string SinePulseBlockToml(const std::string& duration, const std::string& extra = "") {
  return "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2000.0\n"
         "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\nfrequency_hz = 2.0\n"
         "[run]\nduration = " +
         duration + "\n" + extra;
}

}  // namespace rockbench::testing_util
