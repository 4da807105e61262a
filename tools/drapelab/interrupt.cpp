// Ctrl-C and SIGTERM (interrupt.hpp).
#include "interrupt.hpp"

#include <signal.h>
#include <unistd.h>

namespace drapelab::cli {
namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_polling_sections{0};

extern "C" void on_interrupt(int) {
  // The first signal inside a polling section is left to the verb; any other ends the process.
  if (g_polling_sections.load() > 0 && !g_interrupted.exchange(true)) return;
  static const char message[] = "\ninterrupted\n";
  const ssize_t ignored = ::write(STDERR_FILENO, message, sizeof message - 1);
  (void)ignored;
  ::_exit(130);
}

}  // namespace

const std::atomic<bool>& install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // reads and writes resume instead of failing with EINTR
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  return g_interrupted;
}

PollingSection::PollingSection() { g_polling_sections.fetch_add(1); }
PollingSection::~PollingSection() { g_polling_sections.fetch_sub(1); }

}  // namespace drapelab::cli
