#pragma once
// Stopping a long call from outside it. The long loops (Newton's iterations, STE's steps, an
// evaluation's runs, a table build's batches, a dataset's samples) call check_interrupt() between
// steps; an embedding that can be asked to stop (the Python module, on Ctrl-C) installs a check
// for the thread that runs the call. Releasing Python's GIL alone does not do it: Python handles a
// signal only when control comes back to it, at the end of the call.
#include <functional>
#include <stdexcept>

namespace plumekit {

// What check_interrupt() throws when the installed check asks to stop. Not an InputError: the
// input is fine; the embedding turns it back into its own signal (Python's KeyboardInterrupt).
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// Installs `check` (true: stop) for the calling thread while it lives, then restores the one
// before. Only the thread that installs it polls it: worker threads of a call finish their
// share, and the call stops at its next check on this thread.
class InterruptCheck {
 public:
  explicit InterruptCheck(std::function<bool()> check);
  ~InterruptCheck();
  InterruptCheck(const InterruptCheck&) = delete;
  InterruptCheck& operator=(const InterruptCheck&) = delete;

 private:
  std::function<bool()> check_;
  const std::function<bool()>* previous_;
};

// Throws Interrupted when this thread's check says stop; without a check, nothing (one
// thread-local load).
void check_interrupt();

}  // namespace plumekit
