#include "host/base/interrupt.h"

#include <atomic>
#include <csignal>

namespace depthprec {

namespace {
std::atomic<bool> requested{false};

extern "C" void on_signal(int sig) {
  requested.store(true);
  std::signal(sig, SIG_DFL);  // a second signal is not caught
}
}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupt_requested() {
  return requested.load();
}

}  // namespace depthprec
