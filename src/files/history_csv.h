#pragma once
/// history.csv and events.csv: the files of a History (scene/history.h), written and read back.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scene/history.h"

namespace rockbench {

/// CSV header of history.csv: "t,theta1,omega1,mode" (one block), "t,theta1,theta2,omega1,
/// omega2,mode" (two), "t,theta1,...,thetaN,omega1,...,omegaN,mode" (N); with slip and lift,
/// ",u1,...,uN,z1,...,zN" after those.
std::string HistoryCsvHeader(int blocks, bool slip_and_lift = false);
/// The header of a history of `blocks` bodies of another kind than the planar block: "t", each
/// quantity of its state for every body (BodyColumn), "mode".
std::string KindHistoryCsvHeader(const BodyKind& kind, int blocks);
/// The history as CSV text (deterministic formatting: "%.9f" for times, "%.12e" for angles and
/// rates, the mode by ConfigurationName: the thesis's names for one or two blocks, the letters
/// beyond).
std::string HistoryToCsv(const History& history);
/// events.csv text. One or two blocks: header "t,kind,mode_before,mode_after,omega1_before,
/// omega2_before,omega1_after,omega2_after,energy_before_j,energy_after_j,note" (a single block
/// writes its omega2 columns as 0). N >= 3 blocks: "t,kind,mode_before,mode_after,
/// omega1_before,...,omegaN_before,omega1_after,...,omegaN_after,energy_before_j,
/// energy_after_j,note". Same number formats; commas in kind/note become ';'.
std::string EventsToCsv(const History& history);
/// Reads a history.csv (any block count and body kind, from the header). Throws std::runtime_error
/// naming file and line.
History ReadHistoryCsv(const std::filesystem::path& path);
/// Reads an events.csv (EventsToCsv's format) of a stack of `blocks` bodies (0: any) of the kind
/// its header names, as ReadHistoryCsv reads a history: planar blocks (1 or 2 share a header: 2
/// when `blocks` is 0; N >= 3 is read from the header, which must then agree) or bodies of
/// another kind (every body's rate BodyColumn(event_rate_stem, k) before and after, the modes by
/// the kind's contact names: a cylinder's "t,kind,mode_before,mode_after,tilt_rate1_before,
/// tilt_rate1_after,energy_before_j,energy_after_j,note"); the rates go to the events'
/// omega_before_radps and omega_after_radps. A non-empty `shape` (a history's) is the kind the
/// file must be of. Throws std::runtime_error naming file and line; std::invalid_argument for an
/// unknown `shape`.
std::vector<Event> ReadEventsCsv(const std::filesystem::path& path, int blocks = 0,
                                 std::string_view shape = {});

}  // namespace rockbench
