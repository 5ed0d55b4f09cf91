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
  const sss::RadiosityMaps* maps = renderer.module<sss::RadiosityMaps>();
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
/// Whether the reference has a firefly at f's pixel too.
bool sharedFirefly(const gpu::Firefly& f, const std::vector<gpu::Firefly>& theirs) {
  return std::any_of(theirs.begin(), theirs.end(), [&](const gpu::Firefly& r) { return r.x == f.x && r.y == f.y; });
}

/// The image's fireflies at pixels where the reference has none (all of them; the list is capped).
std::size_t newFireflyCount(const std::vector<gpu::Firefly>& ours, const std::vector<gpu::Firefly>& theirs) {
  return static_cast<std::size_t>(
      std::count_if(ours.begin(), ours.end(), [&](const gpu::Firefly& f) { return !sharedFirefly(f, theirs); }));
}

nlohmann::json firefliesNotInReference(const std::vector<gpu::Firefly>& ours, const std::vector<gpu::Firefly>& theirs,
                                       const gpu::Image& image, const gpu::Image& reference, const gpu::Image& mask) {
  nlohmann::json list = nlohmann::json::array();
  for (const gpu::Firefly& f : ours) {
    if (list.size() == kListedFireflies) break;
    if (sharedFirefly(f, theirs)) continue;
    const float value = image.at(f.x, f.y)[f.channel], ref = reference.at(f.x, f.y)[f.channel];
    list.push_back({{"x", f.x}, {"y", f.y}, {"channel", f.channel}, {"over_median", finiteOrNull(f.overMedian)},
                    {"reference_over_median", finiteOrNull(gpu::fireflyRatio(reference, mask, f.x, f.y, f.channel))},
                    {"over_reference", finiteOrNull(ref > 0.0f ? value / ref : std::numeric_limits<double>::infinity())}});
  }
  return list;
}

}  // namespace

nlohmann::json referenceErrorRecord(const gpu::Image& image, const gpu::Image& reference, const gpu::Image& standardError,
                                    const gpu::ImageErrorOptions& options) {
  const gpu::ImageError e = gpu::imageError(image, reference, standardError, options);
  const std::optional<gpu::HalvesError> halves = gpu::imageErrorByHalf(image, reference, standardError, options);
  const std::vector<gpu::Firefly> ours = gpu::fireflies(image, standardError);
  const std::vector<gpu::Firefly> theirs = gpu::fireflies(reference, standardError);
  return {{"rel_rmse", finiteOrNull(e.relRmse)},
          {"mean_ratio", finiteOrNull(e.meanRatio)},
          {"upper_mean_ratio", halves ? finiteOrNull(halves->upper.meanRatio) : nlohmann::json(nullptr)},
          {"lower_mean_ratio", halves ? finiteOrNull(halves->lower.meanRatio) : nlohmann::json(nullptr)},
          {"non_finite", {{"image", e.nonFiniteImage}, {"reference", e.nonFiniteReference}, {"left_out", e.skippedNonFinite}}},
          {"fireflies", ours.size()},
          {"reference_fireflies", theirs.size()},
          {"new_fireflies", newFireflyCount(ours, theirs)},
          {"fireflies_not_in_reference", firefliesNotInReference(ours, theirs, image, reference, standardError)},
          {"pixels", e.pixels}};
}

nlohmann::json frameJson(const FrameRecord& f) {
  using nlohmann::json;
  json passes = json::object(), cpu = json::object(), thread = json::object(), invocations = json::object();
  for (const auto& p : f.gpu.passes) {
    passes[p.name] = finiteOrNull(p.gpuMs);  // a GPU time not read (NaN) is null
    cpu[p.name] = p.cpuMs;
    thread[p.name] = p.threadCpuMs;
    if (p.counts)  // GL_ARB_pipeline_statistics_query; a pass that ran twice in a frame: the last
      invocations[p.name] = {{"vertex", p.counts->vertex}, {"geometry", p.counts->geometry},
                             {"primitives", p.counts->primitives}, {"fragment", p.counts->fragment},
                             {"compute", p.counts->compute}};
  }
  json lights = json::array(), intensities = json::array();
  for (const glm::vec3& p : f.pointLights) lights.push_back({p.x, p.y, p.z});
  for (const glm::vec3& i : f.pointLightIntensities) intensities.push_back({i.x, i.y, i.z});
  json frame = {{"index", f.index}, {"time_s", f.timeS}, {"wall_ms", f.wallMs},
                {"gpu_ms", passes}, {"gpu_total_ms", finiteOrNull(f.gpu.gpuTotalMs)},
                {"cpu_ms", cpu}, {"cpu_total_ms", f.gpu.cpuTotalMs},
                {"thread_cpu_ms", thread}, {"thread_cpu_total_ms", f.gpu.threadCpuTotalMs},
                {"invocations", invocations},
                {"target_reads", f.targetReads >= 0 ? nlohmann::json(f.targetReads) : nlohmann::json(nullptr)},
                {"receiver_change", finiteOrNull(f.receiverChange)},
                {"translucent_change", finiteOrNull(f.translucentChange)},
                {"reference_error", f.reference},
                {"point_lights", lights},
                {"point_light_intensities", intensities},
                {"changed", f.changed},
                {"sss", f.sss},
                {"rss_bytes", f.rssBytes},
                {"pixels", f.pixels}};
  if (!f.view.is_null()) frame["view"] = f.view;
  return frame;
}

namespace {
/// The medians of a map of named series.
nlohmann::json medians(std::map<std::string, std::vector<double>>& series) {
  nlohmann::json out = nlohmann::json::object();
  for (auto& [name, values] : series) out[name] = median(std::move(values));
  return out;
}
}  // namespace

nlohmann::json FrameSummary::invocationMedians() {
  nlohmann::json out = nlohmann::json::object();
  for (auto& [pass, counters] : invocations_) out[pass] = medians(counters);
  return out;
}

void FrameSummary::add(const nlohmann::json& frame) {
  ++frames_;
  const auto number = [](const nlohmann::json& v, std::vector<double>& into) {
    if (v.is_number()) into.push_back(v.get<double>());  // null (not read, or not finite) is left out
  };
  number(frame.value("wall_ms", nlohmann::json()), wall_);
  number(frame.value("gpu_total_ms", nlohmann::json()), gpuTotal_);
  number(frame.value("cpu_total_ms", nlohmann::json()), cpuTotal_);
  number(frame.value("thread_cpu_total_ms", nlohmann::json()), threadTotal_);
  number(frame.value("receiver_change", nlohmann::json()), changes_);
  const auto perPass = [&](const char* key, std::map<std::string, std::vector<double>>& into) {
    if (const auto it = frame.find(key); it != frame.end() && it->is_object())
      for (const auto& [name, value] : it->items()) number(value, into[name]);
  };
  perPass("gpu_ms", perPass_);
  perPass("cpu_ms", perPassCpu_);
  perPass("thread_cpu_ms", perPassThread_);
  if (const auto it = frame.find("invocations"); it != frame.end() && it->is_object())
    for (const auto& [pass, counters] : it->items())
      for (const auto& [counter, value] : counters.items()) number(value, invocations_[pass][counter]);
}

nlohmann::json FrameSummary::json() {
  using nlohmann::json;
  return {{"frames", frames_},
          {"wall_ms_median", median(wall_)},
          {"gpu_total_ms_median", gpuTotal_.empty() ? json(nullptr) : json(median(gpuTotal_))},
          {"gpu_ms_median", medians(perPass_)},
          {"cpu_total_ms_median", median(cpuTotal_)},
          {"cpu_ms_median", medians(perPassCpu_)},
          {"thread_cpu_total_ms_median", median(threadTotal_)},
          {"thread_cpu_ms_median", medians(perPassThread_)},
          {"invocations_median", invocationMedians()},
          {"receiver_change_mean",
           changes_.empty() ? json(nullptr)
                            : json(std::accumulate(changes_.begin(), changes_.end(), 0.0) / double(changes_.size()))}};
}

nlohmann::json runJson(const RunRecord& run) {
  using nlohmann::json;
  json plan = json::array();
  for (const auto& p : run.plan)
    plan.push_back({{"name", p.name}, {"reason", p.reason}, {"reads", p.io.reads}, {"writes", p.io.writes}});
  json gl = glJson(run.backend, run.gl);
  if (!run.glLimits.is_null()) gl["limits"] = run.glLimits;
  json provenance = provenanceJson();
  provenance["gl"] = gl;
  json state = {{"state", run.state}, {"frames_requested", run.framesRequested}, {"frames_written", run.framesWritten}};
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
      {"parameters", run.parameters},
      {"sss", run.sss},
  };
}

}  // namespace tallow::app
