// Studies of a cylinder rocking in 3-D (issue 41): the derived axis base.pga_resultant_g against
// its closed form and an independent fine-grid search, axes paired with zip_with, planar
// engines refused before anything runs, and `rockbench ensemble` on a cylinder study end to end
// with members.csv's overturn columns checked against the members' own runs and the physics of
// the onset threshold.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"
#include "motion/ground_motion.h"
#include "motion/intensity.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "scene/scene.h"
#include "study/study.h"
#include "util/format.h"

namespace rockbench {
namespace {

using testing_util::ReadFile;
using testing_util::Rockbench;

const std::filesystem::path kRecords = std::filesystem::path(ROCKBENCH_SOURCE_DIR) / "records";

// A slender cylinder, D = 0.3 m, H = 1.2 m (onset from rest at (D/H) g = 0.25 g), under the two
// horizontal components of Rinaldi (Northridge 1994): 228 along +x (scale 0.5), 318 along +y
// (scale 0.8), 5 s.
std::string CylinderSceneToml(const std::string& extra = "") {
  return "title = \"cylinder\"\n"
         "[[block]]\nshape = \"cylinder\"\ndiameter = 0.3\nheight = 1.2\ndensity = 2500.0\n"
         "[base.horizontal]\nfile = \"" +
         (kRecords / "northridge1994_rinaldi_receiving_sta_228.AT2").string() +
         "\"\nscale = 0.5\n"
         "[base.transverse]\nfile = \"" +
         (kRecords / "northridge1994_rinaldi_receiving_sta_318.AT2").string() +
         "\"\nscale = 0.8\n"
         "[run]\nduration = 5.0\noutput_interval = 0.01\n"
         "[model]\noverturn_angle = 1.25\n" +
         extra;
}

class CylinderStudyTest : public testing_util::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    Write("cylinder.toml", CylinderSceneToml());
  }
  std::string Error(const std::string& study_text) {
    try {
      LoadStudy(Write("study.toml", study_text));
    } catch (const SceneError& e) {
      return e.what();
    }
    return "no error";
  }
};

// The resultant's peak by an independent search: both components (sampled records, piecewise
// linear between samples) interpolated here on a grid of step h, m/s^2.
double FineGridResultant(const MotionComponent& x, const MotionComponent& y, double t_end_s,
                         double h_s) {
  const auto at = [](const MotionComponent& c, double t) {
    const std::vector<double>& a = c.samples_mps2();
    const double u = (t - c.t0_s()) / c.dt_s();
    if (u < 0.0 || u > static_cast<double>(a.size() - 1)) return 0.0;
    const auto i = static_cast<size_t>(u);
    if (i + 1 >= a.size()) return a.back();
    return a[i] + (u - static_cast<double>(i)) * (a[i + 1] - a[i]);
  };
  double peak = 0.0;
  for (double t = 0.0; t <= t_end_s; t += h_s)
    peak = std::max(peak, std::hypot(at(x, t), at(y, t)));
  return peak;
}

// base.pga_resultant_g = 0.3: the member's two components, scaled by one factor, have the peak
// resultant 0.3 g0, found again here by a search of its own over the member's samples; the
// ratio of the two components' scales (and so of their amplitudes) is the base scene's.
TEST_F(CylinderStudyTest, PgaResultantScalesBothComponentsToTheTargetKeepingTheirRatio) {
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"cylinder.toml\"\n"
                                     "[[axis]]\nkey = \"base.pga_resultant_g\"\n"
                                     "values = [0.3]\n"));
  ASSERT_TRUE(s.cylinder);
  const Scene base = LoadScene(dir_ / "cylinder.toml");
  const Scene m = MemberScene(s, 0);
  ASSERT_TRUE(m.horizontal && m.transverse);
  // Both multiplied by one factor k: 0.5 k / (0.8 k) is 0.625 to the rounding of two products.
  EXPECT_NEAR(m.horizontal->scale / m.transverse->scale,
              base.horizontal->scale / base.transverse->scale, 4e-16);
  EXPECT_NE(m.horizontal->scale, base.horizontal->scale);
  const MotionComponent x = MotionComponent::FromDef(*m.horizontal);
  const MotionComponent y = MotionComponent::FromDef(*m.transverse);
  // Rinaldi's two components share their sample times (dt 0.01 s): the resultant's peak is the
  // largest hypot over the samples, exactly (between samples |a|^2 is a convex quadratic).
  ASSERT_EQ(x.dt_s(), y.dt_s());
  ASSERT_EQ(x.samples_mps2().size(), y.samples_mps2().size());
  double peak = 0.0;
  const auto keep = static_cast<size_t>(std::floor(m.run.duration_s / x.dt_s())) + 1;
  for (size_t i = 0; i < keep; ++i) {
    peak = std::max(peak, std::hypot(x.samples_mps2()[i], y.samples_mps2()[i]));
  }
  // 0.3 g0 to rounding: a few ulps of the scale factor and of hypot (2e-15 relative).
  EXPECT_NEAR(peak / kStandardGravity_mps2, 0.3, 0.3 * 2e-15);
  // The x component alone is below the resultant (its own PGA is not the target).
  EXPECT_LT(MeasureIntensity(x, m.run.duration_s).pga_mps2, peak);
}

// A rotating field, x = A sin(2 pi f t), y = A sin(2 pi f t + 90 deg): its resultant is A at
// every instant (sin^2 + cos^2 = 1), so base.pga_resultant_g = 0.3 makes both amplitudes 0.3 g
// (amplitude_g times scale), whatever the sampling.
TEST_F(CylinderStudyTest, PgaResultantOfARotatingFieldIsItsAmplitude) {
  Write("rotating.toml",
        "title = \"rotating\"\n"
        "[[block]]\nshape = \"cylinder\"\ndiameter = 0.5\nheight = 1.5\ndensity = 2500.0\n"
        "[base.horizontal]\nkind = \"harmonic\"\namplitude_g = 0.12\nfrequency_hz = 2.0\n"
        "[base.transverse]\nkind = \"harmonic\"\namplitude_g = 0.12\nfrequency_hz = 2.0\n"
        "phase_deg = 90\n"
        "[run]\nduration = 3.0\n");
  const StudyDef s = LoadStudy(Write("study.toml",
                                     "scene = \"rotating.toml\"\n"
                                     "[[axis]]\nkey = \"base.pga_resultant_g\"\n"
                                     "values = [0.3]\n"));
  const Scene m = MemberScene(s, 0);
  // sin^2 + cos^2 = 1 to 2 ulps at each sample: the factor is 0.3 / 0.12 to about 1e-15.
  EXPECT_NEAR(m.horizontal->amplitude_g * m.horizontal->scale, 0.3, 1e-15);
  EXPECT_NEAR(m.transverse->amplitude_g * m.transverse->scale, 0.3, 1e-15);
  // The x component alone, base.horizontal.pga_g = 0.3, leaves y as it was.
  const StudyDef sx = LoadStudy(Write("study_x.toml",
                                      "scene = \"rotating.toml\"\n"
                                      "[[axis]]\nkey = \"base.horizontal.pga_g\"\n"
                                      "values = [0.3]\n"));
  const Scene mx = MemberScene(sx, 0);
  EXPECT_NEAR(mx.horizontal->amplitude_g * mx.horizontal->scale, 0.3, 1e-6);
  EXPECT_EQ(mx.transverse->scale, 1.0);
}

// Two records of different sample intervals (0.02 s and 0.03 s, so that the peak may fall at a
// sample of either): MeasureResultantPga is the maximum of |a| over [0, T], which a search on a
// grid of 1e-5 s finds from below within the grid's resolution (the largest slope times h).
TEST(ResultantPga, TwoRecordsOfDifferentIntervalsAgainstAFineGrid) {
  std::vector<double> ax, ay;
  for (int i = 0; i < 200; ++i) ax.push_back(3.0 * std::sin(0.37 * i) + std::cos(1.3 * i));
  for (int i = 0; i < 134; ++i) ay.push_back(2.5 * std::cos(0.51 * i) - std::sin(2.1 * i));
  const MotionComponent x = MotionComponent::FromSamples(ax, 0.02, 0.0, "x");
  const MotionComponent y = MotionComponent::FromSamples(ay, 0.03, 0.0, "y");
  const double t_end = 3.9;
  const double measured = MeasureResultantPga(x, y, t_end).pga_mps2;
  const double h = 1e-5;
  const double grid = FineGridResultant(x, y, t_end, h);
  // Slopes at most (4 + 4) / 0.02 + (3.5 + 3.5) / 0.03 < 700 m/s^3 per component pair.
  EXPECT_GE(measured, grid * (1.0 - 1e-14));
  EXPECT_LE(measured - grid, 700.0 * h);
  // One component: its PGA (MeasureIntensity's, on the same samples).
  EXPECT_EQ(MeasureResultantPga(x, std::nullopt, t_end).pga_mps2,
            MeasureIntensity(x, t_end).pga_mps2);
}

// zip_with pairs an axis's values with an earlier axis's, one to one: 2 pairs x 3 PGAs = 6
// members, the pair's two files always together.
TEST_F(CylinderStudyTest, ZipWithPairsTwoAxesInsideTheProduct) {
  const std::string x1 = (kRecords / "kobe1995_kjma_090.AT2").string();
  const std::string y1 = (kRecords / "kobe1995_kjma_000.AT2").string();
  const std::string x2 = (kRecords / "northridge1994_sylmar_converter_sta_052.AT2").string();
  const std::string y2 = (kRecords / "northridge1994_sylmar_converter_sta_142.AT2").string();
  const std::string axes =
      "[[axis]]\nkey = \"base.horizontal.file\"\nvalues = [\"" + x1 + "\", \"" + x2 +
      "\"]\n"
      "[[axis]]\nkey = \"base.transverse.file\"\nzip_with = \"base.horizontal.file\"\n"
      "values = [\"" +
      y1 + "\", \"" + y2 + "\"]\n";
  const StudyDef s = LoadStudy(Write("study.toml", "scene = \"cylinder.toml\"\n" + axes +
                                                       "[[axis]]\nkey = \"base.pga_resultant_g\"\n"
                                                       "values = [0.2, 0.4, 0.6]\n"));
  ASSERT_EQ(s.member_count(), 6);
  EXPECT_EQ(s.ValueIndices(0), (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(s.ValueIndices(4), (std::vector<int>{1, 1, 1}));
  EXPECT_EQ(s.ValueIndices(5), (std::vector<int>{1, 1, 2}));
  const Scene m4 = MemberScene(s, 4);
  EXPECT_EQ(m4.horizontal->file.string(), x2);
  EXPECT_EQ(m4.transverse->file.string(), y2);
  // Errors name the file and the axis's line.
  EXPECT_NE(Error("scene = \"cylinder.toml\"\n"
                  "[[axis]]\nkey = \"base.transverse.file\"\nzip_with = \"base.horizontal.file\"\n"
                  "values = [\"" +
                  y1 + "\"]\n")
                .find("study.toml:4: axis base.transverse.file: zip_with: expected the key of an "
                      "earlier axis"),
            std::string::npos);
  EXPECT_NE(Error("scene = \"cylinder.toml\"\n"
                  "[[axis]]\nkey = \"base.horizontal.file\"\nvalues = [\"" +
                  x1 + "\", \"" + x2 +
                  "\"]\n"
                  "[[axis]]\nkey = \"base.transverse.file\"\nzip_with = \"base.horizontal.file\"\n"
                  "values = [\"" +
                  y1 + "\"]\n")
                .find("study.toml:5: axis base.transverse.file: zip_with = "
                      "\"base.horizontal.file\": 1 values, axis base.horizontal.file 2"),
            std::string::npos);
  // The resultant's axis and the x component's PGA axis both scale x: refused together.
  EXPECT_NE(Error("scene = \"cylinder.toml\"\n"
                  "[[axis]]\nkey = \"base.pga_resultant_g\"\nvalues = [0.2]\n"
                  "[[axis]]\nkey = \"base.horizontal.pga_g\"\nvalues = [0.2]\n")
                .find("study.toml:2: axis base.pga_resultant_g scales [base.horizontal] too"),
            std::string::npos);
}

// A planar engine in a cylinder study is refused when the study is read, naming the study file,
// the line of `engines` and the engine; a planar study with base.pga_resultant_g (no transverse
// component) scales its one component to that PGA.
TEST_F(CylinderStudyTest, APlanarEngineIsRefusedNamingTheFileLineAndEngine) {
  if (FindEngine("box2d") == nullptr) GTEST_SKIP() << "box2d is not built";
  const std::string e = Error(
      "title = \"t\"\nscene = \"cylinder.toml\"\nengines = [\"reference\", \"ode\", \"box2d\"]\n");
  const std::string where = (dir_ / "study.toml").string() + ":3: engines: \"box2d\"";
  EXPECT_NE(e.find(where), std::string::npos) << e;
  EXPECT_NE(e.find("not the cylinder of the study's scene"), std::string::npos) << e;
}

// members.csv's cells of a line, by the header's column names.
std::vector<std::map<std::string, std::string>> CsvRows(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) header.push_back(c);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < std::min(cells.size(), header.size()); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

// `rockbench ensemble` on a cylinder study: Rinaldi's two components at a resultant PGA of
// 0.1 g and 1.0 g, the reference and ODE, 5 s. The row of each run carries its own run's outcome
// (the member's scene run again here: the same overturn time, azimuth and peak, to the printed
// digits), and the physics of the onset: at 0.1 g, below the threshold (D/H) g = 0.25 g in
// every direction at every instant, the cylinder cannot leave its face (peak tilt 0 for the
// reference, whose onset is exact; an engine's contact noise stays below 1e-6 rad); at 1.0 g,
// four times the threshold, the reference overturns (measured: at 3.83 s).
TEST_F(CylinderStudyTest, ACylinderStudyRunsEndToEndWithTheOverturnColumns) {
  if (FindEngine("ode") == nullptr) GTEST_SKIP() << "ode is not built";
  const std::filesystem::path study =
      Write("study.toml",
            "scene = \"cylinder.toml\"\nengines = [\"reference\", \"ode\"]\n"
            "[[axis]]\nkey = \"base.pga_resultant_g\"\nvalues = [0.1, 1.0]\n");
  const auto run =
      Rockbench("ensemble " + study.string() + " --out " + (dir_ / "out").string() + " --jobs 2");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string csv = ReadFile(dir_ / "out" / "members.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "member,base.pga_resultant_g,p1_radps,alpha1_rad,pga_g,pga_resultant_g,pgv_mps,pgd_m,"
            "arias_mps,d5_95_s,pulse_period_s,engine,status,overturned_block,overturn_t_s,"
            "overturn_azimuth_rad,peak_tilt1_rad,wall_s,converged,reference_overturned_block,"
            "overturn_agree,detail");
  const auto rows = CsvRows(csv);
  ASSERT_EQ(rows.size(), 4u);
  const StudyDef s = LoadStudy(study);
  for (const auto& row : rows) {
    SCOPED_TRACE(row.at("member") + " " + row.at("engine"));
    const int64_t member = std::stoll(row.at("member"));
    // alpha = atan(D / H); the resultant PGA is the axis's value (to rounding).
    EXPECT_EQ(row.at("alpha1_rad"), ShortestText(std::atan2(0.3, 1.2)));
    EXPECT_NEAR(std::stod(row.at("pga_resultant_g")), std::stod(row.at("base.pga_resultant_g")),
                1e-15);
    // The member's own run.
    const Scene scene = MemberScene(s, member);
    const GroundMotion motion = GroundMotion::FromScene(scene);
    const EngineRun own = RunEngine(row.at("engine"), scene, motion);
    EXPECT_EQ(row.at("status"), own.summary.at("status").get<std::string>());
    const nlohmann::json& over = own.summary.at("overturn");
    if (over.is_null()) {
      EXPECT_EQ(row.at("overturned_block"), "");
      EXPECT_EQ(row.at("overturn_t_s"), "");
      EXPECT_EQ(row.at("overturn_azimuth_rad"), "");
      EXPECT_EQ(row.at("peak_tilt1_rad"),
                ShortestText(own.summary.at("peaks").at("tilt1").at("abs_rad").get<double>()));
    } else {
      EXPECT_EQ(row.at("overturned_block"), "1");
      EXPECT_EQ(row.at("overturn_t_s"), ShortestText(over.at("t_s").get<double>()));
      EXPECT_EQ(row.at("overturn_azimuth_rad"), ShortestText(over.at("azimuth_rad").get<double>()));
      // An overturned cylinder's peak is the overturn angle.
      EXPECT_EQ(row.at("peak_tilt1_rad"), "1.25");
      const double azimuth = std::stod(row.at("overturn_azimuth_rad"));
      EXPECT_GT(azimuth, -M_PI);
      EXPECT_LE(azimuth, M_PI);
    }
    if (row.at("engine") == "reference") {
      EXPECT_EQ(row.at("converged"), "true");
      EXPECT_EQ(row.at("overturn_agree"), "");
    } else {
      // The engine's row says whether the member's reference overturned, and whether it agrees.
      const bool ref_over = rows[member * 2].at("overturned_block") == "1";
      EXPECT_EQ(row.at("reference_overturned_block"), ref_over ? "1" : "");
      EXPECT_EQ(row.at("overturn_agree"),
                (row.at("overturned_block") == "1") == ref_over ? "true" : "false");
    }
  }
  // The physics: member 0 (0.1 g) never leaves its face; member 1 (1.0 g) overturns.
  EXPECT_EQ(rows[0].at("status"), "completed");
  EXPECT_EQ(rows[0].at("peak_tilt1_rad"), "0");
  EXPECT_EQ(rows[1].at("overturned_block"), "");
  EXPECT_LT(std::stod(rows[1].at("peak_tilt1_rad")), 1e-6);
  EXPECT_EQ(rows[2].at("status"), "overturned");
  EXPECT_LT(std::stod(rows[2].at("overturn_t_s")), 5.0);
  // study.json says the body; the report reads the folder and says what overturned means.
  EXPECT_NE(ReadFile(dir_ / "out" / "study.json").find("\"body\": \"cylinder\""),
            std::string::npos);
  const auto report =
      Rockbench("report " + (dir_ / "out").string() + " --out " + (dir_ / "report").string());
  ASSERT_EQ(report.exit_code, 0) << report.output;
  const std::string md = ReadFile(dir_ / "report" / "out" / "report.md");
  EXPECT_NE(md.find("overturned = its tilt reached the overturn angle"), std::string::npos);
}

}  // namespace
}  // namespace rockbench
