#include "report/run/energy_section.h"

#include <algorithm>

#include "report/common/number_text.h"

namespace rockbench::report {

void EnergySection(const RunData& run, const reference::StackModel& model, Figures& fig) {
  Page& page = *fig.page;
  page.Heading("Energy");
  GnuplotFigure f;
  f.name = "energy";
  f.height_px = 480;
  Span span;
  std::vector<std::vector<double>> values(run.engines.size());
  for (size_t i = 0; i < run.engines.size(); ++i) {
    for (const Sample& s : run.engines[i].history.samples) {
      values[i].push_back(model.EnergyAboveRest_j(s));
      span.Add(values[i].back());
    }
  }
  // On a log axis, values a billion times below the largest (rest) are gaps.
  const bool log = span.Decades();
  const double floor_j = span.hi * 1e-9;
  for (size_t i = 0; i < run.engines.size(); ++i) {
    std::string dat = "# t_s energy_above_rest_j\n";
    const auto& samples = run.engines[i].history.samples;
    for (size_t k = 0; k < samples.size(); ++k) {
      AppendDat(dat, samples[k].t_s);
      dat += ' ';
      AppendDat(dat, log && values[i][k] < floor_j ? kNaN : values[i][k]);
      dat += '\n';
    }
    f.data_files.push_back({"energy." + run.engines[i].name + ".dat", dat});
  }
  f.script = CommonAxes(run.t_end_s) + "set ylabel 'energy above rest (J)'\n" +
             (log ? "set logscale y\nset format y '10^{%L}'\n" : "");
  std::string plot = "plot ";
  for (size_t i = 0; i < run.engines.size(); ++i) {
    const EngineData& e = run.engines[i];
    if (i > 0) plot += ", ";
    plot += Quote("energy." + e.name + ".dat") + " using 1:2" + RunLineStyle(i, e);
  }
  f.script += plot + "\n";
  fig.Add(
      f, std::string("Energy against time: kinetic energy in the base frame plus potential "
                     "energy above the rest position (J)") +
             (log ? ", log scale (values below 1e-9 of the largest, such as rest, are gaps)" : "") +
             ". Every run's energy, engines included, is evaluated from its angles and rates "
             "with the rigid-block model (reference/kinematics.h" +
             std::string(model.blocks() >= 3 ? "; N blocks: the pivot chain, "
                                               "reference/stack_chain.h"
                                             : "") +
             "), not read from the engine.");
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < run.engines.size(); ++i) {
    rows.push_back({run.engines[i].name, Num(values[i].front(), 6) + " J",
                    Num(values[i].back(), 6) + " J",
                    Num(*std::max_element(values[i].begin(), values[i].end()), 6) + " J"});
  }
  page.Table({"run", "initial", "final", "largest"}, rows);
}

}  // namespace rockbench::report
