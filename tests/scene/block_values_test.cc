// BlockValues (src/scene/block_values.h): a vector of one value per block that keeps up to two
// values in place. Every operation is checked on both sides of the in-place limit and across
// it, against std::vector's results (the type it replaces in Sample and Event).
#include "scene/block_values.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace rockbench {
namespace {

std::vector<double> Ramp(size_t n) {
  std::vector<double> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = 0.5 + static_cast<double>(i);
  return v;
}

TEST(BlockValues, HoldsItsValuesInPlaceUpToTwoAndOnTheHeapBeyond) {
  for (size_t n : {0, 1, 2, 3, 8, 64}) {
    BlockValues v(Ramp(n));
    ASSERT_EQ(v.size(), n);
    EXPECT_EQ(v.empty(), n == 0);
    EXPECT_EQ(v.vector(), Ramp(n));
    // In place: the values live inside the object.
    const auto* self = reinterpret_cast<const char*>(&v);
    const auto* data = reinterpret_cast<const char*>(v.data());
    const bool inside = data >= self && data < self + sizeof v;
    EXPECT_EQ(inside, n <= BlockValues::kInline) << n;
  }
  EXPECT_EQ(sizeof(BlockValues), sizeof(std::vector<double>));
}

TEST(BlockValues, ConstructsAssignsAndResizesAsAVector) {
  EXPECT_EQ(BlockValues(3, 1.5).vector(), std::vector<double>(3, 1.5));
  EXPECT_EQ(BlockValues(2).vector(), std::vector<double>(2, 0.0));
  EXPECT_EQ((BlockValues{0.1, 0.2, 0.3}).vector(), (std::vector<double>{0.1, 0.2, 0.3}));
  for (size_t from : {0, 1, 2, 3, 5}) {
    for (size_t to : {0, 1, 2, 3, 4, 7}) {
      BlockValues v(Ramp(from));
      std::vector<double> want = Ramp(from);
      v.resize(to, -1.0);
      want.resize(to, -1.0);
      EXPECT_EQ(v.vector(), want) << from << " -> " << to;
      v.assign(from, 2.0);
      EXPECT_EQ(v.vector(), std::vector<double>(from, 2.0)) << from << " -> " << to;
      v = BlockValues(Ramp(to));
      EXPECT_EQ(v.vector(), Ramp(to)) << from << " -> " << to;
    }
  }
}

TEST(BlockValues, CopiesAndMovesKeepTheValuesAndOwnTheirStorage) {
  for (size_t n : {1, 2, 3, 6}) {
    for (size_t m : {1, 2, 4}) {
      const BlockValues a(Ramp(n));
      BlockValues copy(a);
      EXPECT_EQ(copy, a);
      copy[0] = 99.0;  // a copy is independent
      EXPECT_EQ(a[0], 0.5);
      BlockValues target(Ramp(m));
      target = a;  // copy assignment over any size
      EXPECT_EQ(target, a);
      BlockValues moved(std::move(target));
      EXPECT_EQ(moved, a);
      EXPECT_TRUE(target.empty());  // NOLINT(bugprone-use-after-move): moved-from is empty
      BlockValues over(Ramp(m));
      over = std::move(moved);
      EXPECT_EQ(over, a);
      const BlockValues& same = over;
      over = same;  // self-assignment keeps the values
      EXPECT_EQ(over, a);
    }
  }
}

TEST(BlockValues, ComparesByValues) {
  EXPECT_EQ(BlockValues({1.0, 2.0}), BlockValues({1.0, 2.0}));
  EXPECT_NE(BlockValues({1.0, 2.0}), BlockValues({1.0, 2.5}));
  EXPECT_NE(BlockValues({1.0, 2.0}), BlockValues({1.0, 2.0, 0.0}));
  double sum = 0.0;
  for (double x : BlockValues({1.0, 2.0, 3.0})) sum += x;
  EXPECT_EQ(sum, 6.0);
}

}  // namespace
}  // namespace rockbench
