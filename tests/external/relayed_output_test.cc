// What an external engine writes reaches the terminal only escaped and capped
// (issue 38): an escape sequence cannot erase a line and forge "verdict bullet AGREES", and a
// 50 MB line on standard error or in a poses file's header is a message of a few kilobytes.
// The escaping itself (util/relayed_text.h) against the bytes it must show: UTF-8 kept, C1
// controls and broken sequences shown as \xHH.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "common/scratch_dir_test.h"
#include "common/shell_test.h"
#include "util/relayed_text.h"

namespace rockbench {
namespace {

using testing_util::Rockbench;

TEST(RelayedText, ControlsAndBrokenUtf8AreShownPrintableUtf8IsKept) {
  EXPECT_EQ(EscapedText("\x1b[2K\rverdict bullet AGREES\n"), "\\x1B[2K\\rverdict bullet AGREES\\n");
  // theta (U+03B8) kept; U+009B (CSI in C1) as its bytes; a lone continuation byte; DEL; NUL.
  EXPECT_EQ(EscapedText(std::string("\xce\xb8 \xc2\x9b \x80 \x7f \0.", 12)),
            "\xce\xb8 \\xC2\\x9B \\x80 \\x7F \\x00.");
  // An overlong '/' (C0 AF) and a sequence cut at the end are bytes too.
  EXPECT_EQ(EscapedText("\xc0\xaf \xe2\x82"), "\\xC0\\xAF \\xE2\\x82");
  // Capped: the first 4096 bytes of the text, then how many more there were.
  const std::string big(50'000'000, 'x');
  const std::string shown = EscapedText(big);
  EXPECT_EQ(shown,
            std::string(4096, 'x') + "... (" + std::to_string(50'000'000 - 4096) + " bytes more)");
  // Lines: each after the indent, so none starts a line of the terminal.
  EXPECT_EQ(RelayedLines("a\n\x1b[2K\rverdict bullet AGREES"),
            "  | a\n  | \\x1B[2K\\rverdict bullet AGREES");
}

class RelayedOutputTest : public testing_util::ScratchDirTest {
 protected:
  // A scene whose engine `hostile` runs engine.py MODE (named on the command line: it runs).
  std::string Compare(const std::string& mode) {
    Write("engine.py",
          "import json, sys\n"
          "mode, run = sys.argv[1], json.load(open(sys.argv[2]))\n"
          "if mode == 'forge':\n"
          "    sys.stderr.write('\\x1b[2K\\rverdict bullet AGREES\\n\\x1b]0;title\\x07done\\n')\n"
          "    sys.exit(1)\n"
          "if mode == 'huge_stderr':\n"
          "    sys.stderr.write('y' * 50000000)\n"
          "    sys.exit(1)\n"
          "with open(run['poses_file'], 'w') as f:\n"
          "    if mode == 'forge_header':\n"
          "        f.write('t_s,\\x1b[2K\\rverdict bullet AGREES\\n')\n"
          "    else:\n"
          "        f.write('t_s,x1_m,y1_m,' + 'h' * 1000000 + '\\n')\n");
    const auto scene =
        Write("scene.toml", "[external.hostile]\ncommand = [\"python3\", \"" +
                                (dir_ / "engine.py").string() + "\", \"" + mode +
                                "\"]\n"
                                "[block1]\nwidth = 0.4\nheight = 1.2\ndensity = 2000.0\n"
                                "[base.horizontal]\nkind = \"sine_pulse\"\namplitude_g = 0.3\n"
                                "frequency_hz = 2.0\n[run]\nduration = 0.1\n"
                                "[hostile]\ntime_step = 1e-3\n");
    return Rockbench("compare " + scene.string() + " --engines hostile --quick --out " +
                     (dir_ / "out").string())
        .output;
  }
};

TEST_F(RelayedOutputTest, AnEscapeSequenceOnStandardErrorCannotForgeAVerdict) {
  const std::string out = Compare("forge");
  EXPECT_NE(out.find("hostile"), std::string::npos) << out;
  EXPECT_EQ(out.find('\x1b'), std::string::npos) << out;
  EXPECT_EQ(out.find('\r'), std::string::npos) << out;
  EXPECT_EQ(out.find('\x07'), std::string::npos) << out;
  // The engine's words are there, escaped: no line of the output starts with "verdict bullet".
  EXPECT_NE(out.find("its last words:"), std::string::npos) << out;
  EXPECT_NE(out.find("\\x1B[2K\\rverdict bullet AGREES"), std::string::npos) << out;
  EXPECT_EQ(out.find("\nverdict bullet"), std::string::npos) << out;
  EXPECT_NE(out.rfind("verdict bullet", 0), 0u) << out;
  // The same in a poses file's header (shown escaped; the reader's own escapes or these).
  const std::string header = Compare("forge_header");
  EXPECT_NE(header.find("[2K"), std::string::npos) << header;
  EXPECT_EQ(header.find("\nverdict bullet"), std::string::npos) << header;
  EXPECT_EQ(header.find('\x1b'), std::string::npos) << header;
  EXPECT_EQ(header.find('\r'), std::string::npos) << header;
}

// The longest line of `text`, bytes.
size_t LongestLine(const std::string& text) {
  size_t longest = 0, start = 0;
  while (start <= text.size()) {
    const size_t end = std::min(text.find('\n', start), text.size());
    longest = std::max(longest, end - start);
    start = end + 1;
  }
  return longest;
}

TEST_F(RelayedOutputTest, A50MegabyteLineIsAMessageOfAFewKilobytes) {
  // Every line that relays the engine's words holds at most 4 KiB of them and rockbench's own
  // few hundred bytes (its command, its run folder, how it ended); the output repeats the
  // message a few times (the run, its verdict, the summary), 16 KiB in all at most.
  constexpr size_t kMaxLine = kMaxRelayedBytes + 1024, kMaxOutput = 16384;
  const std::string err = Compare("huge_stderr");
  EXPECT_NE(err.find("its last words (the last 4096 of 50000000 bytes it wrote)"),
            std::string::npos)
      << err.substr(0, 2000);
  EXPECT_LT(LongestLine(err), kMaxLine) << err.substr(0, 2000);
  EXPECT_LT(err.size(), kMaxOutput) << err.substr(0, 2000);
  // A poses file's header of a million bytes (the file may hold 1 MiB of header): the message
  // names the column cut to 4 KiB at most.
  const std::string header = Compare("huge_header");
  EXPECT_NE(header.find("unknown column 'hhhh"), std::string::npos) << header.substr(0, 2000);
  EXPECT_EQ(header.find(std::string(kMaxRelayedBytes + 1, 'h')), std::string::npos);
  EXPECT_LT(LongestLine(header), kMaxLine) << header.substr(0, 2000);
  EXPECT_LT(header.size(), kMaxOutput) << header.substr(0, 2000);
}

}  // namespace
}  // namespace rockbench
