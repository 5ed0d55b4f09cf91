#include "app/commands/gnuplot.h"

#include <stdexcept>

#include "app/commands/subprocess.h"

namespace tallow::app {
namespace {
/// Every plot of ours: CSV input, PNG output of one size.
constexpr const char* kPreamble = "set datafile separator ','\nset terminal pngcairo size 900,600 font ',11'\n";
constexpr const char* kScript = "plot.gp";
constexpr const char* kLog = "gnuplot.log";

std::filesystem::path gnuplotPath() { return findExecutable("gnuplot"); }

/// The name of output i's variable, and of the file gnuplot draws it into in the private folder.
std::string outputVariable(std::size_t i) { return "output_" + std::to_string(i); }
std::string drawingName(std::size_t i) { return "output_" + std::to_string(i) + ".png"; }

void checkOwnName(std::string_view name) {
  for (const char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.'))
      throw std::logic_error("gnuplot: a private file name of [a-z0-9_.] only, not " + std::string(name));
}
}  // namespace

bool gnuplotAvailable() { return !gnuplotPath().empty(); }

std::string gnuplotString(std::string_view text) {
  std::string q = "'";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\'') q += "''";
    else if (u < 0x20 || u == 0x7f) q += ' ';
    else q += c;
  }
  return q + "'";
}

GnuplotRun::GnuplotRun(const std::filesystem::path& folder)
    : folder_(folder.empty() ? std::filesystem::path(".") : folder),
      private_(std::make_unique<gpu::PrivateFolder>(folder_, "tallow-plot")) {}

GnuplotRun::~GnuplotRun() = default;

std::filesystem::path GnuplotRun::dataPath(std::string_view name) const {
  checkOwnName(name);
  return private_->path() / name;
}

std::string GnuplotRun::dataLiteral(std::string_view name) const {
  checkOwnName(name);
  return gnuplotString(private_->name() + "/" + std::string(name));
}

bool GnuplotRun::draw(const ScriptWriter& writeScript, const std::vector<std::string>& outputs, const std::string& what,
                      const std::string& keptScript) {
  const std::filesystem::path gnuplot = gnuplotPath();
  if (gnuplot.empty()) {
    std::fprintf(stderr, "tallow: gnuplot is not installed; wrote the CSV files without plots\n");
    return false;
  }
  std::vector<std::string> variables;
  for (std::size_t i = 0; i < outputs.size(); ++i) variables.push_back(outputVariable(i));
  const std::filesystem::path script = private_->path() / kScript;
  {
    // The private folder is ours alone: a fixed name there cannot be a planted link.
    std::FILE* f = std::fopen(script.c_str(), "wx");
    if (!f) throw std::runtime_error("cannot write " + script.string());
    std::fputs(kPreamble, f);
    if (!keptScript.empty()) std::fprintf(f, "# redraw in this folder: gnuplot %s\n", keptScript.c_str());
    for (std::size_t i = 0; i < outputs.size(); ++i)
      std::fprintf(f, "if (!exists(\"%s\")) %s = %s\n", variables[i].c_str(), variables[i].c_str(),
                   gnuplotString(outputs[i]).c_str());
    writeScript(f, variables);
    if (std::fclose(f) != 0) throw std::runtime_error("cannot write " + script.string());
  }
  // The drawings go to the private folder: `-e` sets each variable to a name of ours before the
  // script runs (gnuplot's -e takes a command line, so only our names go there).
  std::string assignments;
  for (std::size_t i = 0; i < outputs.size(); ++i)
    assignments += variables[i] + "=" + gnuplotString(private_->name() + "/" + drawingName(i)) + ";";
  SpawnOptions spawn;
  spawn.workingFolder = folder_;
  spawn.stderrFile = private_->path() / kLog;
  if (!runProgram(gnuplot, {"-e", assignments, private_->name() + "/" + kScript}, spawn)) {
    const std::string last = lastMessageLine(private_->path() / kLog);
    throw std::runtime_error("gnuplot failed to draw " + what + (last.empty() ? "" : ": " + last));
  }
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    std::error_code ec;
    const std::filesystem::path target = folder_ / outputs[i];
    std::filesystem::rename(private_->path() / drawingName(i), target, ec);
    if (ec) throw std::runtime_error("cannot write " + target.string() + ": " + ec.message());
  }
  if (!keptScript.empty()) {
    std::error_code ec;
    const std::filesystem::path target = folder_ / keptScript;
    std::filesystem::rename(script, target, ec);
    if (ec) throw std::runtime_error("cannot write " + target.string() + ": " + ec.message());
  }
  return true;
}

}  // namespace tallow::app
