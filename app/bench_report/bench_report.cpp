#include "app/bench_report/bench_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tallow::bench_report {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

/// FP32 lanes per SM of Hopper (GH100); an FMA counts as two FLOPs in vendor peaks and here alike
/// (counted_real.h counts its multiply and its add).
constexpr double kHopperFp32LanesPerSm = 128.0;
constexpr double kFlopsPerFma = 2.0;

/// SMs of the Hopper parts, by a piece of their nvidia-smi name, most specific first (NVIDIA H100
/// architecture whitepaper: 132 SMs on SXM5 and on H100 NVL, 114 on PCIe; H200 and GH200 carry the
/// SXM5 configuration).
struct HopperPart {
  const char* namePiece;
  int sms;
};
constexpr HopperPart kHopperParts[] = {{"H100 PCIe", 114}, {"H800 PCIe", 114}, {"H100", 132},
                                       {"H200", 132},      {"GH200", 132},     {"H800", 132}};

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

json numberOrNull(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

std::vector<std::string> splitTabs(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream s(line);
  while (std::getline(s, cell, '\t')) cells.push_back(cell);
  if (!line.empty() && line.back() == '\t') cells.emplace_back();
  return cells;
}

std::vector<std::vector<std::string>> readTsv(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot be read (is this a bench's runs/ folder?)");
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) rows.push_back(splitTabs(line));
  return rows;
}

json readJson(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.filename().string() + " missing");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    throw std::runtime_error(file.filename().string() + " is not valid JSON: " + e.what());
  }
}

/// Which work a captured frame did, from the passes it timed: the field extracted (the animated
/// candle and blob), the maps accumulating, or neither (converged: only the camera's passes).
std::string frameClass(const json& frame) {
  const json& gpu = frame.value("gpu_ms", json::object());
  if (gpu.contains("field.extract")) return "animated";
  if (gpu.contains("sss.maps")) return "accumulating";
  return "converged";
}

/// Medians over frames of one per-pass object (gpu_ms or cpu_ms), pass by pass.
json passMedians(const std::vector<const json*>& frames, const char* key) {
  std::map<std::string, std::vector<double>> perPass;
  bool any = false;
  for (const json* f : frames) {
    if (!f->contains(key) || !(*f)[key].is_object()) continue;
    any = true;
    for (const auto& [pass, ms] : (*f)[key].items())
      if (ms.is_number()) perPass[pass].push_back(ms.get<double>());
  }
  if (!any) return nullptr;  // this build records no such object (cpu_ms before issue 16)
  json out = json::object();
  for (auto& [pass, values] : perPass) out[pass] = median(values);
  return out;
}

json frameGroup(const std::vector<const json*>& frames) {
  std::vector<double> wall, gpuTotal;
  for (const json* f : frames) {
    wall.push_back(f->value("wall_ms", std::nan("")));
    gpuTotal.push_back(f->value("gpu_total_ms", std::nan("")));
  }
  const double w = median(wall);
  return {{"frames", frames.size()},
          {"wall_ms", numberOrNull(w)},
          {"fps", numberOrNull(w > 0.0 ? 1000.0 / w : std::nan(""))},
          {"gpu_total_ms", numberOrNull(median(gpuTotal))},
          {"gpu_ms", passMedians(frames, "gpu_ms")},
          {"cpu_ms", passMedians(frames, "cpu_ms")}};
}

/// A `tallow capture` row: every frame after the first (which compiles shaders and allocates), by
/// class and all together.
json captureMetrics(const json& stats) {
  const json& frames = stats.at("frames");
  std::vector<const json*> timed;
  for (std::size_t i = frames.size() > 1 ? 1 : 0; i < frames.size(); ++i) timed.push_back(&frames[i]);
  std::map<std::string, std::vector<const json*>> byClass;
  for (const json* f : timed) byClass[frameClass(*f)].push_back(f);
  json classes = json::object();
  for (const auto& [name, group] : byClass) classes[name] = frameGroup(group);
  const json& p = stats.value("parameters", json::object());
  json params = json::object();
  for (const char* key : {"method", "sss.maps", "sss.samples", "sss.map_size", "sss.light_map_size", "sss.frames",
                          "sss.gather", "vpl.count", "field.res", "field.extraction", "camera.fov_deg", "material"})
    if (p.contains(key)) params[key] = p[key];
  const json& res = stats.at("resolution");
  json out = {{"resolution", res},
              {"frames_captured", frames.size()},
              {"triangles", stats.value("triangles", json(0))},  // json defaults: byte counts pass 2³¹
              {"gpu_memory_bytes", stats.value("gpu_memory_bytes", json(0))},
              {"parameters", params},
              {"all", frameGroup(timed)},
              {"classes", classes}};
  if (stats.contains("sss") && stats["sss"].is_object() && stats["sss"].contains("translucent_pixels")) {
    const double pixels = res.at(0).get<double>() * res.at(1).get<double>();
    out["translucent_pixels"] = stats["sss"]["translucent_pixels"];
    out["occupancy"] = stats["sss"]["translucent_pixels"].get<double>() / pixels;
  }
  return out;
}

/// A `tallow probe maps` row (one K, N): the maps pass and its evaluations per second.
json mapsMetrics(const json& maps) {
  const json& r = maps.at("rows").at(0);
  return {{"k", r.at("k")},
          {"n", r.at("n")},
          {"map_size", r.at("map_size")},
          {"maps_ms", r.at("maps_ms")},
          {"frame_wall_ms", r.value("frame_wall_ms", json(nullptr))},
          {"shaded_texels", r.at("shaded_texels")},
          {"evaluations_per_s", r.at("evaluations_per_s")},
          {"map_bytes", r.value("map_bytes", json(nullptr))},
          {"gather", maps.at("settings").value("gather", json(nullptr))}};
}

std::string glString(const json& stats, const char* key) {
  if (stats.contains("gl") && stats["gl"].contains(key)) return stats["gl"][key].get<std::string>();
  if (stats.contains("gpu") && stats["gpu"].contains(key)) return stats["gpu"][key].get<std::string>();
  return "";
}

/// Least-squares line y = a + b x.
std::pair<double, double> fitLine(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i] / n, my += y[i] / n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
  const double b = sxx > 0 ? sxy / sxx : 0.0;
  return {my - b * mx, b};
}

const json* findRow(const json& rows, const std::string& name) {
  for (const json& r : rows)
    if (r["name"] == name && r["status"] == "ok" && r.contains("metrics")) return &r;
  return nullptr;
}

json classFps(const json* row, const char* cls) {
  if (!row) return nullptr;
  const json& c = (*row)["metrics"]["classes"];
  return c.contains(cls) ? c[cls]["fps"] : json(nullptr);
}

json figures(const json& rows, const json& device, const flops::GatherFlops& flops) {
  json f = json::object();
  const json* animated = findRow(rows, "candle_animated");
  const json* converged = findRow(rows, "candle_converged");
  f["candle"] = {{"animated_fps", classFps(animated, "animated")},
                 {"accumulating_fps", classFps(converged, "accumulating")},
                 {"converged_fps", classFps(converged, "converged")},
                 {"paper_fps", 6.0},
                 {"paper_device", "NVIDIA GeForce GTX 780 Ti"}};
  if (animated) {
    f["candle"]["settings"] = (*animated)["metrics"]["parameters"];
    f["candle"]["resolution"] = (*animated)["metrics"]["resolution"];
  }

  const json peak = device.value("fp32_peak_tflops", json(nullptr));
  json gathers = json::object();
  for (const char* name : {"fragment", "compute"}) {
    const json* r = findRow(rows, std::string("gather_") + name);
    if (!r) continue;
    const json& m = (*r)["metrics"];
    const double evals = m["evaluations_per_s"].get<double>();
    const double rate = evals * flops.directional.flopsMean;
    gathers[name] = {{"maps_ms", m["maps_ms"]},
                     {"evaluations_per_s", evals},
                     {"flops_per_s", rate},
                     {"share_of_fp32_peak", peak.is_number() ? json(rate * 1e-12 / peak.get<double>()) : json(nullptr)}};
  }
  if (gathers.contains("fragment") && gathers.contains("compute"))
    gathers["fragment_over_compute_time"] =
        gathers["fragment"]["maps_ms"].get<double>() / gathers["compute"]["maps_ms"].get<double>();
  const flops::LoopFlops& d = flops.directional;
  f["gather"] = {{"flops_per_sample", d.flopsMean},
                 {"flops_per_sample_point_light", flops.point.flopsMean},
                 {"flops_counted", {{"add", d.addMean}, {"mul", d.mulMean}, {"div", d.divMean},
                                    {"special", d.specialMean}, {"other_not_flops", d.otherMean}}},
                 {"fp32_peak_tflops", peak},
                 {"runs", gathers}};

  json dc = json::array();
  for (const json& r : rows) {
    const std::string name = r["name"];
    if (name.rfind("dc_", 0) != 0 || r["status"] != "ok" || !r.contains("metrics")) continue;
    const json& m = r["metrics"];
    const int res = m["parameters"].value("field.res", 0);
    const json& cls = m["classes"];
    if (!cls.contains("animated") || !cls["animated"]["gpu_ms"].is_object() ||
        !cls["animated"]["gpu_ms"].contains("field.extract"))
      continue;
    const double ms = cls["animated"]["gpu_ms"]["field.extract"].get<double>();
    const double cells = std::pow(double(res - 1), 3.0);
    const double triangles = m["triangles"].get<double>();
    dc.push_back({{"res", res},
                  {"extraction", m["parameters"].value("field.extraction", std::string("geometry"))},
                  {"extract_gpu_ms", ms},
                  {"cells", cells},
                  {"cells_per_s", ms > 0 ? json(cells / (ms * 1e-3)) : json(nullptr)},
                  {"triangles", triangles},
                  {"triangles_per_s", ms > 0 ? json(triangles / (ms * 1e-3)) : json(nullptr)},
                  {"frame_fps", cls["animated"]["fps"]},
                  {"cpu_ms", cls["animated"]["cpu_ms"]}});
  }
  f["dual_contouring"] = dc;

  json occ = json::object();
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> points;
  for (const json& r : rows) {
    const std::string name = r["name"];
    if (name.rfind("occupancy_", 0) != 0 || r["status"] != "ok" || !r.contains("metrics")) continue;
    const json& m = r["metrics"];
    if (!m.contains("occupancy")) continue;
    const std::string method = m["parameters"].value("method", "?");
    const double wall = m["all"]["wall_ms"].is_number() ? m["all"]["wall_ms"].get<double>() : std::nan("");
    occ[method].push_back({{"fov_deg", m["parameters"].value("camera.fov_deg", 0.0)},
                           {"occupancy", m["occupancy"]},
                           {"wall_ms", numberOrNull(wall)},
                           {"gpu_total_ms", m["all"]["gpu_total_ms"]}});
    if (std::isfinite(wall)) {
      points[method].first.push_back(m["occupancy"].get<double>());
      points[method].second.push_back(wall);
    }
  }
  json fits = json::object();
  for (auto& [method, xy] : points)
    if (xy.first.size() >= 2) {
      const auto [a, b] = fitLine(xy.first, xy.second);
      fits[method] = {{"intercept_ms", a}, {"ms_per_occupancy", b}};
    }
  json crossover = nullptr;
  if (fits.contains("radiosity-maps") && fits.contains("no-cache")) {
    const double a1 = fits["radiosity-maps"]["intercept_ms"], b1 = fits["radiosity-maps"]["ms_per_occupancy"];
    const double a2 = fits["no-cache"]["intercept_ms"], b2 = fits["no-cache"]["ms_per_occupancy"];
    if (b2 != b1) crossover = (a1 - a2) / (b2 - b1);
  }
  f["occupancy"] = {{"runs", occ}, {"fits", fits}, {"crossover", crossover}, {"paper_crossover", 0.058}};
  return f;
}

}  // namespace

std::optional<double> hopperFp32PeakTflops(const std::string& name, double maxSmClockMhz) {
  if (!(maxSmClockMhz > 0.0)) return std::nullopt;
  for (const HopperPart& part : kHopperParts)
    if (name.find(part.namePiece) != std::string::npos)
      return part.sms * kHopperFp32LanesPerSm * kFlopsPerFma * maxSmClockMhz * 1e6 * 1e-12;
  return std::nullopt;
}

json buildReport(const fs::path& runs, const flops::GatherFlops& flops, const json& bundle) {
  json meta = json::object();
  for (const auto& cells : readTsv(runs / "meta.tsv")) {
    if (cells.size() != 2) throw std::runtime_error((runs / "meta.tsv").string() + ": a line without exactly one tab");
    meta[cells[0]] = cells[1];
  }
  const auto table = readTsv(runs / "rows.tsv");
  if (table.empty() || table[0].size() != 6 || table[0][0] != "name")
    throw std::runtime_error((runs / "rows.tsv").string() + ": no header line name, kind, status, exit, seconds, command");

  json rows = json::array();
  json device = {{"GL_VENDOR", nullptr}, {"GL_RENDERER", nullptr}, {"GL_VERSION", nullptr}, {"backend", nullptr}};
  for (std::size_t i = 1; i < table.size(); ++i) {
    const auto& c = table[i];
    if (c.size() != 6) throw std::runtime_error((runs / "rows.tsv").string() + ":" + std::to_string(i + 1) + ": not 6 columns");
    json row = {{"name", c[0]}, {"kind", c[1]}, {"status", c[2]}, {"exit", c[3].empty() ? json(nullptr) : json(std::stoi(c[3]))},
                {"seconds", std::stod(c[4])}, {"command", c[5]}};
    if (c[2] != "skipped") {
      // The row's last log line says why it failed; its OpenGL errors (TALLOW_GL_ERRORS, printed
      // as "gl error ID: message") are counted whether it failed or not.
      std::ifstream log(runs / (c[0] + ".log"));
      std::string line, last, firstGlError;
      int glErrors = 0;
      while (std::getline(log, line)) {
        if (line.empty()) continue;
        last = line;
        if (line.rfind("gl error", 0) == 0 && glErrors++ == 0) firstGlError = line;
      }
      row["gl_errors"] = glErrors;
      if (glErrors > 0) row["first_gl_error"] = firstGlError;
      if (c[2] != "ok") row["error"] = last;
    }
    if (c[2] == "ok") {
      try {
        const json out = readJson(runs / c[0] / (c[1] == "maps" ? "maps.json" : "stats.json"));
        row["metrics"] = c[1] == "maps" ? mapsMetrics(out) : captureMetrics(out);
        if (device["GL_RENDERER"].is_null()) {
          device["GL_VENDOR"] = glString(out, "GL_VENDOR");
          device["GL_RENDERER"] = glString(out, "GL_RENDERER");
          device["GL_VERSION"] = glString(out, "GL_VERSION");
          device["backend"] = glString(out, "backend");
          // The limits that decide a pass's path on this driver (stats.json's gl.limits: the
          // geometry shader's output, transform feedback, the layer in the vertex shader).
          if (out.contains("gl") && out["gl"].contains("limits")) device["gl_limits"] = out["gl"]["limits"];
        }
      } catch (const std::exception& e) {
        row["status"] = "failed";
        row["error"] = std::string("its output could not be read: ") + e.what();
      }
    }
    rows.push_back(row);
  }
  const std::string renderer = device["GL_RENDERER"].is_string() ? device["GL_RENDERER"].get<std::string>() : "";
  device["software"] = renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos ||
                       renderer.find("swrast") != std::string::npos;
  for (const char* key : {"nvidia_smi_name", "nvidia_smi_driver", "nvidia_smi_memory_mib", "nvidia_smi_max_sm_clock_mhz"})
    device[key] = meta.value(key, json(nullptr));
  device["fp32_peak_tflops"] = nullptr;
  device["fp32_peak_source"] = "unknown: pass --fp32-peak TFLOPS to bench.sh";
  if (meta.contains("fp32_peak_tflops")) {
    device["fp32_peak_tflops"] = std::stod(meta["fp32_peak_tflops"].get<std::string>());
    device["fp32_peak_source"] = "given with --fp32-peak";
  } else if (meta.contains("nvidia_smi_name") && meta.contains("nvidia_smi_max_sm_clock_mhz")) {
    double clock = 0.0;
    try {
      clock = std::stod(meta["nvidia_smi_max_sm_clock_mhz"].get<std::string>());
    } catch (const std::exception&) {
    }
    if (auto peak = hopperFp32PeakTflops(meta["nvidia_smi_name"], clock)) {
      device["fp32_peak_tflops"] = *peak;
      device["fp32_peak_source"] = "SMs of " + meta["nvidia_smi_name"].get<std::string>() +
                                   " x 128 FP32 lanes x 2 (FMA) x its maximum SM clock (nvidia-smi)";
    }
  }

  const auto loop = [](const flops::LoopFlops& l) {
    return json{{"samples", l.samples},
                {"flops_mean", l.flopsMean},
                {"flops_per_shared_sample", l.flopsPerSharedSample},
                {"flops_shared_min", l.flopsSharedMin},
                {"flops_shared_max", l.flopsSharedMax},
                {"flops_per_texel", l.flopsPerTexel},
                {"add", l.addMean},
                {"mul", l.mulMean},
                {"div", l.divMean},
                {"special", l.specialMean},
                {"other_not_flops", l.otherMean}};
  };
  json counted = loop(flops.directional);
  counted["point_light"] = loop(flops.point);
  counted["max_difference_to_float"] = flops.maxValueDifference;
  std::size_t ok = 0, failed = 0, skipped = 0, glErrors = 0;
  for (const json& r : rows) {
    (r["status"] == "ok" ? ok : r["status"] == "skipped" ? skipped : failed)++;
    glErrors += r.value("gl_errors", 0);
  }
  return {{"generated_by", "tallow_bench_report (scripts/device_bench.sh)"},
          {"meta", meta},
          {"bundle", bundle},
          {"device", device},
          {"rows_ok", ok},
          {"rows_failed", failed},
          {"rows_skipped", skipped},
          {"gl_errors", glErrors},
          {"gather_flops", counted},
          {"figures", figures(rows, device, flops)},
          {"rows", rows}};
}

}  // namespace tallow::bench_report
