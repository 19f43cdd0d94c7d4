// The ensemble report (src/report/ensemble_report.h) on ensemble folders written with the
// harness's own members.csv writer: a spectrum whose engine differs from the reference on one
// member says so and marks that member; a fragility study whose engine overturns at twice the
// reference's PGA says the difference excludes zero, and one whose engine agrees says it
// contains zero; a malformed members.csv is an error naming its line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/scratch_dir_test.h"
#include "report/run/run_report.h"
#include "report/study/study_report.h"
#include "study/study_member.h"

namespace rockbench::report {
namespace {

std::string ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

StudyAxis Axis(const std::string& key, const std::vector<double>& values) {
  StudyAxis a;
  a.key = key;
  for (double v : values) {
    std::ostringstream t;
    t << v;
    a.values.push_back({t.str(), t.str(), v, true});
  }
  return a;
}

MemberRow Row(long long member, const std::string& engine, int overturned, double pga_g,
              int impacts = 0, double pgv_over_pga_s = 0.1) {
  MemberRow r;
  r.member = member;
  r.engine = engine;
  r.status = overturned ? "overturned" : "completed";
  r.overturned_block = overturned;
  r.peak_theta_rad = {overturned ? 1.25 : 0.05};
  r.impacts = impacts;
  r.pga_g = pga_g;
  r.pgv_mps = pga_g * 9.80665 * pgv_over_pga_s;
  r.has_result = true;
  r.p_radps = {1.9};
  r.alpha_rad = {0.245};
  return r;
}

class EnsembleReportTest : public testing_util::ScratchDirTest {
 protected:
  // Writes study.json and members.csv for `study` and `rows`.
  std::filesystem::path WriteEnsemble(const std::string& name, const StudyDef& study,
                                      const std::vector<MemberRow>& rows) {
    const std::filesystem::path dir = dir_ / name;
    std::filesystem::create_directories(dir);
    std::string csv = MembersCsvHeader(study);
    for (const MemberRow& r : rows) csv += MembersCsvLine(study, r);
    std::ofstream(dir / "members.csv", std::ios::binary) << csv;
    std::string axes;
    for (const StudyAxis& a : study.axes) {
      axes += std::string(axes.empty() ? "" : ",") + "{\"key\":\"" + a.key + "\"}";
    }
    std::ofstream(dir / "study.json")
        << "{\"title\":\"t\",\"members\":" << study.member_count() << ",\"engines\":"
        << "[\"reference\",\"bullet\"],\"axes\":[" << axes << "],\"wall_s\":1,\"serial_s\":0}";
    return dir;
  }
};

TEST_F(EnsembleReportTest, ASpectrumMarksTheMemberWhereTheEngineDiffers) {
  StudyDef s;
  s.engines = {"reference", "bullet"};
  s.axes = {Axis("pulse.frequency_ratio", {2, 4}), Axis("pulse.amplitude_ratio", {1, 2, 4})};
  std::vector<MemberRow> rows;
  for (long long m = 0; m < 6; ++m) {
    const int ref = m % 3 == 2 ? 1 : 0;  // the largest amplitude overturns
    rows.push_back(Row(m, "reference", ref, 0.3, ref ? 1 : 0));
    rows.push_back(Row(m, "bullet", m == 4 ? 1 : ref, 0.3));  // member 4 differs
  }
  const auto page = WriteEnsembleReport(WriteEnsemble("spectrum", s, rows), dir_ / "out");
  const std::string md = ReadFile(page / "report.md");
  EXPECT_NE(md.find("the same outcome as the reference on 5 of 6 members"), std::string::npos)
      << md;
  EXPECT_NE(md.find("0 members overturn without an impact and 2 after one or more"),
            std::string::npos)
      << md;
  EXPECT_EQ(ReadFile(page / "figures" / "spectrum_0_bullet_differs.dat"), "4 2\n");
  EXPECT_TRUE(std::filesystem::exists(page / "figures" / "spectrum_0.svg"));
}

TEST_F(EnsembleReportTest, FragilitySaysWhetherTheMediansDiffer) {
  StudyDef s;
  s.engines = {"reference", "bullet"};
  std::vector<double> pgas = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.2, 1.5};
  s.axes = {Axis("base.horizontal.seed", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}),
            Axis("base.horizontal.pga_g", pgas)};
  const auto interleave = [&](double engine_median, bool reversed = false) {
    // Member i is (seed, pga) in product order, pga varying fastest; at each PGA x, seed k
    // of 10 fails when k < round(10 Phi(ln(x / median) / beta)): the failures follow a
    // lognormal fragility (beta 0.4) as closely as 10 members allow.
    std::vector<MemberRow> out;
    for (int seed = 0; seed < 10; ++seed) {
      for (size_t j = 0; j < pgas.size(); ++j) {
        const long long m = seed * static_cast<long long>(pgas.size()) + j;
        const double pr = 0.5 * std::erfc(-std::log(pgas[j] / 0.4) / (0.4 * std::sqrt(2.0)));
        const double pe =
            0.5 * std::erfc(-std::log(pgas[j] / engine_median) / (0.4 * std::sqrt(2.0)));
        // PGV/PGA from 0.05 to 0.14 s over the seeds, shuffled against the order in which
        // they fail (the surface's second axis, not a line that separates the outcomes).
        const double ratio = 0.05 + 0.01 * ((3 * seed) % 10);
        out.push_back(Row(m, "reference", seed < std::lround(10 * pr) ? 1 : 0, pgas[j], 0, ratio));
        const int rank = reversed ? 9 - seed : seed;
        out.push_back(Row(m, "bullet", rank < std::lround(10 * pe) ? 1 : 0, pgas[j], 0, ratio));
      }
    }
    return out;
  };
  const auto differ =
      WriteEnsembleReport(WriteEnsemble("differ", s, interleave(0.8)), dir_ / "out");
  const std::string differ_md = ReadFile(differ / "report.md");
  EXPECT_NE(differ_md.find("excludes zero"), std::string::npos);
  // A median twice the reference's is seen on the surface too, by its paired bootstrap.
  EXPECT_NE(differ_md.find("an interval excludes 1"), std::string::npos) << differ_md;
  const auto same = WriteEnsembleReport(WriteEnsemble("same", s, interleave(0.4)), dir_ / "out");
  const std::string same_md = ReadFile(same / "report.md");
  EXPECT_NE(same_md.find("is zero: the two curves are the same"), std::string::npos);
  // Identical members give identical surfaces in every resample: the ratio is 1, exactly.
  EXPECT_NE(same_md.find("across the study's PGV/PGA: 1 [1, 1] at 0.05 s, 1 [1, 1] at "),
            std::string::npos)
      << same_md;
  EXPECT_NE(same_md.find("every interval contains 1"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(same / "figures" / "fragility_surface_0.svg"));
  // The same fractions at every PGA from other members (the seeds' order reversed).
  const auto other =
      WriteEnsembleReport(WriteEnsemble("other", s, interleave(0.4, true)), dir_ / "out");
  const std::string md = ReadFile(other / "report.md");
  EXPECT_NE(md.find("contains zero"), std::string::npos) << md;
  EXPECT_TRUE(std::filesystem::exists(same / "figures" / "fragility_0.svg"));
  EXPECT_TRUE(std::filesystem::exists(same / "figures" / "peak_theta1_vs_pga.svg"));
}

// A motion suite over a stack of three blocks: the fragility of each block's overturning
// (block 1 takes the whole stack down, block 3 falls off block 2; block 2 never overturns
// first), and the peak-angle scatter has a series per block in the renders' trace colours.
TEST_F(EnsembleReportTest, AThreeBlockSuiteHasAFragilityPerBlockAndEveryBlocksPeaks) {
  StudyDef s;
  s.engines = {"reference"};
  s.blocks = 3;
  const std::vector<double> pgas = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0, 1.2, 1.5};
  s.axes = {Axis("base.horizontal.seed", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}),
            Axis("base.horizontal.pga_g", pgas)};
  std::vector<MemberRow> rows;
  int failures[4] = {0, 0, 0, 0};  // by the block that overturned (0: none)
  const auto phi = [](double x, double median) {
    return 0.5 * std::erfc(-std::log(x / median) / (0.4 * std::sqrt(2.0)));
  };
  for (int seed = 0; seed < 10; ++seed) {
    for (size_t j = 0; j < pgas.size(); ++j) {
      // Seed k at PGA x: block 1 (median 0.8 g) when k < 10 Phi, else block 3 (median 0.3 g).
      const int block = seed < std::lround(10 * phi(pgas[j], 0.8))   ? 1
                        : seed < std::lround(10 * phi(pgas[j], 0.3)) ? 3
                                                                     : 0;
      ++failures[block];
      MemberRow r =
          Row(seed * static_cast<long long>(pgas.size()) + j, "reference", block, pgas[j]);
      r.p_radps = {1.9, 2.0, 2.1};
      r.alpha_rad = {0.245, 0.3, 0.35};
      r.peak_theta_rad = {r.peak_theta_rad[0], 0.06, block == 3 ? 1.3 : 0.07};
      rows.push_back(r);
    }
  }
  ASSERT_GT(failures[1], 0);
  ASSERT_GT(failures[3], 0);
  const auto page = WriteEnsembleReport(WriteEnsemble("three", s, rows), dir_ / "out");
  const std::string md = ReadFile(page / "report.md");
  EXPECT_NE(md.find("By the block that overturns"), std::string::npos) << md;
  for (int b : {1, 2, 3}) {
    const std::string row = std::string("| all | reference | block ") + std::to_string(b) +
                            " (blocks " + std::to_string(b) + "-3) | 100 | " +
                            std::to_string(failures[b]) + " | ";
    EXPECT_NE(md.find(row), std::string::npos) << row << "\n" << md;
  }
  EXPECT_NE(md.find("block 2 (blocks 2-3) | 100 | 0 | no fit"), std::string::npos) << md;
  // Every block's peaks, one series each (every member rocked: 100 points), in the trace
  // colours of renders::Palette (block 3: wine, 130 40 90).
  for (int b : {1, 2, 3}) {
    const std::string dat =
        ReadFile(page / "figures" /
                 (std::string("peak_theta_vs_pga_reference_block") + std::to_string(b) + ".dat"));
    EXPECT_EQ(std::count(dat.begin(), dat.end(), '\n'), 100) << b;
  }
  const std::string gp = ReadFile(page / "figures" / "peak_theta_vs_pga_reference.gp");
  EXPECT_NE(gp.find("lc rgb \"#82285a\" title \"block 3\""), std::string::npos) << gp;
  EXPECT_TRUE(std::filesystem::exists(page / "figures" / "peak_theta_vs_pga_reference.svg"));
  EXPECT_FALSE(std::filesystem::exists(page / "figures" / "peak_theta1_vs_pga.svg"));
}

TEST_F(EnsembleReportTest, AMalformedRowNamesItsLine) {
  StudyDef s;
  s.engines = {"reference", "bullet"};
  s.axes = {Axis("pulse.frequency_ratio", {2})};
  const auto dir = WriteEnsemble("bad", s, {Row(0, "reference", 0, 0.3)});
  std::ofstream(dir / "members.csv", std::ios::app) << "1,2,x\n";
  try {
    WriteEnsembleReport(dir, dir_ / "out");
    FAIL() << "no error";
  } catch (const ReportInputError& e) {
    EXPECT_NE(std::string(e.what()).find("members.csv:3: 3 fields"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rockbench::report
