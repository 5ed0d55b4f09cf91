#include "app/commands/stats_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "gpu/atomic_file.h"

namespace tallow::app {
namespace {

/// How often a running stats.json is rewritten at most: a reader polling it sees progress, and a
/// run of many short frames does not spend its time rewriting it.
constexpr std::chrono::seconds kUpdateInterval{1};

[[noreturn]] void cannotWrite(const std::filesystem::path& file, const std::string& reason) {
  throw std::runtime_error("cannot write " + file.string() + ": " + reason);
}

void writeAll(int fd, const std::string& text, const std::filesystem::path& file) {
  const char* data = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) cannotWrite(file, std::strerror(n < 0 ? errno : ENOSPC));
    data += n;
    left -= static_cast<std::size_t>(n);
  }
}

}  // namespace

std::filesystem::path framesFileOf(const std::filesystem::path& stats) {
  std::filesystem::path frames = stats;
  frames.replace_extension(".frames.jsonl");
  return frames;
}

std::string dumpJson(const nlohmann::json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

StatsWriter::StatsWriter(std::filesystem::path stats) : stats_(std::move(stats)), frames_(framesFileOf(stats_)) {}

StatsWriter::~StatsWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void StatsWriter::append(RunRecord& run, const FrameRecord& frame) {
  if (fd_ < 0) {
    // Appends only; O_NOFOLLOW refuses a link planted at the name.
    fd_ = ::open(frames_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd_ < 0) cannotWrite(frames_, std::strerror(errno));
  }
  writeAll(fd_, dumpJson(frameJson(frame)) + "\n", frames_);
  ++run.framesWritten;
  update(run);
}

void StatsWriter::update(const RunRecord& run, bool now) {
  const auto time = std::chrono::steady_clock::now();
  if (!now && updated_ && time - lastUpdate_ < kUpdateInterval) return;
  nlohmann::json doc = runJson(run);
  doc["run"]["frames_file"] = frames_.filename().string();
  gpu::writeTextFileAtomically(stats_, dumpJson(doc, 2) + "\n");
  lastUpdate_ = time;
  updated_ = true;
}

void StatsWriter::finish(const RunRecord& run) {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  // Two passes over the frames' lines, one at a time: their summary, then the document.
  const auto forEachFrame = [&](const auto& visit) {
    std::ifstream in(frames_);
    std::string line;
    while (std::getline(in, line)) {
      nlohmann::json frame = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
      if (!frame.is_discarded()) visit(line, frame);  // a line cut short by a full disk is left out
    }
  };
  FrameSummary summary;
  forEachFrame([&](const std::string&, const nlohmann::json& frame) { summary.add(frame); });
  nlohmann::json doc = runJson(run);
  doc["summary"] = summary.json();
  // The run's keys, then "frames" last, one frame a line (its order in the object means nothing to
  // a JSON reader; one a line keeps a long run's file readable and greppable).
  std::string head = dumpJson(doc, 2);
  head.erase(head.find_last_of('}'));
  while (!head.empty() && (head.back() == '\n' || head.back() == ' ')) head.pop_back();
  gpu::writeFileAtomically(stats_, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << head << ",\n  \"frames\": [";
    bool first = true;
    forEachFrame([&](const std::string& line, const nlohmann::json&) {
      out << (first ? "\n    " : ",\n    ") << line;
      first = false;
    });
    out << (first ? "]\n}\n" : "\n  ]\n}\n");
    out.flush();
    if (!out) cannotWrite(stats_, std::strerror(errno));
  });
  std::error_code ec;
  std::filesystem::remove(frames_, ec);
}

}  // namespace tallow::app
