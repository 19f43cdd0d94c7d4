// ParallelFor runs each index once whatever the thread count and rethrows a job's exception;
// ProgressLine draws only on a terminal.
#include "run/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockbench {
namespace {

TEST(ParallelFor, RunsEveryIndexOnceInItsSlot) {
  for (int threads : {1, 2, 5, 0}) {
    std::vector<int> slot(100, 0);
    std::atomic<int> progress_calls{0};
    ParallelFor(
        100, threads, [&](int i) { slot[i] += i + 1; },
        [&](int done, int total) {
          EXPECT_LE(done, total);
          ++progress_calls;
        });
    for (int i = 0; i < 100; ++i) EXPECT_EQ(slot[i], i + 1) << threads;
    EXPECT_EQ(progress_calls.load(), 100);
  }
  ParallelFor(0, 2, [](int) { FAIL(); });
}

TEST(ParallelFor, RethrowsAJobsException) {
  EXPECT_THROW(ParallelFor(50, 3,
                           [](int i) {
                             if (i == 17) throw std::runtime_error("member 17");
                           }),
               std::runtime_error);
}

std::string Drawn(bool terminal) {
  std::FILE* f = std::tmpfile();
  {
    ProgressLine line("members", f, terminal);
    line.Update(0, 4);
    line.Update(4, 4);
  }
  std::rewind(f);
  std::string text;
  for (int c; (c = std::fgetc(f)) != EOF;) text.push_back(static_cast<char>(c));
  std::fclose(f);
  return text;
}

TEST(ProgressLine, DrawsDoneTotalElapsedAndRemainingOnATerminalOnly) {
  const std::string t = Drawn(true);
  EXPECT_NE(t.find("\rmembers: 4/4, "), std::string::npos) << t;
  EXPECT_NE(t.find("s elapsed, about "), std::string::npos) << t;
  EXPECT_EQ(t.back(), '\n');
  EXPECT_EQ(Drawn(false), "");
}

}  // namespace
}  // namespace rockbench
