#include "interrupt_guard.hpp"

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace drapelab::python {
namespace {

std::atomic<bool> interrupted{false};

extern "C" void take_interrupt(int) { interrupted.store(true); }

bool on_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

}  // namespace

InterruptGuard::InterruptGuard() {
  if (!on_main_thread()) return;
  interrupted.store(false);
  struct sigaction action {};
  action.sa_handler = take_interrupt;
  sigemptyset(&action.sa_mask);
  installed_ = sigaction(SIGINT, &action, &previous_) == 0;
}

InterruptGuard::~InterruptGuard() {
  if (installed_) sigaction(SIGINT, &previous_, nullptr);
}

const std::atomic<bool>* InterruptGuard::flag() const {
  return installed_ ? &interrupted : nullptr;
}

void InterruptGuard::raise_if_interrupted() const {
  if (!installed_ || !interrupted.load()) return;
  PyErr_SetNone(PyExc_KeyboardInterrupt);
  throw py::error_already_set();
}

}  // namespace drapelab::python
