#include "support/run_tallow.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <thread>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "support/temp_dir.h"

extern char** environ;

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

TallowProcess::TallowProcess(const std::vector<std::string>& args, const std::vector<std::string>& env) {
  std::vector<std::string> words = {"/usr/bin/env"};
  words.insert(words.end(), env.begin(), env.end());
  const char* other = std::getenv("TALLOW_TEST_TALLOW");  // as runTallow: another build
  words.push_back(other && *other ? other : TALLOW_TEST_BINARY);
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const std::string out = (io_.path() / "out").string(), err = (io_.path() / "err").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
  posix_spawn_file_actions_destroy(&actions);
}

TallowProcess::~TallowProcess() {
  if (running()) {
    ::kill(pid_, SIGKILL);
    wait();
  }
}

bool TallowProcess::running() {
  if (pid_ <= 0 || status_ >= 0) return false;
  int status = 0;
  const pid_t r = ::waitpid(pid_, &status, WNOHANG);
  if (r == 0) return true;
  status_ = r == pid_ ? (WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status)) : 255;
  return false;
}

bool TallowProcess::waitUntil(const std::function<bool()>& ready, std::chrono::seconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    if (ready()) return true;
    if (!running()) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

void TallowProcess::signal(int sig) {
  if (pid_ > 0) ::kill(pid_, sig);
}

int TallowProcess::wait() {
  if (pid_ <= 0) return -1;
  if (status_ < 0) {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  return status_;
}

int TallowProcess::wait(std::uint64_t& bytesWritten) {
  bytesWritten = 0;
  if (pid_ > 0 && status_ < 0) {
    // Wait for the exit without reaping (WNOWAIT): the zombie's /proc entry still holds its counts.
    siginfo_t info{};
    while (::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
    }
    std::ifstream io("/proc/" + std::to_string(pid_) + "/io");
    for (std::string key; io >> key;) {
      std::uint64_t value = 0;
      io >> value;
      if (key == "wchar:") bytesWritten = value;
    }
  }
  return wait();
}

std::string TallowProcess::out() const { return slurp(io_.path() / "out"); }
std::string TallowProcess::err() const { return slurp(io_.path() / "err"); }

int lineCount(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) n += !line.empty();
  return n;
}

}  // namespace tallow::test
