#include "core/interrupt.hpp"

#include <utility>

namespace plumekit {

namespace {
thread_local const std::function<bool()>* current = nullptr;
}

InterruptCheck::InterruptCheck(std::function<bool()> check)
    : check_(std::move(check)), previous_(current) {
  current = &check_;
}

InterruptCheck::~InterruptCheck() {
  current = previous_;
}

void check_interrupt() {
  if (current && *current && (*current)()) throw Interrupted();
}

}  // namespace plumekit
