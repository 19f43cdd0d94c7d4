#include "report/run/angles_section.h"

#include "report/common/number_text.h"
#include "scene/body_kind.h"
#include "util/format.h"

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

// theta1 .. thetaN against time (one panel per block), every run on shared axes, the reference
// ensemble's band behind.
void AnglesFigure(const RunData& run, Figures& fig) {
  const int nb = run.scene.block_count();
  GnuplotFigure f;
  f.name = "angles";
  f.height_px = PanelsHeight_px(nb);
  for (const EngineData& e : run.engines) {
    std::string dat = "# t_s";
    for (int b = 1; b <= nb; ++b) dat.append(" ").append(BodyColumn("theta", b)).append("_rad");
    dat += "\n";
    for (const Sample& s : e.history.samples) {
      AppendDat(dat, s.t_s);
      for (int b = 0; b < nb; ++b) {
        dat += ' ';
        AppendDat(dat, s.theta_rad[b]);
      }
      dat += '\n';
    }
    f.data_files.push_back({"angles." + e.name + ".dat", dat});
  }
  if (run.band) {
    const EnsembleBand& b = *run.band;
    std::string header = "# t_s";
    std::vector<const std::vector<double>*> columns;
    for (int k = 0; k < nb; ++k) {
      const std::string th = BodyColumn("theta", k + 1);
      header.append(" ").append(th).append("_lo_rad ").append(th).append("_hi_rad");
      columns.push_back(&b.lo_rad[k]);
      columns.push_back(&b.hi_rad[k]);
    }
    f.data_files.push_back({"angles.band.dat", BandDat(run, header + "\n", columns, -kInf)});
  }
  const auto panel = [&](int block) {
    std::string s = "unset arrow\nunset label\n" + OverturnMarks(run) +
                    HorizonMark(run, block, 0.62) + "set ylabel " +
                    Quote("θ_" + std::to_string(block) + " (rad)") + "\n";
    s += "set title " + Quote(BlockTitle(block, nb)) + "\n";
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
              RunLineStyle(i, e);
    }
    return s + plot + "\n";
  };
  f.script = CommonAxes(run.t_end_s);
  if (nb >= 2) {
    f.script += "set multiplot layout " + std::to_string(nb) + ",1\n";
    for (int b = 1; b <= nb; ++b) f.script += panel(b);
    f.script += "unset multiplot\n";
  } else {
    f.script += panel(1);
  }
  fig.Add(f, AnglesCaption(run));
}

}  // namespace rockbench::report
