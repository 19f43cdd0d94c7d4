// rockbench._core: the Python module's C++ core (docs/python.md). Each function calls the
// library the command line uses, with the GIL released and Ctrl-C checked (core_results.h);
// the package's Python layer (python/rockbench/__init__.py) gives them their Pythonic form.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "compare/compare_run.h"
#include "core_results.h"
#include "engine/outcome.h"
#include "files/history_csv.h"
#include "motion/ground_motion.h"
#include "run/engine_registry.h"
#include "run/engine_run.h"
#include "run/summary.h"
#include "run/tolerance.h"
#include "scene/body_kind.h"
#include "scene/scene.h"
#include "study/study.h"
#include "study/study_runner.h"
#include "util/stop_request.h"

namespace rockbench::python {
namespace {

// A scene as read, with what it was read from (to_toml, and the runs' summary.json).
struct PyScene {
  Scene scene;
  std::string toml_text;               // the TOML text it was read from
  std::string path;                    // its file; "" for a scene given as text
  std::vector<std::string> overrides;  // "key=value", applied after the text
};

PyScene LoadSceneFile(const std::string& path, const std::vector<std::string>& overrides) {
  PyScene s;
  s.scene = LoadScene(path, overrides);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  s.toml_text = text.str();
  s.path = path;
  s.overrides = overrides;
  return s;
}

PyScene ParseSceneText(const std::string& text, const std::string& path,
                       const std::vector<std::string>& overrides) {
  PyScene s;
  s.scene = ParseScene(text, path, overrides);
  s.toml_text = text;
  s.overrides = overrides;
  return s;
}

// A run kept in C++: its history's columns and files are made when Python asks for them.
struct RunRecord {
  EngineRun run;
};

// A run's result: its record, its summary.json, its status and timings.
py::dict RunResultDict(EngineRun run, const nlohmann::json& summary, double core_s) {
  py::dict out;
  out["engine"] = run.engine;
  out["status"] = StatusText(run.outcome.status);
  out["summary_json"] = summary.dump(2) + "\n";
  out["one_line"] = run.one_line;
  out["wall_s"] = run.wall_s;
  out["core_s"] = core_s;
  out["record"] = std::make_shared<RunRecord>(RunRecord{std::move(run)});
  return out;
}

// The steady clock, s.
double Clock_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

py::dict Run(const PyScene& s, const std::string& engine) {
  CheckEngineTables(s.scene);
  std::optional<GroundMotion> motion;
  std::optional<EngineRun> run;
  double core_s = 0.0;
  RunInterruptibly([&] {
    const double start_s = Clock_s();
    motion.emplace(GroundMotion::FromScene(s.scene));
    run.emplace(RunEngine(engine, s.scene, *motion));
    core_s = Clock_s() - start_s;
  });
  const nlohmann::json summary = RunSummaryJson(s.path, s.overrides, s.scene, *motion, {&*run});
  py::dict out = RunResultDict(std::move(*run), summary, core_s);
  out["notes"] = PaddingNotes(*motion);
  return out;
}

// Every body's local tolerance (run/tolerance.h), the comparison's pointwise rule, on its grid:
// {"theta1": {"t": array, "tolerance_rad": array}, ...}.
py::dict LocalToleranceColumns(const Scene& scene, const History& reference) {
  py::dict out;
  for (int k = 1; k <= scene.block_count(); ++k) {
    const ToleranceProfile profile = LocalTolerance(scene, k, reference);
    std::vector<double> t, tol;
    if (profile.fixed_rad) {
      t = {0.0, scene.run.duration_s};
      tol = {*profile.fixed_rad, *profile.fixed_rad};
    } else {
      for (size_t i = 0; i < profile.tol_rad.size(); ++i) {
        t.push_back(static_cast<double>(i) * profile.grid_dt_s);
        tol.push_back(profile.tol_rad[i]);
      }
    }
    // Each compared angle of the body's kind: theta for a block, tilt_x and tilt_y (one profile,
    // the tilt's) for a cylinder.
    const BodyKind* kind = FindBodyKind(scene.blocks.at(static_cast<size_t>(k - 1)).shape);
    for (const StateQuantity& q : kind ? kind->state : PlanarBlockKind().state) {
      if (!q.compared_angle) continue;
      out[py::str(BodyColumn(q.stem, k))] =
          py::dict(py::arg("t") = py::array_t<double>(t.size(), t.data()),
                   py::arg("tolerance_rad") = py::array_t<double>(tol.size(), tol.data()));
    }
  }
  return out;
}

py::dict Compare(const PyScene& s, const std::string& engines_text, int jobs,
                 const py::object& log) {
  CheckEngineTables(s.scene);
  std::vector<std::string> engines = ParseEnginesBesideReference(engines_text);
  // "all" leaves out the engines that do not build the scene's bodies (a cylinder's planar
  // engines), said in the note as the command line says it.
  std::string not_run;
  if (engines_text == "all") engines = EnginesThatBuild(s.scene, engines, &not_run);
  CompareRunOptions options;
  options.jobs = jobs;
  options.log = LineCallback(log);
  std::optional<GroundMotion> motion;
  std::optional<CompareRun> run;
  RunInterruptibly([&] {
    motion.emplace(GroundMotion::FromScene(s.scene));
    run.emplace(RunCompare(s.scene, *motion, engines, options));
  });
  py::dict out;
  out["comparison_json"] = run->comparison.dump(2) + "\n";
  py::dict runs;
  runs[py::str(run->reference_run.engine)] =
      RunResultDict(run->reference_run, run->reference_run.summary, run->reference_run.wall_s);
  for (const EngineRun& r : run->engine_runs) {
    runs[py::str(r.engine)] = RunResultDict(r, r.summary, r.wall_s);
  }
  out["runs"] = runs;
  out["failures"] = run->failures;
  py::dict failed;
  for (const FailedEngine& f : run->failed_engines) failed[py::str(f.engine)] = f.reason;
  out["failed_engines"] = failed;
  // A cylinder's landing has one outcome: its model decides the whole run.
  out["undetermined_from_s"] = py::none();
  out["undetermined_detail"] = "";
  if (!run->cylinder_reference()) {
    const reference::Summary& rs = run->reference().used().summary;
    if (rs.undetermined_from_s) out["undetermined_from_s"] = py::float_(*rs.undetermined_from_s);
    out["undetermined_detail"] = rs.undetermined_detail;
  }
  out["not_run_note"] = not_run + NotRunNote(engines);
  out["local_tolerance"] = LocalToleranceColumns(run->reference_scene, run->reference_run.history);
  return out;
}

py::list Engines() {
  py::list out;
  out.append(py::dict(py::arg("name") = "reference", py::arg("built") = true,
                      py::arg("version") = FindEngine("reference")->version(),
                      py::arg("reason") = "", py::arg("brought_by") = ""));
  for (const RegisteredEngine& e : EngineRegistry()) {
    out.append(py::dict(py::arg("name") = e.name, py::arg("built") = e.engine != nullptr,
                        py::arg("version") = e.engine != nullptr ? e.engine->version() : "",
                        py::arg("reason") = e.missing_reason,
                        py::arg("brought_by") = e.brought_by));
  }
  return out;
}

// The command-line program beside the module: its `ensemble --worker` runs a study's members.
std::filesystem::path WorkerProgram() {
  const std::filesystem::path program(ROCKBENCH_PROGRAM);
  if (!std::filesystem::exists(program)) {
    throw SceneError("the rockbench program " + program.string() +
                     " (the study's workers) is missing: build it (scripts/build.sh)");
  }
  return program;
}

py::list RunStudy(const std::string& path, const std::string& out, int jobs, bool resume,
                  bool keep_histories, const py::object& progress) {
  const double start_s = StudyClock_s();
  const StudyDef study = LoadStudy(path);
  LocalStudyOptions options;
  options.out_dir = out;
  options.resume = resume;
  options.pool.executable = WorkerProgram();
  options.pool.jobs =
      jobs > 0 ? jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  options.pool.out_dir = out;
  options.pool.keep_histories = keep_histories;
  options.pool.worker_log = std::filesystem::path(out) / "workers.log";
  std::vector<std::string> notes;
  options.note = [&notes](const std::string& note) { notes.push_back(note); };
  if (!progress.is_none()) {
    const std::function<void(const std::string&)> call = LineCallback(progress);
    options.progress = [call](int64_t done, int64_t total) {
      call(std::to_string(done) + "/" + std::to_string(total));
    };
  }
  RunInterruptibly([&] { RunStudyHere(study, options, start_s); });
  return py::cast(notes);
}

}  // namespace
}  // namespace rockbench::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace rockbench;
  using namespace rockbench::python;
  m.doc() = "rockbench's C++ core; use the package rockbench (docs/python.md).";
  // A scene error names the file, line and key, as on the command line.
  py::register_exception<SceneError>(m, "SceneError", PyExc_ValueError);
  py::register_exception<StopRequested>(m, "StopRequested", PyExc_KeyboardInterrupt);

  py::class_<RunRecord, std::shared_ptr<RunRecord>>(m, "RunRecord")
      .def("history_columns", [](const RunRecord& r) { return HistoryColumns(r.run.history); })
      .def("history_csv", [](const RunRecord& r) { return HistoryToCsv(r.run.history); })
      .def("events_csv", [](const RunRecord& r) { return EventsToCsv(r.run.history); });
  py::class_<PyScene>(m, "Scene")
      .def_property_readonly("toml_text", [](const PyScene& s) { return s.toml_text; })
      .def_property_readonly("path", [](const PyScene& s) { return s.path; })
      .def_property_readonly("overrides", [](const PyScene& s) { return s.overrides; })
      .def_property_readonly("blocks", [](const PyScene& s) { return s.scene.block_count(); })
      .def_property_readonly("title", [](const PyScene& s) { return s.scene.title; })
      .def_property_readonly("duration_s", [](const PyScene& s) { return s.scene.run.duration_s; });
  m.def("load_scene", &LoadSceneFile, py::arg("path"), py::arg("overrides"));
  m.def("parse_scene", &ParseSceneText, py::arg("text"), py::arg("path"), py::arg("overrides"));
  m.def("run", &Run, py::arg("scene"), py::arg("engine"));
  m.def("compare", &Compare, py::arg("scene"), py::arg("engines"), py::arg("jobs"), py::arg("log"));
  m.def("engines", &Engines);
  m.def("run_study", &RunStudy, py::arg("path"), py::arg("out"), py::arg("jobs"), py::arg("resume"),
        py::arg("keep_histories"), py::arg("progress"));
  m.attr("version") = ROCKBENCH_VERSION;
}
