#include "app/commands/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace tallow::app {
namespace {

/// Lines mode: at most one line per this many seconds (the first after as long).
constexpr double kLineIntervalS = 1.0;
/// Bar mode: redraws at most this often (a terminal flooded with redraws slows the task).
constexpr double kBarIntervalS = 0.1;
constexpr int kDefaultColumns = 80;
constexpr int kMinBarCells = 10, kMaxBarCells = 40;

double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

int terminalColumns(std::FILE* out) {
  winsize size{};
  if (::ioctl(fileno(out), TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  if (const char* columns = std::getenv("COLUMNS")) {
    const int c = std::atoi(columns);
    if (c > 0) return c;
  }
  return kDefaultColumns;
}

/// Characters as a terminal counts them (UTF-8 continuation bytes take no column).
std::size_t displayWidth(const std::string& text) {
  std::size_t n = 0;
  for (const char c : text) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

/// `text` cut to at most `columns` characters, on a character boundary.
std::string clip(const std::string& text, std::size_t columns) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80 && n++ == columns) return text.substr(0, i);
  }
  return text;
}

/// "frames", "passes", "rows".
std::string plural(const std::string& unit) { return unit + (!unit.empty() && unit.back() == 's' ? "es" : "s"); }

std::string percent(int done, int total) { return std::to_string(std::clamp(100 * done / total, 0, 100)) + "%"; }

std::string timing(const ProgressState& s) {
  std::string t = formatDuration(s.elapsedS);
  const double left = secondsLeft(s.done, s.total, s.elapsedS);
  if (left > 0.0) t += ", about " + formatDuration(left) + " left";
  return t;
}

}  // namespace

ProgressMode progressMode() {
  if (const char* env = std::getenv("TALLOW_PROGRESS")) {
    if (std::strcmp(env, "bar") == 0) return ProgressMode::Bar;
    if (std::strcmp(env, "lines") == 0) return ProgressMode::Lines;
    if (std::strcmp(env, "off") == 0) return ProgressMode::Off;
  }
  return ::isatty(STDERR_FILENO) ? ProgressMode::Bar : ProgressMode::Lines;
}

std::string formatDuration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "?";
  char text[48];
  if (seconds < 10.0) {
    std::snprintf(text, sizeof text, "%.1f s", seconds);
  } else if (seconds < 60.0) {
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  } else if (seconds < 3600.0) {
    const long s = std::lround(seconds);
    std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60.0);
    std::snprintf(text, sizeof text, "%ld h %02ld min", m / 60, m % 60);
  }
  return text;
}

double secondsLeft(int done, int total, double elapsedS) {
  if (done <= 0 || total <= 0 || !(elapsedS >= 0.0)) return -1.0;
  return elapsedS / done * std::max(total - done, 0);
}

std::string progressLine(const ProgressState& s) {
  std::string line = s.task + ": " + s.unit + " " + std::to_string(s.done);
  if (s.total > 0) line += " of " + std::to_string(s.total) + " (" + percent(s.done, s.total) + ")";
  line += ", " + timing(s);
  if (!s.detail.empty()) line += "; " + s.detail;
  return line;
}

std::string progressBar(const ProgressState& s, int columns) {
  const std::string counts =
      s.total > 0 ? std::to_string(s.done) + "/" + std::to_string(s.total) + " " + plural(s.unit) + "  " + percent(s.done, s.total)
                  : std::to_string(s.done) + " " + plural(s.unit);
  const std::string right = "  " + counts + "  " + timing(s) + (s.detail.empty() ? "" : "  " + s.detail);
  const int room = columns - 1 - static_cast<int>(displayWidth(s.task) + 3 + displayWidth(right));
  const int cells = std::clamp(room, kMinBarCells, kMaxBarCells);
  const int filled = s.total > 0 ? std::clamp(cells * s.done / s.total, 0, cells) : 0;
  std::string bar = s.task + " [" + std::string(static_cast<std::size_t>(filled), '#') +
                    std::string(static_cast<std::size_t>(cells - filled), '-') + "]" + right;
  return clip(bar, static_cast<std::size_t>(std::max(columns - 1, 1)));
}

Progress::Progress(std::string task, std::string unit, int total, ProgressMode mode, std::FILE* out, Clock clock)
    : task_(std::move(task)), unit_(std::move(unit)), total_(total), mode_(mode), out_(out),
      clock_(clock ? std::move(clock) : Clock(steadySeconds)) {
  start_ = last_ = clock_();
}

Progress::~Progress() { finish(); }

ProgressState Progress::state(double now) const {
  ProgressState s;
  s.task = task_;
  s.unit = unit_;
  s.done = done_;
  s.total = total_;
  s.elapsedS = now - start_;
  s.detail = detail_;
  return s;
}

void Progress::draw(double now) {
  if (mode_ == ProgressMode::Bar) {
    std::fprintf(out_, "\r\033[K%s", progressBar(state(now), terminalColumns(out_)).c_str());
    barShown_ = true;
  } else if (mode_ == ProgressMode::Lines) {
    std::fprintf(out_, "tallow: %s\n", progressLine(state(now)).c_str());
  }
  std::fflush(out_);
  last_ = now;
}

void Progress::update(int done, const std::string& detail) {
  const std::lock_guard lock(mutex_);
  if (done < done_) return;
  done_ = done;
  detail_ = detail;
  const double now = clock_();
  if (mode_ == ProgressMode::Bar && (now - last_ >= kBarIntervalS || (total_ > 0 && done >= total_) || !barShown_))
    draw(now);
  else if (mode_ == ProgressMode::Lines && now - last_ >= kLineIntervalS)
    draw(now);
}

void Progress::print(const std::string& line, std::FILE* stream) {
  const std::lock_guard lock(mutex_);
  const bool redraw = barShown_;
  if (barShown_) {
    std::fputs("\r\033[K", out_);
    std::fflush(out_);
    barShown_ = false;
  }
  std::fprintf(stream, "%s\n", line.c_str());
  std::fflush(stream);
  if (redraw) draw(clock_());
}

void Progress::finish() {
  const std::lock_guard lock(mutex_);
  if (!barShown_) return;
  std::fputs("\r\033[K", out_);
  std::fflush(out_);
  barShown_ = false;
}

}  // namespace tallow::app
