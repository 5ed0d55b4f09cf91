#pragma once
// Stopping a long command cleanly on SIGINT (Ctrl-C), SIGTERM or SIGHUP (the terminal closed, a
// dropped ssh session): while an InterruptScope lives, the
// first such signal only sets a flag (and says so on stderr); the command checks it between steps
// (capture: after the frame in hand; reference: after the pass in hand; bench: between frames),
// writes what is done whole, and exits with 128 + the signal (130, 143, 129), as a shell reports a
// command the signal ended. A second signal ends the process at once, as if no handler were
// installed, for a user who does not want to wait for the step in hand; the same signal again within
// half a second is the same request (timeout(1) sends it to the command and then to its group).
#include <exception>

namespace tallow::app {

class InterruptScope {
 public:
  /// Installs the handlers and clears an earlier stop request; the destructor restores the
  /// handlers that were there before.
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
};

/// The signal that asked the command to stop (SIGINT, SIGTERM or SIGHUP); 0 when none has.
int interruptSignal();
inline bool interrupted() { return interruptSignal() != 0; }
/// 128 + interruptSignal(): the exit status of a command stopped by it (130 for SIGINT, 143 for
/// SIGTERM, 129 for SIGHUP).
int interruptExitCode();
/// "SIGINT", "SIGTERM", "SIGHUP": for stats.json and the files' metadata.
const char* interruptName();

/// Thrown out of a step that a stop request cut short (nothing of that step is kept).
class Interrupted : public std::exception {
 public:
  const char* what() const noexcept override { return "interrupted"; }
};
/// Throws Interrupted when a stop was requested.
void throwIfInterrupted();

}  // namespace tallow::app
