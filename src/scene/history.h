#pragma once
/// Histories and events: what every engine (the reference included) returns, and their files.
#include <filesystem>
#include <string>
#include <vector>

#include "scene/mode.h"

namespace rockbench {

/// One sample of the state. For a single block theta2/omega2 are unused (written as absent).
struct Sample {
  double t_s = 0.0;
  double theta1_rad = 0.0;
  double theta2_rad = 0.0;
  double omega1_radps = 0.0;
  double omega2_radps = 0.0;
  Mode mode = Mode::kRest;
};

/// An event: impact, transition, initiation, rest, overturn, assumption violated, ...
struct Event {
  double t_s = 0.0;
  std::string kind;  ///< "ground_impact", "interface_impact", "initiation", "transition", "rest",
                     ///< "overturn", "assumption_violated"
  Mode mode_before = Mode::kRest;
  Mode mode_after = Mode::kRest;
  double omega1_before = 0.0, omega2_before = 0.0;     ///< rad/s
  double omega1_after = 0.0, omega2_after = 0.0;       ///< rad/s
  double energy_before_j = 0.0, energy_after_j = 0.0;  ///< kinetic + potential, J
  std::string note;  ///< free text (no commas), e.g. "inadmissible: ..." or a criterion name
};

struct History {
  bool two_blocks = true;
  std::vector<Sample> samples;
  std::vector<Event> events;
};

/// CSV header of history.csv: "t,theta1,theta2,omega1,omega2,mode" (two blocks) or
/// "t,theta1,omega1,mode" (one block).
std::string HistoryCsvHeader(bool two_blocks);
/// The history as CSV text (deterministic formatting: "%.9f" for times, "%.12e" for angles and
/// rates, the mode by ModeName). A single-block history has no theta2/omega2 columns.
std::string HistoryToCsv(const History& history);
/// events.csv text: header "t,kind,mode_before,mode_after,omega1_before,omega2_before,
/// omega1_after,omega2_after,energy_before_j,energy_after_j,note"; same number formats; commas
/// in kind/note become ';'.
std::string EventsToCsv(const History& history);
/// Reads a history.csv (either header). Throws std::runtime_error naming file and line.
History ReadHistoryCsv(const std::filesystem::path& path);
/// Reads an events.csv (EventsToCsv's format). Throws std::runtime_error naming file and line.
std::vector<Event> ReadEventsCsv(const std::filesystem::path& path);

/// The whole content of a file (bytes as stored). Throws std::runtime_error naming the file
/// when it cannot be opened or read.
std::string ReadTextFile(const std::filesystem::path& path);

/// Writes `text` to `path` atomically: to "<path>.tmp.<pid>" in the same folder, fsync, then
/// rename over `path`. Creates missing parent folders. Throws std::runtime_error.
void WriteFileAtomic(const std::filesystem::path& path, const std::string& text);

}  // namespace rockbench
