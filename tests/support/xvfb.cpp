#include "support/xvfb.h"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

namespace tallow::test {

bool xvfbAvailable() { return std::system("command -v Xvfb >/dev/null 2>&1") == 0; }

XvfbResult runUnderXvfb(const std::string& command, const std::filesystem::path& dir) {
  const std::string script =
      "cd '" + dir.string() + "' || exit 1; for try in 1 2 3 4 5; do rm -f display.txt; "
      "Xvfb -displayfd 3 -screen 0 800x600x24 -nolisten tcp 3>display.txt >xvfb.log 2>&1 & pid=$!; "
      "for i in $(seq 400); do [ -s display.txt ] && break; sleep 0.05; done; n=$(head -n 1 display.txt); "
      "if [ -z \"$n\" ]; then kill $pid 2>/dev/null; wait $pid 2>/dev/null; echo \"Xvfb did not start: $(cat xvfb.log)\" >run.txt; continue; fi; "
      "( export DISPLAY=:$n; " + command + " ) >run.txt 2>&1; "
      "rc=$?; kill $pid; wait $pid 2>/dev/null; "
      "if [ $rc -ne 0 ] && grep -q \"Failed to open display\" run.txt; then cat xvfb.log >>run.txt; sleep $try; continue; fi; "
      "exit $rc; done; exit 1";
  // Single quotes for bash -c: each ' inside becomes '\''.
  std::string quoted;
  for (char c : script) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  const int status = std::system(("bash -c '" + quoted + "'").c_str());
  XvfbResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::ifstream out(dir / "run.txt");
  r.output.assign(std::istreambuf_iterator<char>(out), std::istreambuf_iterator<char>());
  return r;
}

}  // namespace tallow::test
