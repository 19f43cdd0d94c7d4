#pragma once
/// The sections of an ensemble report (ensemble_report.cc assembles them): overturning spectra
/// of pulse studies (ensemble_spectra.cc), fragility curves and the peak-angle scatter of
/// motion-suite studies (ensemble_fragility.cc). Each adds its headings, tables and figures to
/// the page and its findings, in plain words, to `findings`.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "report/common/page.h"
#include "report/study/study_csv.h"

namespace rockbench::report {

/// How a run ended, as the maps colour it.
enum class OverturnClass {
  kNone,        ///< no block overturned
  kBlock1,      ///< block 1 overturned (and with it the stack)
  kBlock2,      ///< block 2 fell off block 1
  kUpperBlock,  ///< N >= 3 blocks: block 3 or one above it fell (EnsembleRecord says which)
  kStopped,     ///< the reference's model stopped (assumption_violated: uplift, sliding)
  kFailed,      ///< no result (crash, wall_limit, error) or an engine's blow-up
};
OverturnClass ClassOf(const EnsembleRecord& r);
std::string ClassName(OverturnClass c);

/// N >= 3 blocks: per run and block, how often that block overturned first and its peak angle
/// over the members (one row per block and run: readable at 6 to 8 blocks). Nothing for one or
/// two blocks.
void BlocksSection(const EnsembleData& d, Page& page, std::vector<std::string>& findings);

/// Whether the study is a pulse spectrum: numeric frequency and amplitude axes
/// (pulse.frequency_ratio and pulse.amplitude_ratio, or base.horizontal.frequency_hz and
/// base.horizontal.amplitude_g).
bool HasSpectrumAxes(const EnsembleData& d);
void SpectraSection(const EnsembleData& d, const std::filesystem::path& fig_dir, Page& page,
                    std::vector<std::string>& findings);

/// Member -> run -> that run's point (usable runs only), of one group of a study.
template <class Point>
using PointsByMember = std::map<long long, std::map<std::string, Point>>;

/// The points of the members that both the reference and `engine` have, in member order:
/// (the reference's, the engine's), point i of each the same member (for a paired bootstrap).
template <class Point>
std::pair<std::vector<Point>, std::vector<Point>> PairedWithReference(
    const PointsByMember<Point>& members, const std::string& engine) {
  std::pair<std::vector<Point>, std::vector<Point>> out;
  for (const auto& [member, runs] : members) {
    const auto ref = runs.find("reference"), eng = runs.find(engine);
    if (ref == runs.end() || eng == runs.end()) continue;
    out.first.push_back(ref->second);
    out.second.push_back(eng->second);
  }
  return out;
}

/// Whether the study varies the motion over a suite (base.horizontal.file or
/// base.horizontal.seed) so that a fragility curve over PGA is defined.
bool HasMotionSuite(const EnsembleData& d);
/// The columns of the axes that choose or scale the motion (record, seed, PGA or PGV target,
/// scale, amplitude): the other axes make a fragility study's groups.
std::vector<int> MotionAxisColumns(const EnsembleData& d);
void FragilitySection(const EnsembleData& d, const std::filesystem::path& fig_dir, Page& page,
                      std::vector<std::string>& findings);

/// The two-parameter fragility (PGA and PGV/PGA, Purvance et al. 2008) per group and run: the
/// median contours on one figure and a table of their parameters.
void FragilitySurfaceSection(const EnsembleData& d, const std::filesystem::path& fig_dir,
                             Page& page, std::vector<std::string>& findings);

/// Peak |theta1| against PGA, one series per engine; N >= 3 blocks: a figure per run, one
/// series per block in the renders' trace colours (renders::Palette::chart_theta).
void ScatterSection(const EnsembleData& d, const std::filesystem::path& fig_dir, Page& page);

/// The values of every axis but `except`, as one label ("kind=sine_pulse, size_factor=2"),
/// for grouping; empty when no other axis.
std::string GroupLabel(const EnsembleData& d, const EnsembleRecord& r,
                       const std::vector<int>& except);

}  // namespace rockbench::report
