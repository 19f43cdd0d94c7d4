// The report in a real browser: Debian's headless Chromium opens report.html from disk (no
// network), a probe script reads every figure's decoded size and box, and a full-page
// screenshot shows that each figure's box holds a picture, not blank page.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "files/atomic_file.h"
#include "renders/animation.h"
#include "renders/image.h"
#include "report/run/run_report.h"
#include "report/run_folder.h"
#include "scene/history.h"
#include "util/subprocess.h"

namespace rockbench::report {
namespace {

namespace fs = std::filesystem;
using testing_util::RockbenchOk;
using testing_util::SceneFile;
using testing_util::Slurp;

// Runs once the page has loaded (and its images decoded): writes what the test needs into an
// attribute of <body>, which --dump-dom prints.
constexpr const char* kProbe = R"(<script>
window.addEventListener('load', function () {
  setTimeout(function () {
    var out = {height: document.documentElement.scrollHeight, figures: [], videos: []};
    document.querySelectorAll('img.rb-figure').forEach(function (img) {
      var r = img.getBoundingClientRect();
      out.figures.push({natural_w: img.naturalWidth, natural_h: img.naturalHeight,
                        complete: img.complete, x: r.left + window.scrollX,
                        y: r.top + window.scrollY, w: r.width, h: r.height});
    });
    document.querySelectorAll('video').forEach(function (v) {
      out.videos.push({ready: v.readyState, w: v.videoWidth, h: v.videoHeight,
                       error: v.error ? v.error.code : 0});
    });
    document.body.setAttribute('data-rb-probe', JSON.stringify(out));
  }, 300);
});
</script>
)";

std::string HtmlUnescape(std::string s) {
  const std::pair<const char*, const char*> kEntities[] = {
      {"&quot;", "\""}, {"&#39;", "'"}, {"&lt;", "<"}, {"&gt;", ">"}, {"&amp;", "&"}};
  for (const auto& [from, to] : kEntities) {
    for (size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + 1)) {
      s.replace(p, std::string(from).size(), to);
    }
  }
  return s;
}

class ReportBrowserTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("rockbench_report_browser_test_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Chromium with a fresh profile, nothing that reaches the network, a wall-clock limit.
  ProcessResult Chromium(const std::vector<std::string>& extra, const fs::path& page) {
    const fs::path profile = dir_ / ("profile_" + std::to_string(++runs_));
    std::vector<std::string> argv = {chromium_.string(),
                                     "--headless",
                                     "--no-sandbox",
                                     "--disable-gpu",
                                     "--disable-dev-shm-usage",
                                     "--disable-quic",
                                     "--no-first-run",
                                     "--disable-background-networking",
                                     "--disable-component-update",
                                     "--disable-sync",
                                     "--hide-scrollbars",
                                     "--user-data-dir=" + profile.string(),
                                     "--virtual-time-budget=5000"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    argv.push_back("file://" + page.string());
    ProcessOptions options;
    options.timeout_s = 120.0;
    return RunProcess(argv, options);
  }

  fs::path dir_;
  fs::path chromium_;
  int runs_ = 0;
};

TEST_F(ReportBrowserTest, EveryFigureIsDecodedAndVisibleInChromium) {
  const auto chromium = renders::FindExecutable("chromium");
  ASSERT_TRUE(chromium.has_value())
      << "chromium is not installed: the browser check needs Debian's package `chromium` "
         "(scripts/install-deps.sh installs it)";
  chromium_ = *chromium;

  // A short comparison with Bullet, and its full report (figures, keyframes, animation).
  RockbenchOk({"compare", SceneFile("thesis_free_rocking.toml").string(), "--out",
               (dir_ / "free").string(), "--set", "run.duration=1.5"});
  const RunReportResult r = WriteRunReport(dir_ / "free", dir_ / "out");
  const std::string html = Slurp(r.page_dir / "report.html");
  int in_html = 0;
  for (size_t p = html.find("class=\"rb-figure\""); p != std::string::npos;
       p = html.find("class=\"rb-figure\"", p + 1)) {
    ++in_html;
  }
  ASSERT_EQ(in_html, r.figure_count);
  ASSERT_GE(r.figure_count, 6);  // five plots and at least one keyframe

  // Pass 1: the probe (a copy of the page with the script, beside it so the video resolves).
  std::string probe_html = html;
  probe_html.insert(probe_html.rfind("</body>"), kProbe);
  const fs::path probe_page = r.page_dir / "probe.html";
  WriteFileAtomic(probe_page, probe_html);
  const ProcessResult dom = Chromium({"--window-size=1280,1000", "--dump-dom"}, probe_page);
  ASSERT_TRUE(dom.ok()) << "chromium failed (" << dom.exit_code << ", timed out " << dom.timed_out
                        << "):\n"
                        << dom.err;
  const std::string key = "data-rb-probe=\"";
  const size_t at = dom.out.find(key);
  ASSERT_NE(at, std::string::npos) << "the probe did not run; page as dumped:\n"
                                   << dom.out.substr(0, 2000);
  const size_t end = dom.out.find('"', at + key.size());
  const auto probe =
      nlohmann::json::parse(HtmlUnescape(dom.out.substr(at + key.size(), end - at - key.size())));
  const int height = probe["height"].get<int>();
  ASSERT_EQ(static_cast<int>(probe["figures"].size()), r.figure_count);
  for (const auto& f : probe["figures"]) {
    EXPECT_TRUE(f["complete"].get<bool>());
    EXPECT_GT(f["natural_w"].get<int>(), 0) << "a figure did not decode: " << f.dump();
    EXPECT_GT(f["natural_h"].get<int>(), 0) << f.dump();
    EXPECT_GT(f["w"].get<double>(), 100.0) << f.dump();
    EXPECT_GT(f["h"].get<double>(), 50.0) << f.dump();
  }
  // The animation beside the page plays in Debian's Chromium (H.264 MP4): its frames decode
  // at the size the report asked for.
  ASSERT_EQ(probe["videos"].size(), 1u);
  EXPECT_EQ(probe["videos"][0]["error"].get<int>(), 0);
  EXPECT_GE(probe["videos"][0]["ready"].get<int>(), 1);
  EXPECT_EQ(probe["videos"][0]["w"].get<int>(), RunReportOptions{}.animation_width_px);

  // Pass 2: the page itself, whole, in one screenshot of its full height.
  ASSERT_LT(height, 16000) << "page too tall for one screenshot";
  const fs::path shot = dir_ / "page.png";
  const ProcessResult s =
      Chromium({"--window-size=1280," + std::to_string(height), "--screenshot=" + shot.string()},
               r.page_dir / "report.html");
  ASSERT_TRUE(s.ok()) << s.err;
  const renders::Image img = renders::ReadPng(shot);
  ASSERT_EQ(img.width_px, 1280);
  ASSERT_GE(img.height_px, height);
  for (const auto& f : probe["figures"]) {
    SCOPED_TRACE(f.dump());
    // Inside the border (1 px) and a little margin: the picture's own pixels.
    const int x0 = static_cast<int>(f["x"].get<double>()) + 3;
    const int y0 = static_cast<int>(f["y"].get<double>()) + 3;
    const int x1 = static_cast<int>(f["x"].get<double>() + f["w"].get<double>()) - 3;
    const int y1 = static_cast<int>(f["y"].get<double>() + f["h"].get<double>()) - 3;
    ASSERT_TRUE(x0 >= 0 && y0 >= 0 && x1 <= img.width_px && y1 <= img.height_px && x1 > x0 &&
                y1 > y0);
    // Not blank: the box's most common colour (its background) covers less than 99.5% of it.
    std::map<int, long> colours;
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        const renders::Rgb c = img.at(x, y);
        ++colours[(c.r << 16) | (c.g << 8) | c.b];
      }
    }
    long most = 0;
    for (const auto& [c, n] : colours) most = std::max(most, n);
    const long all = static_cast<long>(x1 - x0) * (y1 - y0);
    EXPECT_GE(colours.size(), 3u);
    EXPECT_LT(static_cast<double>(most), 0.995 * static_cast<double>(all))
        << "the figure's box is (almost) one colour: " << most << " of " << all << " pixels";
  }
}

}  // namespace
}  // namespace rockbench::report
