// Every shipped scene's agreement with the reference model, checked against the committed
// tolerances in tests/agreement/tolerances.toml (docs/agreement.md). One test per comparison
// (scene, engine, settings), named after it; a failure prints the metric, the measured value,
// the bound and the entry's why. Tightening a bound is free; loosening one means editing the
// tolerance file, where review sees it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "run/engine_run.h"
#include "tolerances.h"

namespace rockbench::agreement {

// gtest prints a failing test's parameter with this.
void PrintTo(const BoundGroup& g, std::ostream* os) {
  *os << g.TestName();
}

namespace {

const std::filesystem::path kSourceDir = ROCKBENCH_SOURCE_DIR;
const std::filesystem::path kTolerances = kSourceDir / "tests" / "agreement" / "tolerances.toml";
const std::filesystem::path kScenes = kSourceDir / "scenes";

// The comparisons of the committed file; none when it is invalid (then IsValid fails and says
// why), so that listing the tests never throws.
std::vector<BoundGroup> CommittedGroups() {
  try {
    return GroupBounds(LoadTolerances(kTolerances, kScenes));
  } catch (const std::exception&) {
    return {};
  }
}

TEST(TolerancesFile, IsValid) {
  try {
    const std::vector<BoundGroup> groups = GroupBounds(LoadTolerances(kTolerances, kScenes));
    EXPECT_FALSE(groups.empty()) << kTolerances << " has no [[bound]] entries";
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
}

// Every scene in scenes/ is guarded: it has at least one bound for every engine other than the
// reference.
TEST(TolerancesFile, EveryShippedSceneHasAnEngineBound) {
  ASSERT_FALSE(SceneFiles(kScenes).empty()) << kScenes;
  try {
    for (const std::string& missing :
         UnguardedScenes(LoadTolerances(kTolerances, kScenes), kScenes)) {
      ADD_FAILURE() << "scenes/" << missing << ": no bound in " << kTolerances.string()
                    << ": add [[bound]] entries for this scene and engine (docs/agreement.md)";
    }
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
}

class AgreementTest : public ::testing::TestWithParam<BoundGroup> {};

TEST_P(AgreementTest, MeetsTheCommittedBounds) {
  const BoundGroup& g = GetParam();
  const std::vector<std::string> available = AvailableEngines();
  if (std::find(available.begin(), available.end(), g.engine) == available.end()) {
    GTEST_SKIP() << "engine " << g.engine << " is not in this build";
  }
  const nlohmann::json agreement = RunComparison(g);
  std::printf("%s\n", g.TestName().c_str());
  for (const Bound& b : g.bounds) {
    const Verdict v = CheckBound(b, agreement);
    std::printf("  %s\n", v.message.substr(0, v.message.find('\n')).c_str());
    if (!v.pass) ADD_FAILURE() << v.message;
  }
}

INSTANTIATE_TEST_SUITE_P(Committed, AgreementTest, ::testing::ValuesIn(CommittedGroups()),
                         [](const ::testing::TestParamInfo<BoundGroup>& info) {
                           return info.param.TestName();
                         });
// An invalid file instantiates nothing; TolerancesFile.IsValid reports it.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(AgreementTest);

}  // namespace
}  // namespace rockbench::agreement
