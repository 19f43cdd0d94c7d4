#include "core_results.h"

#include <pybind11/numpy.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "files/history_csv.h"
#include "scene/mode.h"
#include "util/stop_request.h"

namespace rockbench::python {
namespace {

// One column of body `body` (1-based) of `quantity` over every sample.
py::array_t<double> Column(const History& history, const StateQuantityReader& quantity, int body) {
  py::array_t<double> out(static_cast<py::ssize_t>(history.samples.size()));
  auto view = out.mutable_unchecked<1>();
  for (size_t i = 0; i < history.samples.size(); ++i) {
    view(static_cast<py::ssize_t>(i)) = quantity(history.samples[i], body);
  }
  return out;
}

// The names of history.csv's columns, in its order: its header, as the file's writer makes it
// (files/history_csv.h) for a history of these bodies.
std::vector<std::string> CsvColumns(const History& history) {
  History empty;
  empty.blocks = history.blocks;
  empty.slip_and_lift = history.slip_and_lift;
  empty.shape = history.shape;
  const std::string text = HistoryToCsv(empty);
  std::vector<std::string> names;
  std::string name;
  for (const char c : text.substr(0, text.find('\n'))) {
    if (c == ',') {
      names.push_back(name);
      name.clear();
    } else {
      name += c;
    }
  }
  names.push_back(name);
  return names;
}

}  // namespace

py::dict HistoryColumns(const History& history) {
  py::dict out;
  for (const std::string& name : CsvColumns(history)) {
    if (name == "mode") {
      py::list mode;
      for (const Sample& s : history.samples) mode.append(py::str(ConfigurationName(s.mode)));
      out["mode"] = mode;
      continue;
    }
    if (name == "t") {
      py::array_t<double> t(static_cast<py::ssize_t>(history.samples.size()));
      auto view = t.mutable_unchecked<1>();
      for (size_t i = 0; i < history.samples.size(); ++i) {
        view(static_cast<py::ssize_t>(i)) = history.samples[i].t_s;
      }
      out["t"] = t;
      continue;
    }
    // A body's column: the quantity's stem, then the body's number (BodyColumn).
    const size_t digits = name.find_last_not_of("0123456789") + 1;
    const StateQuantityReader quantity(history, name.substr(0, digits));
    out[py::str(name)] = Column(history, quantity, std::stoi(name.substr(digits)));
  }
  return out;
}

void RunInterruptibly(const std::function<void()>& work) {
  std::mutex mutex;
  std::condition_variable finished_cv;
  bool finished = false;
  std::exception_ptr error;
  ClearStopRequest();
  bool interrupted = false;
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        work();
      } catch (...) {
        error = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mutex);
      finished = true;
      finished_cv.notify_all();
    });
    std::unique_lock<std::mutex> lock(mutex);
    while (!finished_cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished; })) {
      if (interrupted) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire acquire;
        // Ctrl-C: Python's handler has set a flag; this raises KeyboardInterrupt (kept set).
        if (PyErr_CheckSignals() != 0) interrupted = true;
      }
      if (interrupted) RequestStop();
      lock.lock();
    }
    lock.unlock();
    worker.join();
  }
  ClearStopRequest();
  if (interrupted) throw py::error_already_set();
  if (error) std::rethrow_exception(error);
}

std::function<void(const std::string&)> LineCallback(const py::object& callback) {
  if (callback.is_none()) return {};
  // Shared, so that copies of the function (made without the GIL) never touch the object's
  // reference count; the last copy drops it with the GIL held.
  std::shared_ptr<py::object> held(new py::object(callback), [](py::object* o) {
    py::gil_scoped_acquire acquire;
    delete o;
  });
  return [held](const std::string& line) {
    py::gil_scoped_acquire acquire;
    (*held)(line);
  };
}

}  // namespace rockbench::python
