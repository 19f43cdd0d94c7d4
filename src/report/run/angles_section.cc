#include "report/run/angles_section.h"

#include "report/common/number_text.h"

namespace rockbench::report {
namespace {

std::string AnglesCaption(const RunData& run) {
  std::string caption =
      "Block angles against time (rad; positive: tilted to the right), the reference model and "
      "every engine on shared axes";
  if (!OverturnMarks(run).empty()) caption += "; dashed vertical lines: overturning";
  if (run.band) {
    caption += "; shaded: the band " + BandTitle(run) +
               " and the nominal reference span (reference/ensemble_band.csv)";
  } else {
    caption += "; no reference ensemble was run, so there is no band";
  }
  if (AnyHorizonMark(run)) {
    caption += "; dashed blue vertical line: the block's predictability horizon";
  }
  return caption + ".";
}

}  // namespace

// theta1 and theta2 against time, every run on shared axes, the reference ensemble's band behind.
void AnglesFigure(const RunData& run, Figures& fig) {
  const bool two = run.scene.block_count() == 2;
  GnuplotFigure f;
  f.name = "angles";
  f.height_px = two ? 720 : 420;
  for (const EngineData& e : run.engines) {
    std::string dat = two ? "# t_s theta1_rad theta2_rad\n" : "# t_s theta1_rad\n";
    for (const Sample& s : e.history.samples) {
      AppendDat(dat, s.t_s);
      dat += ' ';
      AppendDat(dat, s.theta_rad[0]);
      if (two) {
        dat += ' ';
        AppendDat(dat, s.theta_rad[1]);
      }
      dat += '\n';
    }
    f.data_files.push_back({"angles." + e.name + ".dat", dat});
  }
  if (run.band) {
    const EnsembleBand& b = *run.band;
    f.data_files.push_back(
        {"angles.band.dat",
         two ? BandDat(run, "# t_s theta1_lo_rad theta1_hi_rad theta2_lo_rad theta2_hi_rad\n",
                       {&b.lo_rad[0], &b.hi_rad[0], &b.lo_rad[1], &b.hi_rad[1]}, -kInf)
             : BandDat(run, "# t_s theta1_lo_rad theta1_hi_rad\n", {&b.lo_rad[0], &b.hi_rad[0]},
                       -kInf)});
  }
  const auto panel = [&](int block) {
    std::string s = "unset arrow\nunset label\n" + OverturnMarks(run) +
                    HorizonMark(run, block, 0.62) + "set ylabel " +
                    Quote("θ_" + std::to_string(block) + " (rad)") + "\n";
    s += "set title " + Quote(block == 1 ? "block 1 (lower)" : "block 2 (upper)") + "\n";
    std::string plot = "plot ";
    if (run.band) {
      plot += Quote("angles.band.dat") + " using 1:" + std::to_string(2 * block) + ":" +
              std::to_string(2 * block + 1) + " with filledcurves fc rgb " + Quote(kBandColour) +
              " fs solid 1.0 noborder title " + Quote(BandTitle(run)) + ", ";
    }
    for (size_t i = 0; i < run.engines.size(); ++i) {
      const EngineData& e = run.engines[i];
      if (i > 0) plot += ", ";
      plot += Quote("angles." + e.name + ".dat") + " using 1:" + std::to_string(1 + block) +
              " with lines lw " + (i == 0 ? "2.2" : "1.4") + (i == 0 ? "" : " dt 2") + " lc rgb " +
              Quote(e.colour) + " title " + Quote(e.label);
    }
    return s + plot + "\n";
  };
  f.script = CommonAxes(run.t_end_s);
  if (two) {
    f.script += "set multiplot layout 2,1\n" + panel(1) + panel(2) + "unset multiplot\n";
  } else {
    f.script += panel(1);
  }
  fig.Add(f, AnglesCaption(run));
}

}  // namespace rockbench::report
