#include "app/commands/frame_stats.h"

#include "gpu/image_error.h"
#include "gpu/image_io.h"
#include "sss/maps/radiosity_maps.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>

#include "app/commands/provenance.h"

namespace tallow::app {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::size_t residentBytes() {
  std::ifstream in("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  if (!(in >> pages >> resident)) return 0;
  return resident * static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
}

nlohmann::json mapsRecord(const sss::Renderer& renderer) {
  const sss::RadiosityMaps* maps = renderer.radiosityMaps();
  if (!maps) return nullptr;
  return {{"maps", maps->views().size()}, {"frames_accumulated", maps->frames()}, {"map_bytes", maps->bytes()}};
}

nlohmann::json pixelsRecord(const gpu::PixelCensus& census, bool floatAsked) {
  return {{"non_finite", census.nonFinite},
          {"beyond_half", census.beyondHalf},
          {"exr", floatAsked || census.beyondHalf > 0 ? "float" : "half"}};
}

nlohmann::json clippedRecord(const gpu::Image& image, const std::vector<std::uint8_t>& translucent,
                             const gpu::ToneMapSettings& toneMap) {
  const std::vector<std::uint8_t> rgb = gpu::toneMappedRgb8(image, toneMap);
  std::size_t pixels = 0, clipped = 0;
  constexpr std::uint8_t kNearWhite = 250;  // 0.98 of 255, rounded up
  for (std::size_t i = 0; i < translucent.size() && 3 * i + 2 < rgb.size(); ++i) {
    if (!translucent[i]) continue;
    ++pixels;
    if (rgb[3 * i] >= kNearWhite && rgb[3 * i + 1] >= kNearWhite && rgb[3 * i + 2] >= kNearWhite) ++clipped;
  }
  return {{"translucent", pixels}, {"translucent_clipped", clipped}};
}

nlohmann::json changedParameters(const nlohmann::json& before, const nlohmann::json& after) {
  nlohmann::json out = nlohmann::json::object();
  for (auto it = after.begin(); it != after.end(); ++it)
    if (!before.contains(it.key()) || before.at(it.key()) != it.value()) out[it.key()] = it.value();
  return out;
}

namespace {

/// JSON numbers cannot be infinite or NaN: those become null.
nlohmann::json finiteOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

/// The image's fireflies at pixels where the reference has none, at most kListedFireflies of them, each
/// with how near the reference's own pixel came to the threshold: what tells a speckle of noise (the
/// reference near its median there) from a feature at the threshold that a small bias tips over.
constexpr std::size_t kListedFireflies = 32;
nlohmann::json firefliesNotInReference(const std::vector<gpu::Firefly>& ours, const std::vector<gpu::Firefly>& theirs,
                                       const gpu::Image& image, const gpu::Image& reference, const gpu::Image& mask) {
  nlohmann::json list = nlohmann::json::array();
  for (const gpu::Firefly& f : ours) {
    if (list.size() == kListedFireflies) break;
    const bool shared = std::any_of(theirs.begin(), theirs.end(), [&](const gpu::Firefly& r) { return r.x == f.x && r.y == f.y; });
    if (shared) continue;
    const float value = image.at(f.x, f.y)[f.channel], ref = reference.at(f.x, f.y)[f.channel];
    list.push_back({{"x", f.x}, {"y", f.y}, {"channel", f.channel}, {"over_median", finiteOrNull(f.overMedian)},
                    {"reference_over_median", finiteOrNull(gpu::fireflyRatio(reference, mask, f.x, f.y, f.channel))},
                    {"over_reference", finiteOrNull(ref > 0.0f ? value / ref : std::numeric_limits<double>::infinity())}});
  }
  return list;
}

}  // namespace

nlohmann::json referenceErrorRecord(const gpu::Image& image, const gpu::Image& reference, const gpu::Image& standardError) {
  const gpu::ImageError e = gpu::imageError(image, reference, standardError);
  const std::optional<gpu::HalvesError> halves = gpu::imageErrorByHalf(image, reference, standardError);
  const std::vector<gpu::Firefly> ours = gpu::fireflies(image, standardError);
  const std::vector<gpu::Firefly> theirs = gpu::fireflies(reference, standardError);
  return {{"rel_rmse", e.relRmse},
          {"mean_ratio", e.meanRatio},
          {"upper_mean_ratio", halves ? nlohmann::json(halves->upper.meanRatio) : nlohmann::json(nullptr)},
          {"lower_mean_ratio", halves ? nlohmann::json(halves->lower.meanRatio) : nlohmann::json(nullptr)},
          {"fireflies", ours.size()},
          {"reference_fireflies", theirs.size()},
          {"fireflies_not_in_reference", firefliesNotInReference(ours, theirs, image, reference, standardError)},
          {"pixels", e.pixels}};
}

nlohmann::json toJson(const RunRecord& run) {
  using nlohmann::json;
  json frames = json::array();
  std::vector<double> wall;
  std::map<std::string, std::vector<double>> perPass, perPassCpu, perPassThread;
  std::vector<double> gpuTotal, cpuTotal, threadTotal, changes;
  // A GPU time not read (NaN) is null, and left out of the medians.
  const auto number = &finiteOrNull;
  for (const FrameRecord& f : run.frames) {
    json passes = json::object(), cpu = json::object(), thread = json::object();
    for (const auto& p : f.gpu.passes) {
      passes[p.name] = number(p.gpuMs);
      cpu[p.name] = p.cpuMs;
      thread[p.name] = p.threadCpuMs;
      if (std::isfinite(p.gpuMs)) perPass[p.name].push_back(p.gpuMs);
      perPassCpu[p.name].push_back(p.cpuMs);
      perPassThread[p.name].push_back(p.threadCpuMs);
    }
    frames.push_back({{"index", f.index}, {"time_s", f.timeS}, {"wall_ms", f.wallMs},
                      {"gpu_ms", passes}, {"gpu_total_ms", number(f.gpu.gpuTotalMs)},
                      {"cpu_ms", cpu}, {"cpu_total_ms", f.gpu.cpuTotalMs},
                      {"thread_cpu_ms", thread}, {"thread_cpu_total_ms", f.gpu.threadCpuTotalMs},
                      {"receiver_change", number(f.receiverChange)},
                      {"translucent_change", number(f.translucentChange)},
                      {"reference_error", f.reference},
                      {"point_lights", [&] {
                         json lights = json::array();
                         for (const glm::vec3& p : f.pointLights) lights.push_back({p.x, p.y, p.z});
                         return lights;
                       }()},
                      {"changed", f.changed},
                      {"sss", f.sss},
                      {"rss_bytes", f.rssBytes},
                      {"pixels", f.pixels}});
    if (!f.view.is_null()) frames.back()["view"] = f.view;
    if (std::isfinite(f.receiverChange)) changes.push_back(f.receiverChange);
    wall.push_back(f.wallMs);
    if (f.gpu.gpuKnown()) gpuTotal.push_back(f.gpu.gpuTotalMs);
    cpuTotal.push_back(f.gpu.cpuTotalMs);
    threadTotal.push_back(f.gpu.threadCpuTotalMs);
  }
  json passMedians = json::object(), cpuMedians = json::object(), threadMedians = json::object();
  for (auto& [name, values] : perPass) passMedians[name] = median(values);
  for (auto& [name, values] : perPassCpu) cpuMedians[name] = median(values);
  for (auto& [name, values] : perPassThread) threadMedians[name] = median(values);
  json plan = json::array();
  for (const auto& p : run.plan)
    plan.push_back({{"name", p.name}, {"reason", p.reason}, {"reads", p.io.reads}, {"writes", p.io.writes}});
  const json gl = glJson(run.backend, run.gl);
  json provenance = provenanceJson();
  provenance["gl"] = gl;
  json state = {{"state", run.state}, {"frames_requested", run.framesRequested}, {"frames_written", run.frames.size()}};
  if (!run.stopReason.empty()) state["stop_reason"] = run.stopReason;
  return {
      {"command", run.command},
      {"run", state},
      {"provenance", provenance},
      {"preset", {{"name", run.presetName}, {"path", run.presetPath}}},
      {"gl", gl},
      {"resolution", {run.width, run.height}},
      {"accumulate", run.accumulate},
      {"triangles", run.triangles},
      {"gpu_memory_bytes", run.gpuBytes},
      {"plan", plan},
      {"frames", frames},
      {"summary",
       {{"frames", run.frames.size()},
        {"wall_ms_median", median(wall)},
        {"gpu_total_ms_median", gpuTotal.empty() ? json(nullptr) : json(median(gpuTotal))},
        {"gpu_ms_median", passMedians},
        {"cpu_total_ms_median", median(cpuTotal)},
        {"cpu_ms_median", cpuMedians},
        {"thread_cpu_total_ms_median", median(threadTotal)},
        {"thread_cpu_ms_median", threadMedians},
        {"receiver_change_mean",
         changes.empty() ? json(nullptr) : json(std::accumulate(changes.begin(), changes.end(), 0.0) / double(changes.size()))}}},
      {"parameters", run.parameters},
      {"sss", run.sss},
  };
}

}  // namespace tallow::app
