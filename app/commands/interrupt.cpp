#include "app/commands/interrupt.h"

#include <unistd.h>

#include <csignal>
#include <ctime>
#include <cstring>
#include <iterator>

namespace tallow::app {
namespace {

volatile std::sig_atomic_t gSignal = 0;
// When the first request came (CLOCK_MONOTONIC, ms): timeout(1) signals its child and then its
// whole process group, so one request arrives twice within microseconds.
volatile long long gFirstMs = 0;
constexpr long long kSameRequestMs = 500;

long long monotonicMs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);  // async-signal-safe (POSIX)
  return static_cast<long long>(t.tv_sec) * 1000 + t.tv_nsec / 1'000'000;
}
// Written from the handler with write(2), the async-signal-safe way to say something.
constexpr char kNotice[] =
    "\ntallow: stopping: finishing the step in hand and writing what is done (again to stop at once)\n";
// SIGHUP: the terminal went away (a dropped ssh session); the run ends as it would on SIGTERM.
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

void onSignal(int signal) {
  if (gSignal == 0) {
    gSignal = signal;
    gFirstMs = monotonicMs();
    const ssize_t ignored = ::write(STDERR_FILENO, kNotice, sizeof kNotice - 1);
    (void)ignored;
    return;
  }
  // The same request again (timeout's second copy, to the process group): already in hand.
  if (signal == gSignal && monotonicMs() - gFirstMs < kSameRequestMs) return;
  // The second request: the default action (the process ends with that signal), now.
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

struct sigaction gPrevious[std::size(kSignals)];
struct sigaction gPreviousSigpipe;

}  // namespace

InterruptScope::InterruptScope() {
  gSignal = 0;
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  // Interrupted reads and writes resume: the flag is looked at between steps, not by every call.
  action.sa_flags = SA_RESTART;
  for (std::size_t i = 0; i < std::size(kSignals); ++i) sigaction(kSignals[i], &action, &gPrevious[i]);
  // With the terminal gone (SIGHUP), a progress line written into a pipe whose reader died must fail
  // with EPIPE, not end the run before it wrote what it has.
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &gPreviousSigpipe);
}

InterruptScope::~InterruptScope() {
  for (std::size_t i = 0; i < std::size(kSignals); ++i) sigaction(kSignals[i], &gPrevious[i], nullptr);
  sigaction(SIGPIPE, &gPreviousSigpipe, nullptr);
}

int interruptSignal() { return gSignal; }

int interruptExitCode() { return 128 + gSignal; }

const char* interruptName() {
  switch (gSignal) {
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    case 0:
      return "";
    default:
      return "signal";
  }
}

void throwIfInterrupted() {
  if (gSignal != 0) throw Interrupted();
}

}  // namespace tallow::app
