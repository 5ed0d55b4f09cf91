#include "app/commands/gnuplot.h"

#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "gpu/atomic_file.h"

namespace tallow::app {
namespace {
/// Every plot of ours: CSV input, PNG output of one size.
constexpr const char* kPreamble = "set datafile separator ','\nset terminal pngcairo size 900,600 font ',11'\n";
}  // namespace

bool gnuplotAvailable() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

std::string gnuplotString(const std::string& text) {
  std::string q = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

bool runGnuplot(const std::filesystem::path& script, const PlotScriptWriter& writeScript,
                const std::vector<std::filesystem::path>& outputs, const std::string& what, bool keepScript) {
  if (!gnuplotAvailable()) {
    std::fprintf(stderr, "tallow: gnuplot is not installed; wrote the CSV files without plots\n");
    return false;
  }
  std::vector<std::filesystem::path> temporaries;
  for (const auto& o : outputs) {
    std::string name = ".";
    name += o.filename().string();
    name += ".tmp";
    temporaries.push_back(o.parent_path() / name);
  }
  {
    std::FILE* f = std::fopen(script.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + script.string());
    std::fputs(kPreamble, f);
    writeScript(f, temporaries);
    std::fclose(f);
  }
  // gnuplot's messages go to a temporary log (removed with it), whose last line says what failed.
  std::string logName = ".";
  logName += script.filename().string();
  logName += ".log";
  const gpu::PendingFile log(script.parent_path() / logName);
  std::string command = "gnuplot '";
  command += script.string();
  command += "' 2>'";
  command += log.temporary().string();
  command += "'";
  const int rc = std::system(command.c_str());
  if (!keepScript) std::filesystem::remove(script);
  if (rc != 0) {
    for (const auto& t : temporaries) std::filesystem::remove(t);
    std::ifstream in(log.temporary());
    std::string line, last;
    while (std::getline(in, line))
      if (line.find_first_not_of(" \t^") != std::string::npos) last = line;
    throw std::runtime_error("gnuplot failed to draw " + what + (last.empty() ? "" : ": " + last));
  }
  for (std::size_t i = 0; i < outputs.size(); ++i) std::filesystem::rename(temporaries[i], outputs[i]);
  return true;
}

}  // namespace tallow::app
