#pragma once
// A test suite's scene and the reference's run of it, made once per suite: a suite derives from
// ReferenceSuite<itself> and its SetUpTestSuite calls RunReference(scene).
#include <gtest/gtest.h>

#include <memory>
#include <utility>

#include "motion/ground_motion.h"
#include "reference/simulate.h"
#include "scene/scene.h"

namespace rockbench::testing_util {

template <typename Suite>
class ReferenceSuite : public ::testing::Test {
 protected:
  /// Keeps `scene` and the reference's run of it with no base motion.
  static void RunReference(Scene scene) {
    scene_ = std::make_unique<Scene>(std::move(scene));
    ref_ = std::make_unique<reference::Result>(reference::Simulate(*scene_, GroundMotion()));
  }
  static void TearDownTestSuite() {
    ref_.reset();
    scene_.reset();
  }
  static inline std::unique_ptr<Scene> scene_;
  static inline std::unique_ptr<reference::Result> ref_;
};

}  // namespace rockbench::testing_util
