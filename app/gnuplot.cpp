#include "app/gnuplot.h"

#include <cstdlib>
#include <stdexcept>

namespace tallow::app {

bool gnuplotAvailable() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

void runGnuplot(const std::filesystem::path& script, const std::function<void(std::FILE*)>& writeScript,
                const std::vector<PlotOutput>& outputs, const std::string& what, bool keepScript) {
  {
    std::FILE* f = std::fopen(script.c_str(), "w");
    if (!f) throw std::runtime_error("cannot write " + script.string());
    writeScript(f);
    std::fclose(f);
  }
  std::string command = "gnuplot '";
  command += script.string();
  command += "' 2>/dev/null";
  const int rc = std::system(command.c_str());
  if (!keepScript) std::filesystem::remove(script);
  if (rc != 0) {
    for (const PlotOutput& o : outputs) std::filesystem::remove(o.temporary);
    throw std::runtime_error("gnuplot failed to draw " + what);
  }
  for (const PlotOutput& o : outputs) std::filesystem::rename(o.temporary, o.final);
}

}  // namespace tallow::app
