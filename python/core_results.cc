#include "core_results.h"

#include <pybind11/numpy.h>

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "scene/body_kind.h"
#include "scene/mode.h"
#include "util/stop_request.h"

namespace rockbench::python {
namespace {

// One column of body `body` (1-based) of quantity `stem` over every sample.
py::array_t<double> Column(const History& history, const StateQuantityReader& quantity, int body) {
  py::array_t<double> out(static_cast<py::ssize_t>(history.samples.size()));
  auto view = out.mutable_unchecked<1>();
  for (size_t i = 0; i < history.samples.size(); ++i) {
    view(static_cast<py::ssize_t>(i)) = quantity(history.samples[i], body);
  }
  return out;
}

// Every body's column of quantity `stem`, in body order.
void AddBodyColumns(const History& history, const std::string& stem, py::dict* out) {
  const StateQuantityReader quantity(history, stem);
  for (int k = 1; k <= history.blocks; ++k) {
    (*out)[py::str(BodyColumn(stem, k))] = Column(history, quantity, k);
  }
}

}  // namespace

py::dict HistoryColumns(const History& history) {
  py::dict out;
  py::array_t<double> t(static_cast<py::ssize_t>(history.samples.size()));
  auto tv = t.mutable_unchecked<1>();
  for (size_t i = 0; i < history.samples.size(); ++i) {
    tv(static_cast<py::ssize_t>(i)) = history.samples[i].t_s;
  }
  out["t"] = t;
  // The columns in history.csv's order (files/history_csv.h).
  std::vector<std::string> before_mode, after_mode;
  if (history.shape == PlanarBlockKind().shape) {
    before_mode = {"theta", "omega"};
    if (history.slip_and_lift) after_mode = {"u", "z"};
  } else if (const BodyKind* kind = FindBodyKind(history.shape)) {
    for (const StateQuantity& q : kind->state) before_mode.push_back(q.stem);
  }
  for (const std::string& stem : before_mode) AddBodyColumns(history, stem, &out);
  py::list mode;
  for (const Sample& s : history.samples) mode.append(py::str(ConfigurationName(s.mode)));
  out["mode"] = mode;
  for (const std::string& stem : after_mode) AddBodyColumns(history, stem, &out);
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
