#include "app/commands/bench_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <thread>

#include "app/commands/bench_plot.h"
#include "app/commands/capture_command.h"
#include "app/commands/comparison_figure.h"
#include "app/commands/frame_stats.h"
#include "app/commands/gnuplot.h"
#include "app/commands/interrupt.h"
#include "app/commands/output_folder.h"
#include "app/commands/mesh_command.h"
#include "app/commands/progress.h"
#include "app/commands/provenance.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/params.h"
#include "gpu/atomic_file.h"
#include "gpu/gl_context.h"
#include "gpu/image_error.h"
#include "gpu/image_io.h"
#include "sss/maps/radiosity_maps.h"
#include "sss/reference/reference_integrator.h"
#include "sss/renderer.h"

namespace tallow::app {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

/// The reference integrates subsurface transport for every method but albedo; the bench's ground
/// truth is that, whatever method the rows use.
constexpr const char* kReferenceMethod = "radiosity-maps";
/// The equal-time reference draws a stream independent of the converged one it is compared with.
constexpr std::uint64_t kReferenceSeed = 1;
constexpr std::uint64_t kEqualTimeSeedOffset = 1000;
/// A cap on the equal-time reference's passes, which its time budget stops long before.
constexpr int kEqualTimeMaxPasses = 1 << 16;
/// Fewer object pixels than this make the error a statistic of a handful of pixels: said.
constexpr std::size_t kFewObjectPixels = 1000;
/// Where each row's pictures go: DIR/rows/<row>/.
constexpr const char* kRowsFolder = "rows";

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// One method × setting.
struct Case {
  std::string method;
  std::vector<std::string> values;  ///< one per sweep
  int group = 0;                    ///< index of its reference
  std::string name;                 ///< file-name stem
  SceneOptions scene;
  LoadedScene loaded;
};

/// The settings a reference depends on (the non-knob swept values) and its result.
struct ReferenceGroup {
  std::vector<std::pair<std::string, std::string>> settings;
  SceneOptions scene;
  gpu::Image radiance, standardError;
  gpu::Image emergent;  ///< --receivers: the emergent term alone, alpha 1 on receiver pixels
  std::size_t objectPixels = 0;
  std::size_t fireflies = 0;  ///< gpu::fireflyCount of the reference itself (its own noise)
  json info;  ///< passes, relative error, seconds, file
  /// The GPU's triangles of the field objects, which the integrations here (the reference, the
  /// equal-time runs) take; made before the bench's own context exists.
  sss::FieldMeshes fieldMeshes;
  std::string file;  ///< name in DIR, when computed here
  bool complete = true;  ///< false: a stop request cut its integration short
  /// Its relative standard error ε (NaN when unknown): a row's error below it is the reference's noise.
  double relError() const {
    if (info.contains("rel_error") && info["rel_error"].is_number()) return info["rel_error"].get<double>();
    if (info.contains("attributes") && info["attributes"].contains("tallow.rel_error")) {
      try {
        return std::stod(info["attributes"]["tallow.rel_error"].get<std::string>());
      } catch (const std::exception&) {
        // Not a number: unknown.
      }
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
};

struct FramePoint {
  int index = 0;
  double cumulativeMs = 0.0;
  gpu::ImageError error;
};

struct RowResult {
  int frames = 0, convergedFrames = 0;
  double firstWallMs = 0.0;
  gpu::ImageError firstError, lastError;
  std::optional<gpu::HalvesError> lastHalves;  ///< the last frame's upper and lower half of the object
  std::size_t lastFireflies = 0;              ///< gpu::fireflyCount of the last frame
  std::vector<double> wallMs, accumulatingMs, convergedMs;
  std::map<std::string, std::vector<double>> passMs;
  std::map<std::string, std::vector<double>> passCpuMs;  ///< the CPU clock's time in each pass
  std::vector<FramePoint> convergence;
  std::size_t gpuBytes = 0, triangles = 0;
  std::optional<std::size_t> mapsBytes;
  std::optional<int> mapSize, lightMapSize;  ///< the radiosity maps' sizes in use (what "auto" chose)
  std::optional<int> maps;                   ///< K in use (what sss.maps=auto chose)
  gpu::Image first, last;
  // --equal-time
  std::optional<gpu::ImageError> equalTimeError;
  int equalTimePasses = 0;
  double equalTimeMs = 0.0;
  gpu::Image equalTimeImage;
  // --receivers
  std::optional<gpu::ImageError> receiverError;
};

std::string fileStem(const std::string& text) {
  std::string s;
  for (const char c : text) s += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
  return s;
}

std::vector<std::vector<std::string>> cartesian(const std::vector<Sweep>& sweeps) {
  std::vector<std::vector<std::string>> combos{{}};
  for (const Sweep& s : sweeps) {
    std::vector<std::vector<std::string>> next;
    for (const auto& c : combos)
      for (const std::string& v : s.values) {
        next.push_back(c);
        next.back().push_back(v);
      }
    combos = std::move(next);
  }
  return combos;
}

void checkOptions(const BenchOptions& o) {
  if (o.outDir.empty()) throw InputError("bench: --out DIR is required");
  if (o.frames < kMinBenchFrames)
    throw InputError("--frames: must be at least " + std::to_string(kMinBenchFrames));
  const int given = (o.reference.empty() ? 0 : 1) + (o.refRelError ? 1 : 0) + (o.refSpp == kNotGiven ? 0 : 1);
  if (given != 1)
    throw InputError("bench: give exactly one of --reference REF.exr, --ref-rel-error E or --ref-spp S");
  if (o.refRelError && !(std::isfinite(*o.refRelError) && *o.refRelError > 0.0))
    throw InputError("--ref-rel-error: must be a positive number");
  if (o.refSpp != kNotGiven && o.refSpp < 1) throw InputError("--ref-spp: must be at least 1");
  if (o.refPoints < 0) throw InputError("--ref-points: must be 0 (automatic) or more");
  checkTime("--time", o.timeS);
}

/// --reference REF.exr and REF_stderr.exr (with --receivers also REF_emergent.exr), checked against
/// the render size.
void loadGivenReference(const BenchOptions& o, int width, int height, ReferenceGroup& g) {
  ReferenceImages pair = readReferencePair(o.reference, width, height, "the bench");
  g.radiance = std::move(pair.radiance);
  g.standardError = std::move(pair.standardError);
  if (o.receivers) g.emergent = readReferenceImage(emergentPath(o.reference), width, height, "the bench");
  g.info = {{"file", std::filesystem::absolute(o.reference).string()}};
  try {
    for (const auto& [k, v] : gpu::readExrStringAttributes(o.reference)) g.info["attributes"][k] = v;
  } catch (const std::exception&) {
    // Attributes are informative only; the pixels were read above.
  }
}

void computeGroupReference(const BenchOptions& o, ReferenceGroup& g, const sss::ReferenceProgress& progress) {
  ReferenceOptions r;
  r.scene = g.scene;
  r.timeS = o.timeS;
  r.spp = o.refSpp;
  r.relError = o.refRelError;
  r.points = o.refPoints;
  r.seed = kReferenceSeed;
  r.pixelFilter = "centre";  // the rows are drawn at the pixel centres (render.aa=1 in their sets)
  r.out = g.file;  // validateReferenceOptions wants a name; nothing is written by computeReference
  if (o.receivers) r.emergent = sss::kDefaultEmitterPoints;
  const sss::ReferenceResult result = computeReference(r, progress, &g.fieldMeshes);
  g.complete = !interrupted();
  g.radiance = result.radiance;
  g.standardError = result.standardError;
  g.emergent = result.emergent;
  g.info = {{"file", g.file},
            {"passes", result.passes},
            {"points_per_pass", result.pointsPerPass},
            {"rel_error", result.relError},
            {"rel_error_statistic", sss::kReferenceErrorStatistic},
            {"seconds", result.seconds},
            {"seed", kReferenceSeed},
            {"threads", std::thread::hardware_concurrency()}};
  if (o.receivers)
    g.info["emergent"] = {{"emitter_points", result.emitterPoints},
                          {"receiver_pixels", result.emergentPixels},
                          {"rel_error", result.emergentRelError},
                          {"rel_error_statistic", sss::kEmergentErrorStatistic}};
}

/// Our method's frames after a warm-up frame and a restart (see docs/commands.md).
RowResult runRow(const Case& c, const ReferenceGroup& ref, const gpu::ShaderLibrary& shaders, int minFrames,
                 double timeS, bool receivers) {
  const sss::Scene& scene = c.loaded.config.scene;
  const sss::RenderSettings& settings = c.loaded.config.render;
  sss::Renderer renderer(shaders, scene, settings);
  renderer.render(scene, settings, timeS);  // warm-up: shader compiles, allocations, the field's extraction
  glFinish();
  renderer.restartAccumulation();

  RowResult row;
  // Progressive methods accumulate for their frame count; two converged frames follow.
  const int accumulated =
      settings.sss.method == sss::SssMethod::ImageSpace ? settings.imageSpace.frames : settings.sss.frames;
  row.frames = std::max(minFrames, accumulated + 2);
  double cumulative = 0.0;
  for (int i = 0; i < row.frames; ++i) {
    throwIfInterrupted();  // a row stopped half-way is not a row: it is left out
    const auto plan = renderer.planFrame(scene, settings, timeS);
    const bool accumulating = std::any_of(plan.begin(), plan.end(), [](const sss::PlannedPass& p) {
      return p.name == "sss.maps" || p.name == "image_space.scatter";
    });
    const auto start = Clock::now();
    sss::FrameTimings timings = renderer.render(scene, settings, timeS);
    glFinish();
    const double ms = msSince(start);
    renderer.resolveTimings(timings);  // after glFinish: no wait
    cumulative += ms;
    row.wallMs.push_back(ms);
    (accumulating ? row.accumulatingMs : row.convergedMs).push_back(ms);
    for (const auto& p : timings.passes) {
      row.passMs[p.name].push_back(p.gpuMs);
      row.passCpuMs[p.name].push_back(p.cpuMs);
    }
    gpu::Image image = renderer.readRadiance();
    const gpu::ImageError e = gpu::imageError(image, ref.radiance, ref.standardError);
    row.convergence.push_back({i, cumulative, e});
    if (i == 0) {
      row.firstWallMs = ms;
      row.firstError = e;
      row.first = std::move(image);
    } else if (i + 1 == row.frames) {
      row.lastError = e;
      row.last = std::move(image);
    }
  }
  if (receivers) {
    // The VPL term alone: the same frame without VPLs (the maps stay as they are: vpl.count is not
    // part of their state), subtracted.
    sss::RenderSettings without = settings;
    without.vpl.count = 0;
    renderer.render(scene, without, timeS);
    const gpu::Image dark = renderer.readRadiance();
    gpu::Image term = row.last;
    for (std::size_t i = 0; i < term.pixels.size(); ++i)
      term.pixels[i] = glm::vec4(glm::vec3(term.pixels[i] - dark.pixels[i]), 1.0f);
    row.receiverError = gpu::imageError(term, ref.emergent, ref.emergent);
  }
  row.lastHalves = gpu::imageErrorByHalf(row.last, ref.radiance, ref.standardError);
  row.lastFireflies = gpu::fireflyCount(row.last, ref.standardError);
  row.convergedFrames = static_cast<int>(row.convergedMs.size());
  row.gpuBytes = renderer.gpuBytes();
  row.triangles = renderer.triangleCount();
  if (const sss::RadiosityMaps* maps = renderer.module<sss::RadiosityMaps>()) {
    row.mapsBytes = maps->bytes();
    if (maps->mapSize() > 0) row.mapSize = maps->mapSize();  // 0: the method drew no maps (no-cache)
    if (!maps->views().empty()) row.maps = static_cast<int>(maps->views().size());
    if (maps->lightMapSize() > 0) row.lightMapSize = maps->lightMapSize();
  }
  return row;
}

/// The reference integrator with a fresh seed, stopped once it has run as long as our first frame.
void runEqualTime(const LoadedScene& truth, const ReferenceGroup& ref, const BenchOptions& o, RowResult& row) {
  sss::ReferenceSettings s;
  s.timeS = o.timeS;
  s.maxPasses = kEqualTimeMaxPasses;
  s.pointsPerPass = o.refPoints;
  s.seed = kReferenceSeed + kEqualTimeSeedOffset;
  s.pixelFilter = sss::PixelFilter::Centre;  // as the reference it is compared with
  s.fieldMeshes = ref.fieldMeshes;
  const double budgetMs = row.firstWallMs;
  const auto start = Clock::now();
  const sss::ReferenceResult r = sss::renderReference(
      truth.config.scene, truth.config.render, s, [&](int, double) { return msSince(start) < budgetMs && !interrupted(); });
  throwIfInterrupted();
  row.equalTimeMs = msSince(start);
  row.equalTimePasses = r.passes;
  row.equalTimeError = gpu::imageError(r.radiance, ref.radiance, ref.standardError);
  row.equalTimeImage = r.radiance;
}

/// A mean ratio for the console, to 3 decimals.
std::string ratioText(double ratio) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", ratio);
  return text;
}

json optionalNumber(const std::vector<double>& values) { return values.empty() ? json(nullptr) : json(median(values)); }

std::string cell(const json& v) {
  if (v.is_null()) return "";
  if (v.is_number()) return formatNumber(v.get<double>());
  return v.is_string() ? v.get<std::string>() : v.dump();
}

json errorJson(const gpu::ImageError& e) {
  const auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return {{"rmse", number(e.rmse)}, {"rel_rmse", number(e.relRmse)}, {"max", number(e.maxError)},
          {"mean_ratio", number(e.meanRatio)}, {"non_finite_pixels", e.nonFiniteImage}};
}

/// "4.2%" (or "unknown" for a reference without an estimate).
std::string percent(double v) {
  if (!std::isfinite(v)) return "unknown";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * v);
  return text;
}

/// The rows' convergence after the restart (convergence.png, its script kept as convergence.gp,
/// which reads convergence.csv beside it). `rows`: the rows' names (fileStem: no blank in them).
void writeConvergencePlot(const std::filesystem::path& outDir, const std::string& title,
                          const std::vector<std::string>& rows) {
  std::string words;
  for (const std::string& r : rows) words += (words.empty() ? "" : " ") + r;
  GnuplotRun(outDir).draw(
      [&](std::FILE* f, const std::vector<std::string>& output) {
        // convergence.csv: column 1 the row's name; the others are looked up by header name.
        std::fprintf(f,
                     "set key autotitle columnhead\n"
                     "set output %s\n"
                     "set title %s noenhanced\n"
                     "set xlabel 'frames since the restart'\nset ylabel 'relative RMSE'\nset grid\n"
                     "set key outside right noenhanced\n"
                     "rows = %s\n"
                     "plot for [r in rows] 'convergence.csv' using ((strcol(1) eq r) ? column('frame') + 1 : 1/0):'rel_rmse' "
                     "with linespoints title r\n",
                     output[0].c_str(), gnuplotString(title + ": convergence after a restart").c_str(),
                     gnuplotString(words).c_str());
      },
      {"convergence.png"}, "the bench's convergence plot", "convergence.gp");
}

/// What the bench has done so far, as the tables and bench.json say it.
struct BenchState {
  const BenchOptions* options = nullptr;
  const LoadedScene* base = nullptr;
  std::vector<std::string> methods;
  std::vector<Sweep> sweeps;
  std::vector<Case>* cases = nullptr;
  std::vector<ReferenceGroup>* groups = nullptr;
  std::vector<std::pair<std::size_t, RowResult>> rows;  ///< (case index, result), in the order run
  std::vector<std::string> passNames;                   ///< in the order first seen
  std::vector<std::string> warnings;
  json gpu;
  std::string state = "running";  ///< "running", "complete", "interrupted"
};

/// bench.csv, convergence.csv and bench.json of the rows done, each rewritten whole.
void writeTables(const std::filesystem::path& out, const BenchState& b) {
  const BenchOptions& o = *b.options;
  const bool givenReference = !o.reference.empty();
  std::vector<std::string> header = {"row", "method"};
  for (const Sweep& s : b.sweeps) header.push_back(s.key);
  for (const char* h : {"reference", "reference_rel_error", "frames", "converged_frames", "first_wall_ms", "first_rmse",
                        "first_rel_rmse", "median_wall_ms", "median_accumulating_wall_ms", "median_converged_wall_ms"})
    header.push_back(h);
  for (const std::string& p : b.passNames) header.push_back("gpu_ms_" + p);
  for (const char* h : {"last_rmse", "last_rel_rmse", "last_max_error", "last_upper_mean_ratio", "last_lower_mean_ratio",
                        "last_fireflies", "reference_fireflies"})
    header.push_back(h);
  if (o.equalTime)
    for (const char* h : {"equal_time_ms", "equal_time_passes", "equal_time_rel_rmse"}) header.push_back(h);
  for (const char* h : {"object_pixels", "gpu_bytes", "maps_bytes", "triangles"}) header.push_back(h);

  json jsonRows = json::array(), jsonConvergence = json::array();
  std::string csv, convergenceCsv = "row,method";
  for (const Sweep& s : b.sweeps) convergenceCsv += "," + s.key;
  convergenceCsv += ",frame,cumulative_wall_ms,rmse,rel_rmse\n";
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (i) csv += ',';
    csv += header[i];
  }
  csv += "\n";
  const Registry registry = parameterRegistry(b.base->materials);
  for (const auto& [index, row] : b.rows) {
    const Case& c = (*b.cases)[index];
    const ReferenceGroup& ref = (*b.groups)[static_cast<std::size_t>(c.group)];
    json settings = json::object();
    for (std::size_t i = 0; i < b.sweeps.size(); ++i) settings[b.sweeps[i].key] = c.values[i].empty() ? json(nullptr) : json(c.values[i]);  // null: not read
    json passMedians = json::object();
    for (const std::string& p : b.passNames) {
      const auto it = row.passMs.find(p);
      passMedians[p] = it == row.passMs.end() ? json(nullptr) : json(median(it->second));
    }
    const double eps = ref.relError();
    json values = {{"row", c.name},
                   {"method", c.method},
                   {"folder", std::string(kRowsFolder) + "/" + c.name},
                   {"reference", givenReference ? std::filesystem::path(o.reference).filename().string() : ref.file},
                   {"reference_rel_error", std::isfinite(eps) ? json(eps) : json(nullptr)},
                   {"frames", row.frames},
                   {"converged_frames", row.convergedFrames},
                   {"first_wall_ms", row.firstWallMs},
                   {"first_rmse", row.firstError.rmse},
                   {"first_rel_rmse", row.firstError.relRmse},
                   {"median_wall_ms", median(row.wallMs)},
                   {"median_accumulating_wall_ms", optionalNumber(row.accumulatingMs)},
                   {"median_converged_wall_ms", optionalNumber(row.convergedMs)},
                   {"last_rmse", row.lastError.rmse},
                   {"last_rel_rmse", row.lastError.relRmse},
                   {"last_max_error", row.lastError.maxError},
                   {"last_fireflies", row.lastFireflies},
                   {"reference_fireflies", ref.fireflies},
                   {"last_upper_mean_ratio", row.lastHalves ? json(row.lastHalves->upper.meanRatio) : json(nullptr)},
                   {"last_lower_mean_ratio", row.lastHalves ? json(row.lastHalves->lower.meanRatio) : json(nullptr)},
                   {"object_pixels", row.lastError.pixels},
                   {"gpu_bytes", row.gpuBytes},
                   {"maps_bytes", row.mapsBytes ? json(*row.mapsBytes) : json(nullptr)},
                   {"map_size_used", row.mapSize ? json(*row.mapSize) : json(nullptr)},
                   {"maps_used", row.maps ? json(*row.maps) : json(nullptr)},
                   {"light_map_size_used", row.lightMapSize ? json(*row.lightMapSize) : json(nullptr)},
                   {"triangles", row.triangles}};
    if (row.equalTimeError) {
      values["equal_time_ms"] = row.equalTimeMs;
      values["equal_time_passes"] = row.equalTimePasses;
      values["equal_time_rel_rmse"] = row.equalTimeError->relRmse;
    }
    for (std::size_t i = 0; i < header.size(); ++i) {
      const std::string& h = header[i];
      json v = values.contains(h) ? values[h] : settings.contains(h) ? settings[h] : json(nullptr);
      if (h.rfind("gpu_ms_", 0) == 0) v = passMedians[h.substr(7)];
      if (i) csv += ',';
      csv += cell(v);
    }
    csv += "\n";
    json convergence = json::array();
    for (const FramePoint& p : row.convergence) {
      convergenceCsv += c.name + "," + c.method;
      for (const std::string& v : c.values) convergenceCsv += "," + v;
      // Appended piece by piece: `"," + std::string&&` trips GCC 12's false -Wrestrict (bug 105651).
      for (const std::string& cellText : {std::to_string(p.index), formatNumber(p.cumulativeMs),
                                          formatNumber(p.error.rmse), formatNumber(p.error.relRmse)}) {
        convergenceCsv += ',';
        convergenceCsv += cellText;
      }
      convergenceCsv += '\n';
      convergence.push_back({{"frame", p.index}, {"cumulative_wall_ms", p.cumulativeMs}, {"rmse", p.error.rmse},
                             {"rel_rmse", p.error.relRmse}});
    }
    values["settings"] = settings;
    values["gpu_ms_median"] = passMedians;
    json cpuMedians = json::object();
    for (const auto& [name, ms] : row.passCpuMs) cpuMedians[name] = median(ms);
    values["cpu_ms_median"] = cpuMedians;
    values["wall_ms"] = row.wallMs;
    values["first_error"] = errorJson(row.firstError);
    values["last_error"] = errorJson(row.lastError);
    if (row.equalTimeError) values["equal_time_error"] = errorJson(*row.equalTimeError);
    if (row.receiverError) values["receiver_error"] = errorJson(*row.receiverError);
    values["parameters"] = registry.snapshot(c.loaded.config);
    jsonRows.push_back(values);
    jsonConvergence.push_back({{"row", c.name}, {"frames", convergence}});
  }

  json references = json::array();
  for (const ReferenceGroup& g : *b.groups) {
    json s = json::object();
    for (const auto& [k, v] : g.settings) s[k] = v;
    json entry = g.info;
    entry["settings"] = s;
    entry["object_pixels"] = g.objectPixels;
    entry["fireflies"] = g.fireflies;
    entry["complete"] = g.complete;
    references.push_back(entry);
  }
  json provenance = provenanceJson();
  provenance["gl"] = b.gpu;
  const json result = {
      {"command", "bench"},
      {"run", {{"state", b.state}, {"rows_requested", b.cases->size()}, {"rows_written", b.rows.size()}}},
      {"provenance", provenance},
      {"preset", b.base->presetName},
      {"width", b.base->config.render.width},
      {"height", b.base->config.render.height},
      {"time_s", o.timeS},
      {"sets", o.scene.sets},
      {"sweeps", o.sweeps},
      {"methods", b.methods},
      {"min_frames", o.frames},
      {"equal_time", o.equalTime},
      {"receivers", o.receivers},
      {"gpu", b.gpu},
      {"cpu", provenance["cpu"]},
      {"reference_method", kReferenceMethod},
      {"references", references},
      {"warnings", b.warnings},
      {"error_metric",
       "over object pixels (reference standard-error alpha >= 0.5): e_p = sqrt(dr^2+dg^2+db^2); rmse = "
       "sqrt(mean e_p^2); rel_rmse = rmse / sqrt(mean (r^2+g^2+b^2) of the reference); max = max e_p"},
      {"rows", jsonRows},
      {"convergence", jsonConvergence}};
  gpu::writeTextFileAtomically(out / "bench.csv", csv);
  gpu::writeTextFileAtomically(out / "convergence.csv", convergenceCsv);
  gpu::writeTextFileAtomically(out / "bench.json", result.dump(2) + "\n");
}

/// A row's pictures in DIR/rows/<row>/: first.png, last.png, last.exr and comparison.png (the
/// reference, the first and last frames, with --equal-time the reference run as long as the first
/// frame, and their differences to the reference in false colour).
void writeRowPictures(const std::filesystem::path& folder, const Case& c, const ReferenceGroup& ref,
                      const RowResult& row, bool figures) {
  std::filesystem::create_directories(folder);
  const gpu::ToneMapSettings& toneMap = c.loaded.config.render.toneMap;
  gpu::writePng(folder / "first.png", row.first, toneMap);
  gpu::writePng(folder / "last.png", row.last, toneMap);
  gpu::writeExr(folder / "last.exr", row.last, gpu::ExrPixelType::Float);
  if (!figures) return;
  FigureSpec spec;
  spec.title = c.name;
  spec.toneMap = toneMap;
  spec.mask = &ref.standardError;
  spec.images = {{&ref.radiance, "reference"},
                 {&row.first, "first frame (" + percent(row.firstError.relRmse) + ")"},
                 {&row.last, "last frame, " + std::to_string(row.frames) + " frames (" +
                                 percent(row.lastError.relRmse) + ")"}};
  spec.differences = {{&row.first, &ref.radiance, "|first − reference|", 1},
                      {&row.last, &ref.radiance, "|last − reference|", 2}};
  if (row.equalTimeError) {
    std::string caption = "equal-time reference (";
    caption += percent(row.equalTimeError->relRmse);
    caption += ")";
    spec.images.push_back({&row.equalTimeImage, caption});
    spec.differences.push_back({&row.equalTimeImage, &ref.radiance, "|equal time − reference|", 3});
  }
  writeComparisonFigure(folder / "comparison.png", spec);
}

/// The registry keys the passes planned for `config` read or are paced by (sss/pass.h), the
/// surface pass's share for the selected method included.
std::set<std::string> keysRead(const Config& config) {
  std::set<std::string> keys;
  for (const sss::PlannedPass& p : sss::Renderer::plan(config.scene, config.render)) {
    keys.insert(p.io.reads.begin(), p.io.reads.end());
    keys.insert(p.io.paces.begin(), p.io.paces.end());
  }
  return keys;
}

/// A sweep of a method's knob applies only to the methods that read its key (issue 19): for the
/// others its values would render identical rows, so they get one row, the key not applicable
/// (an empty value: no part in the row's name, null in bench.json). Keys that change the ground
/// truth are left to every method: each value is compared against its own reference.
std::vector<Case> onlyWhereRead(std::vector<Case> cases, const std::vector<Sweep>& sweeps) {
  // A method reads a key when a pass of any of its rows does: the plan itself may depend on the
  // swept value (vpl.count=0 plans no VPL pass), so every value is asked.
  std::map<std::string, std::set<std::string>> readBy;
  for (const Case& c : cases) readBy[c.method].merge(keysRead(c.loaded.config));
  std::vector<Case> kept;
  std::set<std::pair<std::string, std::vector<std::string>>> seen;
  for (Case& c : cases) {
    for (std::size_t i = 0; i < sweeps.size(); ++i)
      if (sweeps[i].knob && readBy[c.method].count(sweeps[i].key) == 0) c.values[i].clear();  // not applicable
    if (!seen.emplace(c.method, c.values).second) continue;  // the same row as one already kept
    c.name = fileStem(c.method);
    for (std::size_t i = 0; i < sweeps.size(); ++i)
      if (!c.values[i].empty()) c.name += '_' + fileStem(sweeps[i].key) + '-' + fileStem(c.values[i]);
    kept.push_back(std::move(c));
  }
  return kept;
}

}  // namespace

int runBench(const BenchOptions& o) {
  checkOptions(o);
  std::vector<Sweep> sweeps;
  for (const std::string& text : o.sweeps) {
    sweeps.push_back(parseSweep(text));
    for (std::size_t i = 0; i + 1 < sweeps.size(); ++i)
      if (sweeps[i].key == sweeps.back().key) throw InputError("--sweep: " + sweeps.back().key + " is swept twice");
  }
  const bool givenReference = !o.reference.empty();
  for (const Sweep& s : sweeps)
    if (givenReference && !s.knob)
      throw InputError("--sweep: " + s.key + " changes the ground truth, so it needs one reference per value: use "
                       "--ref-rel-error or --ref-spp instead of --reference");

  // Every case through the registry before any file or GL work: unknown keys, values out of range
  // and unknown methods give the registry's one line.
  const LoadedScene base = loadScene(o.scene);
  const Registry registry = parameterRegistry(base.materials);
  // --methods and --sweep each under its own name before they are combined into the rows' settings.
  checkMethods(registry, o.methods);
  for (std::size_t i = 0; i < sweeps.size(); ++i)
    for (const std::string& v : sweeps[i].values) checkSweepValue(registry, base.config, o.sweeps[i], sweeps[i].key, v);
  std::vector<std::string> methods = o.methods;
  if (methods.empty()) methods = registry.find("method")->choices;
  std::vector<Case> cases;
  std::vector<ReferenceGroup> groups;
  std::map<std::vector<std::string>, int> groupOf;
  for (const std::string& method : methods)
    for (const auto& values : cartesian(sweeps)) {
      Case c;
      c.method = method;
      c.values = values;
      c.scene = o.scene;
      // The CPU reference has no visible flame: the rows are rendered without it (first, so that a
      // --set render.flame=true given on purpose still wins).
      c.scene.sets.insert(c.scene.sets.begin(), "render.flame=false");
      // Each frame is measured as drawn, at the pixel centres, against a reference at the pixel
      // centres: anti-aliasing (render.aa) is measured on its own (scripts/results_picture.py), and
      // the VPL term is the difference of two frames (a still's average would mix them).
      c.scene.sets.insert(c.scene.sets.begin(), "render.aa=1");
      c.scene.sets.push_back("method=" + method);
      std::vector<std::string> truthKey;
      std::vector<std::pair<std::string, std::string>> truthSettings;
      for (std::size_t i = 0; i < sweeps.size(); ++i) {
        c.scene.sets.push_back(sweeps[i].key + "=" + values[i]);
        if (!sweeps[i].knob) {
          truthKey.push_back(values[i]);
          truthSettings.emplace_back(sweeps[i].key, values[i]);
        }
      }
      c.loaded = loadScene(c.scene);
      const auto [it, added] = groupOf.emplace(truthKey, static_cast<int>(groups.size()));
      if (added) {
        ReferenceGroup g;
        g.settings = truthSettings;
        g.scene = o.scene;
        for (const auto& [k, v] : truthSettings) g.scene.sets.push_back(k + "=" + v);
        g.scene.sets.push_back(std::string("method=") + kReferenceMethod);
        groups.push_back(std::move(g));
      }
      c.group = it->second;
      cases.push_back(std::move(c));
    }
  cases = onlyWhereRead(std::move(cases), sweeps);
  const int width = base.config.render.width, height = base.config.render.height;
  for (const Case& c : cases)
    if (c.loaded.config.render.width != width || c.loaded.config.render.height != height)
      throw InputError("--sweep: every row must render at one size; sweep --size-independent keys only");

  const std::filesystem::path out(o.outDir);
  checkWritableFolder(out);
  // The folder is this run's: a second bench into it refuses, and what an earlier one left goes
  // just before this one writes its first file.
  OutputFolder folder(out, "bench");
  bool claimed = false;
  const auto claimFolder = [&] {
    if (claimed) return;
    folder.clearEarlierRun({"bench.csv", "bench.json", "convergence.csv", "convergence.png", "convergence.gp",
                            "speed_error.png", "speed_error.gp", "reference.exr", "reference_*.exr", kRowsFolder});
    claimed = true;
  };

  BenchState state;
  state.options = &o;
  state.base = &base;
  state.methods = methods;
  state.sweeps = sweeps;
  state.cases = &cases;
  state.groups = &groups;
  const auto warn = [&](Progress* progress, const std::string& text) {
    state.warnings.push_back(text);
    const std::string line = "tallow: warning: bench: " + text;
    if (progress) progress->print(line, stderr);
    else std::fprintf(stderr, "%s\n", line.c_str());
  };

  // SIGINT/SIGTERM: the reference in hand stops after its pass, a row in hand is dropped; what is
  // done is written (the references, the rows finished, the tables of those, the plots).
  const InterruptScope interruptScope;

  // The references: read, or integrated on the CPU and written as soon as each is done.
  for (std::size_t gi = 0; gi < groups.size(); ++gi) {
    ReferenceGroup& g = groups[gi];
    if (!givenReference || o.equalTime)
      g.fieldMeshes = drawnFieldMeshes(loadScene(g.scene), g.scene.shaderDir, o.timeS, o.gl);
    if (givenReference) {
      loadGivenReference(o, width, height, g);
    } else {
      g.file = "reference";
      if (groups.size() > 1) g.file += "_" + std::to_string(gi);
      g.file += ".exr";
      std::string what = "reference";
      if (groups.size() > 1) what += " " + std::to_string(gi + 1) + " of " + std::to_string(groups.size());
      Progress progress(what, "pass", 0);
      ReferenceOptions tracked;
      tracked.spp = o.refSpp;
      tracked.relError = o.refRelError;
      ReferenceTracker tracker(tracked, progress);
      computeGroupReference(o, g, std::ref(tracker));
      progress.finish();
      claimFolder();
      std::map<std::string, std::string> attributes = {{"tallow.preset", base.presetName},
                                                       {"tallow.passes", std::to_string(g.info["passes"].get<int>())},
                                                       {"tallow.rel_error", formatNumber(g.relError())},
                                                       {"tallow.version", tallowVersion()},
                                                       {"tallow.complete", g.complete ? "yes" : "no"}};
      gpu::writeExrFiles({{out / g.file, &g.radiance, gpu::ExrPixelType::Float, attributes},
                          {standardErrorPath(out / g.file), &g.standardError, gpu::ExrPixelType::Float, attributes}});
      std::fprintf(stderr, "tallow: bench: %s: %d pass(es), relative standard error ε %s%s\n", g.file.c_str(),
                   g.info["passes"].get<int>(), percent(g.relError()).c_str(), g.complete ? "" : " (stopped early)");
    }
    g.objectPixels = gpu::objectPixels(g.standardError);
    if (const std::size_t bad = gpu::nonFinitePixels(g.radiance))
      throw std::runtime_error("bench: the reference has " + std::to_string(bad) +
                               " NaN or infinite pixel(s): every error against it would be undefined");
    g.fireflies = gpu::fireflyCount(g.radiance, g.standardError);
    if (o.receivers && (g.emergent.pixels.empty() || gpu::objectPixels(g.emergent) == 0))
      throw InputError("bench: --receivers: the reference has no receiver pixel (no opaque surface in view)");
    if (g.objectPixels == 0)
      throw InputError("bench: the reference has no object pixel (no translucent object in view), so there is "
                       "nothing to compare");
    if (g.objectPixels < kFewObjectPixels)
      warn(nullptr, "only " + std::to_string(g.objectPixels) + " object pixels are compared" +
                        (givenReference ? std::string() : " (" + g.file + ")") + ": an error over so few pixels says " +
                        "little; raise --size or bring the object closer");
    if (interrupted()) break;
  }

  gpu::ContextOptions contextOptions;
  contextOptions.backend = gpu::parseGlBackend(o.gl);
  contextOptions.visible = false;
  const auto context = gpu::GlContext::create(contextOptions);
  const gpu::ShaderLibrary shaders = makeShaderLibrary(o.scene.shaderDir);
  state.gpu = glJson(*context);
  const bool figures = gnuplotAvailable();
  if (!figures) std::fprintf(stderr, "tallow: gnuplot is not installed: no comparison pictures and no plots\n");

  // The rows, each written when it is done (its pictures, then the tables of every row so far).
  const std::vector<std::string>& allMethods = registry.find("method")->choices;
  Progress progress("bench", "row", static_cast<int>(cases.size()));
  for (std::size_t ci = 0; ci < cases.size() && !interrupted(); ++ci) {
    const Case& c = cases[ci];
    const ReferenceGroup& ref = groups[static_cast<std::size_t>(c.group)];
    progress.update(static_cast<int>(ci), c.name);
    if (o.scene.explain)
    {
      std::string text = sss::formatPlan(sss::Renderer::plan(c.loaded.config.scene, c.loaded.config.render), c.name + ": ");
      if (!text.empty() && text.back() == '\n') text.pop_back();  // print() ends the line
      progress.print(text, stdout);
    }
    RowResult row;
    try {
      row = runRow(c, ref, shaders, o.frames, o.timeS, o.receivers);
      if (o.equalTime) {
        LoadedScene truth = loadScene(ref.scene);
        runEqualTime(truth, ref, o, row);
      }
    } catch (const Interrupted&) {
      break;
    }
    for (const auto& [name, ms] : row.passMs)
      if (std::find(state.passNames.begin(), state.passNames.end(), name) == state.passNames.end())
        state.passNames.push_back(name);
    char line[640];
    std::snprintf(line, sizeof line,
                  "%-40s first %9.3f ms rel %-7s median %9.3f ms  last rel %-7s (reference ε %s)  mean/ref upper %s "
                  "lower %s  fireflies %zu (reference %zu)",
                  c.name.c_str(), row.firstWallMs, percent(row.firstError.relRmse).c_str(), median(row.wallMs),
                  percent(row.lastError.relRmse).c_str(), percent(ref.relError()).c_str(),
                  row.lastHalves ? ratioText(row.lastHalves->upper.meanRatio).c_str() : "-",
                  row.lastHalves ? ratioText(row.lastHalves->lower.meanRatio).c_str() : "-", row.lastFireflies,
                  ref.fireflies);
    progress.print(line, stdout);
    if (!row.lastError.finite())
      warn(&progress, c.name + ": " + std::to_string(row.lastError.nonFiniteImage) +
                          " object pixel(s) of the last frame are NaN or infinite: its error is undefined");
    claimFolder();
    writeRowPictures(out / kRowsFolder / c.name, c, ref, row, figures);
    // The pictures are on disk: the row keeps only its numbers.
    row.first = row.last = row.equalTimeImage = gpu::Image();
    state.rows.emplace_back(ci, std::move(row));
    writeTables(out, state);
    progress.update(static_cast<int>(ci + 1));
  }
  progress.finish();

  state.state = interrupted() ? "interrupted" : "complete";
  claimFolder();
  writeTables(out, state);
  if (figures && !state.rows.empty()) {
    std::vector<SpeedErrorPoint> points;
    for (const auto& [index, row] : state.rows) {
      const Case& c = cases[index];
      SpeedErrorPoint p;
      p.method = c.method;
      p.style = static_cast<int>(std::find(allMethods.begin(), allMethods.end(), c.method) - allMethods.begin());
      for (std::size_t i = 0; i < sweeps.size(); ++i)
        if (!c.values[i].empty()) p.label += (p.label.empty() ? "" : ", ") + c.values[i];
      p.ms = median(row.wallMs);
      p.error = row.lastError.relRmse;
      points.push_back(p);
    }
    std::vector<ReferenceLine> lines;
    for (const ReferenceGroup& g : groups) {
      std::string label = "reference ε " + percent(g.relError());
      for (const auto& [k, v] : g.settings) label += (label.find('(') == std::string::npos ? " (" : ", ") + k + "=" + v;
      if (!g.settings.empty()) label += ")";
      lines.push_back({g.relError(), label});
    }
    writeSpeedErrorPlot(out, base.presetName, points, lines);
    std::vector<std::string> rowNames;
    for (const auto& [index, row] : state.rows) rowNames.push_back(cases[index].name);
    writeConvergencePlot(out, base.presetName, rowNames);
  }
  if (interrupted()) {
    std::fprintf(stderr, "tallow: bench stopped by %s after %zu of %zu row(s); wrote them to %s\n", interruptName(),
                 state.rows.size(), cases.size(), out.string().c_str());
    return interruptExitCode();
  }
  std::printf("tallow: bench of %s (%dx%d, %zu row(s), %s) -> %s\n", base.presetName.c_str(), width, height,
              state.rows.size(), context->info().renderer.c_str(), out.string().c_str());
  // A row whose error is undefined is a failed comparison, not a perfect one.
  const std::size_t undefined = static_cast<std::size_t>(std::count_if(
      state.rows.begin(), state.rows.end(), [](const auto& r) { return !r.second.lastError.finite(); }));
  if (undefined > 0) {
    std::fprintf(stderr, "tallow: bench: %zu row(s) rendered NaN or infinite pixels: their error is undefined\n",
                 undefined);
    return 1;
  }
  return 0;
}

}  // namespace tallow::app
