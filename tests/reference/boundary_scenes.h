#pragma once
// Scenes and block lists shared by the tests of the reference at the boundaries of its models
// (boundaries_test.cc, chattering_independent_test.cc).
#include <array>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace rockbench::reference::test_scenes {

/// Three blocks (width x height, m; 2500 kg/m^3) with friction 0.5 at every interface, under a
/// record of the repository's at `scale`, 15 s, no perturbation members.
inline Scene ThreeBlocks(const std::array<double, 6>& wh, const std::string& record, double scale) {
  std::string text;
  for (int i = 0; i < 3; ++i) {
    text += "[[block]]\nwidth = " + std::to_string(wh[2 * i]) +
            "\nheight = " + std::to_string(wh[2 * i + 1]) + "\ndensity = 2500.0\nfriction = 0.5\n";
  }
  text += "[base.horizontal]\nfile = \"records/" + record + "\"\nscale = " + std::to_string(scale) +
          "\n[run]\nduration = 15.0\noutput_interval = 0.01\n";
  Scene s = ParseScene(text, std::string(ROCKBENCH_SOURCE_DIR) + "/three_blocks.toml");
  s.compare.members = 0;
  return s;
}

/// 0.8 x 0.8, 0.6 x 0.6 and 0.4 x 0.8 m under Rinaldi 228: the stack slips first at a ground
/// impact and chatters (hundreds of impacts and stick-slip transitions within 1 ms) at 6.79 s.
inline Scene ThreeBlocksWithFriction() {
  return ThreeBlocks({0.8, 0.8, 0.6, 0.6, 0.4, 0.8}, "northridge1994_rinaldi_receiving_sta_228.AT2",
                     1.0);
}

/// The scene's blocks as an independent formulation's block type B (aggregate: half width, half
/// height, mass, central inertia of a uniform rectangle, friction).
template <class B>
std::vector<B> BlocksOf(const Scene& s) {
  std::vector<B> out;
  for (const BlockDef& d : s.blocks) {
    const double b = d.width_m / 2, h = d.height_m / 2;
    out.push_back({b, h, d.mass_kg, d.mass_kg * (b * b + h * h) / 3.0, d.friction});
  }
  return out;
}

}  // namespace rockbench::reference::test_scenes
