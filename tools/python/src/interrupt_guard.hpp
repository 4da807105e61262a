// Ctrl-C while the GIL is released. Python's own SIGINT handler only sets a flag that the
// interpreter reads between bytecodes, which never happens while C++ steps a solver; so during a
// long call the guard takes SIGINT itself and sets the flag the solvers' loops read, and the call
// then stops after the current step and raises KeyboardInterrupt. Only on the main thread, where
// Python handles signals; elsewhere the guard does nothing.
#pragma once

#include <atomic>
#include <csignal>

namespace drapelab::python {

class InterruptGuard {
 public:
  InterruptGuard();   // with the GIL held
  ~InterruptGuard();  // restores Python's handler
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

  // The flag to hand to the loops (null off the main thread).
  const std::atomic<bool>* flag() const;
  // With the GIL held: raises KeyboardInterrupt if Ctrl-C came during the call.
  void raise_if_interrupted() const;

 private:
  bool installed_ = false;
  struct sigaction previous_ {};
};

}  // namespace drapelab::python
