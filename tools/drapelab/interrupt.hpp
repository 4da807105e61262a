// Ctrl-C (SIGINT) and SIGTERM. Inside a polling section the signal sets the flag that the verb
// polls between steps, so it stops at the next step and leaves valid files; a second signal ends
// the process at once. Outside one (loading a scene, parsing), the process ends at once with exit
// code 130: nothing has been written yet, or only files replaced whole by a rename.
#pragma once

#include <atomic>

namespace drapelab::cli {

// Installs the handlers; the flag they set.
const std::atomic<bool>& install_interrupt_handlers();

// While one exists, a signal sets the flag instead of ending the process.
class PollingSection {
 public:
  PollingSection();
  ~PollingSection();
  PollingSection(const PollingSection&) = delete;
  PollingSection& operator=(const PollingSection&) = delete;
};

}  // namespace drapelab::cli
