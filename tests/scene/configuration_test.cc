// The configuration of a stack of N blocks (scene/mode.h): one contact per interface, its
// names, and its agreement with the thesis's modes for one and two blocks.
#include <gtest/gtest.h>

#include "scene/mode.h"

namespace rockbench {
namespace {

constexpr Mode kAllModes[] = {Mode::kRest, Mode::k1a, Mode::k1b, Mode::k2a, Mode::k2b,
                              Mode::k3a,   Mode::k3b, Mode::k4a, Mode::k4b};

TEST(ConfigurationTest, ANewStackIsAtRestOnEveryFace) {
  const Configuration c(kMaxBlocks);
  EXPECT_EQ(c.size(), kMaxBlocks);
  EXPECT_TRUE(c.at_rest());
  EXPECT_EQ(c.open_count(), 0);
  for (int k = 0; k < kMaxBlocks; ++k) EXPECT_EQ(c[k], Contact::kFace) << k;
}

TEST(ConfigurationTest, EachInterfaceKeepsItsOwnContact) {
  // Every interface set, in both words of the packing, and read back without disturbing its
  // neighbours.
  Configuration c(kMaxBlocks);
  for (int k = 0; k < kMaxBlocks; ++k) c.set(k, static_cast<Contact>(k % 3));
  for (int k = 0; k < kMaxBlocks; ++k) EXPECT_EQ(c[k], static_cast<Contact>(k % 3)) << k;
  c.set(33, Contact::kFace);
  EXPECT_EQ(c[32], static_cast<Contact>(32 % 3));
  EXPECT_EQ(c[33], Contact::kFace);
  EXPECT_EQ(c[34], static_cast<Contact>(34 % 3));
  int open = 0;
  for (int k = 0; k < kMaxBlocks; ++k) open += c[k] != Contact::kFace;
  EXPECT_EQ(c.open_count(), open);
  EXPECT_FALSE(c.at_rest());
}

TEST(ConfigurationTest, EqualityComparesSizeAndEveryContact) {
  Configuration a(3), b(3);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, Configuration(4));  // the same faces, one more interface
  b.set(2, Contact::kLeft);
  EXPECT_NE(a, b);
  a.set(2, Contact::kLeft);
  EXPECT_EQ(a, b);
}

TEST(ConfigurationTest, TwoBlocksAreTheThesisModes) {
  for (const Mode mode : kAllModes) {
    const Configuration c = ConfigurationOf(mode, 2);
    EXPECT_EQ(c.size(), 2);
    EXPECT_EQ(c[0], ContactsOf(mode).ground);
    EXPECT_EQ(c[1], ContactsOf(mode).interface);
    ASSERT_TRUE(ModeOfConfiguration(c).has_value());
    EXPECT_EQ(*ModeOfConfiguration(c), mode);
    EXPECT_EQ(ConfigurationName(c), ModeName(mode));
    ASSERT_TRUE(ParseConfiguration(ModeName(mode), 2).has_value());
    EXPECT_EQ(*ParseConfiguration(ModeName(mode), 2), c);
  }
  // The letters name the same configurations: 1a is both corners right, 4b block 2 on its left.
  EXPECT_EQ(*ParseConfiguration("rr", 2), ConfigurationOf(Mode::k1a, 2));
  EXPECT_EQ(*ParseConfiguration("fl", 2), ConfigurationOf(Mode::k4b, 2));
}

TEST(ConfigurationTest, OneBlockHasRestAndTheTwoRockingSides) {
  EXPECT_EQ(ConfigurationName(ConfigurationOf(Mode::kRest, 1)), "rest");
  EXPECT_EQ(ConfigurationName(ConfigurationOf(Mode::k3a, 1)), "3a");
  EXPECT_EQ(ConfigurationName(ConfigurationOf(Mode::k3b, 1)), "3b");
  EXPECT_EQ(ConfigurationOf(Mode::k3a, 1)[0], Contact::kRight);
  EXPECT_EQ(*ParseConfiguration("l", 1), ConfigurationOf(Mode::k3b, 1));
  // Block 2's modes do not exist for one block.
  EXPECT_FALSE(ParseConfiguration("1a", 1).has_value());
  EXPECT_FALSE(ParseConfiguration("4b", 1).has_value());
}

TEST(ConfigurationTest, ThreeOrMoreBlocksAreNamedByLetters) {
  Configuration c(3);
  c.set(1, Contact::kRight);
  c.set(2, Contact::kLeft);
  EXPECT_EQ(ConfigurationName(c), "frl");
  EXPECT_EQ(*ParseConfiguration("frl", 3), c);
  EXPECT_EQ(ConfigurationName(Configuration(5)), "fffff");
  // Wrong length, an unknown letter, a thesis name for three blocks, an impossible stack.
  EXPECT_FALSE(ParseConfiguration("fr", 3).has_value());
  EXPECT_FALSE(ParseConfiguration("fxr", 3).has_value());
  EXPECT_FALSE(ParseConfiguration("rest", 3).has_value());
  EXPECT_FALSE(ParseConfiguration("", 0).has_value());
  EXPECT_FALSE(ParseConfiguration(std::string(kMaxBlocks + 1, 'f'), kMaxBlocks + 1).has_value());
}

}  // namespace
}  // namespace rockbench
