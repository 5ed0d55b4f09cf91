#include "support/run_tallow.h"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "support/temp_dir.h"

namespace tallow::test {
namespace {
std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

CommandResult runTallow(const std::vector<std::string>& args, const std::vector<std::string>& env) {
  TempDir io;
  // Appended piece by piece: `" " + std::string&&` trips GCC 12's false -Wrestrict (bug 105651).
  std::string command = "env";
  auto word = [&command](const std::string& w) {
    command += ' ';
    command += quote(w);
  };
  for (const auto& e : env) word(e);
  // $TALLOW_TEST_TALLOW runs the tests against another build, e.g. an older one to show that a
  // new test fails there.
  const char* other = std::getenv("TALLOW_TEST_TALLOW");
  word(other && *other ? other : TALLOW_TEST_BINARY);
  for (const auto& a : args) word(a);
  command += " >";
  command += quote((io.path() / "out").string());
  command += " 2>";
  command += quote((io.path() / "err").string());
  command += " </dev/null";
  const int status = std::system(command.c_str());
  CommandResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(io.path() / "out");
  r.err = slurp(io.path() / "err");
  return r;
}

int lineCount(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) n += !line.empty();
  return n;
}

}  // namespace tallow::test
