// Page: the HTML is self-contained (figures embedded, warnings first) and the Markdown twin
// refers to the same files.
#include "report/common/page.h"

#include <gtest/gtest.h>

#include "common/scratch_dir_test.h"

namespace rockbench::report {
namespace {

using PageTest = testing_util::ScratchDirTest;

TEST(Base64, MatchesRfc4648TestVectors) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Base64(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(HtmlEscape, EscapesMarkup) {
  EXPECT_EQ(HtmlEscape("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;");
}

TEST_F(PageTest, HtmlEmbedsFiguresAndPutsWarningsFirst) {
  Write("fig.svg", "<svg xmlns='http://www.w3.org/2000/svg'/>");
  Page page("Scene <one>");
  page.Heading("Angles");
  page.Figure("fig.svg", "theta1 against time");
  page.Warning("block 2 slides: friction 0.3 is below the 0.45 the model needs");
  page.Table({"metric", "value"}, {{"max error", "1e-3 rad"}});
  const std::string html = page.Html(dir_);
  EXPECT_NE(html.find("<title>Scene &lt;one&gt;</title>"), std::string::npos);
  const size_t warning = html.find("block 2 slides");
  ASSERT_NE(warning, std::string::npos);
  EXPECT_LT(warning, html.find("<h2>Angles</h2>"));
  EXPECT_NE(html.find("src=\"data:image/svg+xml;base64," +
                      Base64("<svg xmlns='http://www.w3.org/2000/svg'/>") + "\""),
            std::string::npos);
  EXPECT_NE(html.find("<td>1e-3 rad</td>"), std::string::npos);
  EXPECT_EQ(page.figures().size(), 1u);
}

TEST_F(PageTest, AMissingFigureIsAnErrorNamingIt) {
  Page page("p");
  page.Figure("nowhere.svg", "missing");
  try {
    page.Html(dir_);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere.svg"), std::string::npos);
  }
}

TEST(Page, MarkdownRefersToTheFilesAndEscapesTableCells) {
  Page page("p");
  page.Warning("uplift");
  page.Figure("figures/a.svg", "A");
  page.Table({"x|y", "z"}, {{"1", "2"}});
  const std::string md = page.Markdown();
  EXPECT_NE(md.find("> - uplift"), std::string::npos);
  EXPECT_NE(md.find("![A](figures/a.svg)"), std::string::npos);
  EXPECT_NE(md.find("| x\\|y | z |"), std::string::npos);
  EXPECT_NE(md.find("|---|---|"), std::string::npos);
}

TEST(Page, RejectsRaggedTablesAndUnknownFigureTypes) {
  Page page("p");
  EXPECT_THROW(page.Table({"a", "b"}, {{"1"}}), std::invalid_argument);
  EXPECT_THROW(page.Figure("x.bmp", "bmp"), std::runtime_error);
}

}  // namespace
}  // namespace rockbench::report
