// Progress of long commands (app/commands/progress.h) and their stop on a signal
// (app/commands/interrupt.h): the texts, the time left, the once-a-second rule of logs, and the flag
// a first SIGINT sets instead of ending the process.
#include "app/commands/progress.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include <csignal>
#include <cstdio>
#include <string>

#include "app/commands/interrupt.h"

namespace tallow::app {
namespace {

std::string readAll(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  char buffer[256];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
  return text;
}

int lines(const std::string& text) {
  int n = 0;
  for (const char c : text) n += c == '\n';
  return n;
}

TEST(Progress, TextsSayWhereTheTaskStandsAndHowLongIsLeft) {
  EXPECT_EQ(formatDuration(3.25), "3.2 s");
  EXPECT_EQ(formatDuration(42.4), "42 s");
  EXPECT_EQ(formatDuration(185.0), "3 min 05 s");
  EXPECT_EQ(formatDuration(7440.0), "2 h 04 min");
  // 10 of 40 steps in 25 s: 2.5 s a step, 30 left.
  EXPECT_DOUBLE_EQ(secondsLeft(10, 40, 25.0), 75.0);
  EXPECT_LT(secondsLeft(0, 40, 25.0), 0.0) << "nothing done: unknown";
  EXPECT_LT(secondsLeft(3, 0, 25.0), 0.0) << "no total: unknown";
  ProgressState s{"capture", "frame", 10, 40, 25.0, ""};
  EXPECT_EQ(progressLine(s), "capture: frame 10 of 40 (25%), 25 s, about 1 min 15 s left");
  s.total = 0;
  s.detail = "relative standard error 3.1%";
  EXPECT_EQ(progressLine(s), "capture: frame 10, 25 s; relative standard error 3.1%");
  s.total = 40;
  s.detail = "";
  const std::string bar = progressBar(s, 80);
  EXPECT_LE(bar.size(), 79u) << bar;
  EXPECT_EQ(bar.rfind("capture [", 0), 0u) << bar;
  EXPECT_NE(bar.find("10/40 frames  25%"), std::string::npos) << bar;
  // A quarter of the cells are filled.
  const std::size_t open = bar.find('['), close = bar.find(']');
  const std::string cells = bar.substr(open + 1, close - open - 1);
  EXPECT_EQ(std::count(cells.begin(), cells.end(), '#'), static_cast<long>(cells.size() / 4)) << bar;
  EXPECT_LE(progressBar(s, 30).size(), 29u) << "a narrow terminal: cut, never wrapped";
}

TEST(Progress, LogsGetOneLineASecondAtMost) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  double now = 0.0;
  {
    Progress p("capture", "frame", 100, ProgressMode::Lines, out, [&] { return now; });
    // Fifty quick steps in 0.9 s: silent (a quick run leaves no trail).
    for (int i = 1; i <= 50; ++i) {
      now = 0.018 * i;
      p.update(i);
    }
    EXPECT_EQ(lines(readAll(out)), 0);
    // Then 50 steps over 5 s: a line at most every second.
    for (int i = 51; i <= 100; ++i) {
      now = 0.9 + 0.1 * (i - 50);
      p.update(i);
    }
  }
  const std::string text = readAll(out);
  EXPECT_GE(lines(text), 4) << text;
  EXPECT_LE(lines(text), 6) << text;
  EXPECT_NE(text.find("tallow: capture: frame "), std::string::npos) << text;
  std::fclose(out);
}

TEST(Progress, TheBarIsRedrawnInPlaceAndCleared) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  double now = 0.0;
  {
    Progress p("reference", "pass", 4, ProgressMode::Bar, out, [&] { return now; });
    for (int i = 1; i <= 4; ++i) {
      now += 1.0;
      p.update(i, "relative standard error 5%");
    }
    p.print("a row", out);  // the bar steps aside for the line, then comes back
  }
  const std::string text = readAll(out);
  EXPECT_EQ(lines(text), 1) << "the bar never ends a line; the printed one does";
  EXPECT_NE(text.find("4/4 passes  100%"), std::string::npos) << text;
  EXPECT_NE(text.find("\r\033[Ka row\n"), std::string::npos) << "cleared before the line";
  EXPECT_EQ(text.substr(text.size() - 4), "\r\033[K") << "cleared at the end";
  std::fclose(out);
}

TEST(Interrupt, AFirstSignalOnlyAsksTheCommandToStop) {
  {
    const InterruptScope scope;
    EXPECT_FALSE(interrupted());
    std::raise(SIGTERM);  // with the handler installed: the process goes on
    EXPECT_TRUE(interrupted());
    EXPECT_EQ(interruptExitCode(), 143);
    EXPECT_STREQ(interruptName(), "SIGTERM");
    EXPECT_THROW(throwIfInterrupted(), Interrupted);
  }
  const InterruptScope again;  // a new scope starts clear
  EXPECT_FALSE(interrupted());
  EXPECT_NO_THROW(throwIfInterrupted());
}

TEST(Interrupt, TheSameSignalTwiceAtOnceIsOneRequest) {
  // timeout(1) signals its child and then its whole process group: one request arrives twice,
  // microseconds apart, and must not count as the second request that ends the process at once.
  const InterruptScope scope;
  std::raise(SIGTERM);
  std::raise(SIGTERM);
  EXPECT_TRUE(interrupted());
  EXPECT_EQ(interruptExitCode(), 143);
}

TEST(InterruptDeathTest, ASecondRequestLaterEndsTheProcessAtOnce) {
  EXPECT_EXIT(
      {
        const InterruptScope scope;
        std::raise(SIGTERM);
        std::this_thread::sleep_for(std::chrono::milliseconds(700));  // a user asking again
        std::raise(SIGTERM);
        std::exit(0);
      },
      testing::KilledBySignal(SIGTERM), "");
}

}  // namespace
}  // namespace tallow::app
