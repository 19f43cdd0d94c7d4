#pragma once
// What the Python core hands back: a run's history as named numpy columns (owned copies), and
// the study's progress and interruption plumbing shared by core.cc's functions.
#include <pybind11/pybind11.h>

#include <exception>
#include <functional>
#include <optional>
#include <string>

#include "scene/history.h"

namespace rockbench::python {

namespace py = pybind11;

// The columns of history.csv, in its order, each a numpy array of float64 (the exact doubles
// of the run, not the file's 13 digits) or, for "mode", a list of str: {name: column}.
py::dict HistoryColumns(const History& history);

// Runs `work` on a thread of its own with the GIL released, and checks for Python's signals
// (Ctrl-C) every 50 ms meanwhile. On KeyboardInterrupt the work is asked to stop
// (util/stop_request.h), its thread is joined, and the KeyboardInterrupt is raised. An exception
// of the work is rethrown here (pybind11 maps SceneError to ValueError).
void RunInterruptibly(const std::function<void()>& work);

// A callable that calls `callback(line)` with the GIL held; none when `callback` is None.
std::function<void(const std::string&)> LineCallback(const py::object& callback);

}  // namespace rockbench::python
