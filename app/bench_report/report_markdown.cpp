// results.md of the device bench, from the JSON of buildReport (bench_report.cpp): every number
// in it is read from that JSON, which the runs wrote.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "app/bench_report/bench_report.h"

namespace tallow::bench_report {
namespace {

using nlohmann::json;

std::string fmt(const json& v, int digits = 2) {
  if (!v.is_number()) return "—";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v.get<double>());
  return buf;
}

/// 1.23 G, 45.6 M, 789 k: rates that span many orders of magnitude.
std::string si(const json& v) {
  if (!v.is_number()) return "—";
  const double x = v.get<double>();
  const char* units[] = {"", " k", " M", " G", " T"};
  int u = 0;
  double y = x;
  while (std::abs(y) >= 1000.0 && u < 4) y /= 1000.0, ++u;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g%s", y, units[u]);
  return buf;
}

std::string pct(const json& v) {
  if (!v.is_number()) return "—";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * v.get<double>());
  return buf;
}

std::string str(const json& v) { return v.is_string() ? v.get<std::string>() : v.is_null() ? "—" : v.dump(); }

std::string mib(const json& v) {
  if (!v.is_number()) return "—";
  return fmt(v.get<double>() / (1024.0 * 1024.0), 1);
}

/// "pass a / b" cells for one frame class: GPU ms and, where the build records it, CPU ms.
void passTable(std::ostringstream& md, const json& cls) {
  const json& gpu = cls["gpu_ms"];
  const json& cpu = cls["cpu_ms"];
  md << "| pass | GPU [ms] | CPU [ms] |\n|---|---:|---:|\n";
  json names = json::object();
  if (gpu.is_object())
    for (const auto& [k, v] : gpu.items()) names[k] = true;
  if (cpu.is_object())
    for (const auto& [k, v] : cpu.items()) names[k] = true;
  for (const auto& [k, v] : names.items())
    md << "| " << k << " | " << fmt(gpu.is_object() ? gpu.value(k, json(nullptr)) : json(nullptr), 3) << " | "
       << (cpu.is_object() ? fmt(cpu.value(k, json(nullptr)), 3) : std::string("not recorded")) << " |\n";
  md << "\n";
}

}  // namespace

std::string renderMarkdown(const json& r) {
  std::ostringstream md;
  const json& meta = r["meta"];
  const json& dev = r["device"];
  const json& fig = r["figures"];
  md << "# Tallow device bench\n\n";
  md << "Written by `tallow_bench_report` from the runs of `bench.sh` (docs/device-bench.md); every number "
        "comes from those runs.\n\n";
  md << "- Device: `" << str(dev["GL_RENDERER"]) << "`, " << str(dev["GL_VENDOR"]) << ", OpenGL " << str(dev["GL_VERSION"])
     << ", context `" << str(dev["backend"]) << "`\n";
  if (dev.contains("gl_limits") && dev["gl_limits"].is_object()) {
    md << "- GL limits:";
    for (const auto& [key, value] : dev["gl_limits"].items()) md << " `" << key << "` " << value.dump() << ";";
    md << "\n";
  }
  if (dev["nvidia_smi_name"].is_string())
    md << "- nvidia-smi: " << str(dev["nvidia_smi_name"]) << ", driver " << str(dev["nvidia_smi_driver"]) << ", "
       << str(dev["nvidia_smi_memory_mib"]) << " MiB, maximum SM clock " << str(dev["nvidia_smi_max_sm_clock_mhz"])
       << " MHz\n";
  md << "- FP32 peak: " << (dev["fp32_peak_tflops"].is_number() ? fmt(dev["fp32_peak_tflops"], 1) + " TFLOP/s" : "—")
     << " (" << str(dev["fp32_peak_source"]) << ")\n";
  md << "- CPU: " << str(meta.value("cpu", json(nullptr))) << ", " << str(meta.value("cpu_threads", json(nullptr)))
     << " threads; " << str(meta.value("host", json(nullptr))) << ", " << str(meta.value("glibc", json(nullptr))) << "\n";
  md << "- Mode `" << str(meta.value("mode", json(nullptr))) << "`, started " << str(meta.value("started_utc", json(nullptr)))
     << ", " << str(meta.value("finished_s", json(nullptr))) << " s of rows in a budget of "
     << str(meta.value("budget_s", json(nullptr))) << " s\n";
  if (r["bundle"].is_object())
    md << "- Bundle: Tallow " << str(r["bundle"].value("commit", json(nullptr))) << ", built "
       << str(r["bundle"].value("built_utc", json(nullptr))) << "\n";
  md << "- Rows: " << r["rows_ok"].get<int>() << " ok, " << r["rows_failed"].get<int>() << " failed, "
     << r["rows_skipped"].get<int>() << " skipped; " << r["gl_errors"].get<int>() << " OpenGL error(s)\n\n";
  if (dev["software"].get<bool>())
    md << "**A software renderer (" << str(dev["GL_RENDERER"]) << ") ran these rows: its times say nothing about a "
          "GPU.** This run only shows that the bench and its report work.\n\n";

  // --- The figures --------------------------------------------------------------------------------
  md << "## Figures\n\n";
  const json& candle = fig["candle"];
  const json size = candle.value("resolution", json(nullptr));
  md << "- Candle at " << (size.is_array() ? std::to_string(size[0].get<int>()) + "x" + std::to_string(size[1].get<int>()) : "—")
     << ", K = " << str(candle.value("settings", json::object()).value("sss.maps", json(nullptr)))
     << ", N = " << str(candle.value("settings", json::object()).value("sss.samples", json(nullptr))) << ", "
     << str(candle.value("settings", json::object()).value("vpl.count", json(nullptr)))
     << " VPLs (the paper's Fig. 1: K = 28, N = 45, 80 VPLs): **" << fmt(candle["animated_fps"])
     << " fps animated** (every frame: field, maps, VPLs), "
     << fmt(candle["accumulating_fps"]) << " fps while the paused maps accumulate, **" << fmt(candle["converged_fps"])
     << " fps converged**; the paper: " << fmt(candle["paper_fps"], 0) << " fps on an " << str(candle["paper_device"]) << ".\n";
  const json& g = fig["gather"];
  md << "- Gather: " << fmt(g["flops_per_sample"], 0)
     << " FLOPs per sample and band, counted by running the shader's shared lines (directional dipole, "
     << str(r["gather_flops"].value("material", json(nullptr))) << "; see below).";
  for (const char* name : {"compute", "fragment"})
    if (g["runs"].contains(name)) {
      const json& run = g["runs"][name];
      md << " " << name << ": " << si(run["evaluations_per_s"]) << " samples/s × FLOPs = **" << si(run["flops_per_s"])
         << "FLOP/s**, " << pct(run["share_of_fp32_peak"]) << " of the FP32 peak;";
    }
  if (g["runs"].contains("fragment_over_compute_time"))
    md << " fragment / compute time " << fmt(g["runs"]["fragment_over_compute_time"]) << ".";
  md << "\n";
  md << "- Dual contouring (melting candle, GPU time of `field.extract`):";
  for (const json& d : fig["dual_contouring"])
    md << " " << d["res"].get<int>() << "³ " << d.value("extraction", std::string("geometry")) << ": **"
       << si(d["cells_per_s"]) << " cells/s**;";
  if (fig["dual_contouring"].empty()) md << " —";
  md << "\n";
  const json& occ = fig["occupancy"];
  md << "- Cached against no-cache (chocolate-milk blob, animated): equal cost at **" << pct(occ["crossover"])
     << "** screen occupancy (least-squares lines of wall time; the paper: " << pct(occ["paper_crossover"])
     << " at 1024², GTX 780 Ti).\n\n";

  // --- Rows -----------------------------------------------------------------------------------------
  md << "## Rows\n\n";
  md << "Times are medians over the frames after the first (which compiles shaders and allocates). `fps` is "
        "1000 / median wall time; GPU is the sum of the passes' GL timer queries.\n\n";
  md << "| row | status | s | size | frames | fps | wall [ms] | GPU [ms] | GPU memory [MiB] | triangles |\n";
  md << "|---|---|---:|---|---:|---:|---:|---:|---:|---:|\n";
  for (const json& row : r["rows"]) {
    md << "| " << str(row["name"]) << " | " << str(row["status"]) << " | " << fmt(row["seconds"], 0) << " | ";
    if (!row.contains("metrics")) {
      md << "— | — | — | — | — | — | — |\n";
      continue;
    }
    const json& m = row["metrics"];
    if (row["kind"] == "maps") {
      md << m["map_size"].get<int>() << "² maps, K " << m["k"].get<int>() << ", N " << m["n"].get<int>() << " | — | — | "
         << fmt(m["frame_wall_ms"]) << " | " << fmt(m["maps_ms"]) << " (maps) | " << mib(m["map_bytes"]) << " | — |\n";
      continue;
    }
    md << m["resolution"][0].get<int>() << "x" << m["resolution"][1].get<int>() << " | " << m["frames_captured"].get<int>()
       << " | " << fmt(m["all"]["fps"]) << " | " << fmt(m["all"]["wall_ms"]) << " | " << fmt(m["all"]["gpu_total_ms"])
       << " | " << mib(m["gpu_memory_bytes"]) << " | " << m["triangles"].get<long long>() << " |\n";
  }
  md << "\n";
  bool anyProblem = false;
  for (const json& row : r["rows"])
    if (row["status"] != "ok") {
      if (!anyProblem) md << "Rows that did not finish:\n\n";
      anyProblem = true;
      md << "- `" << str(row["name"]) << "` " << str(row["status"]) << ": "
         << (row.contains("error") ? str(row["error"]) : std::string("not started, the time budget was spent")) << "\n";
    }
  if (anyProblem) md << "\n";
  for (const json& row : r["rows"])
    if (row.value("gl_errors", 0) > 0)
      md << "- `" << str(row["name"]) << "`: " << row["gl_errors"].get<int>() << " OpenGL error(s), the first: `"
         << str(row["first_gl_error"]) << "`\n";
  if (r["gl_errors"].get<int>() > 0) md << "\n";

  // --- Per-pass times of the candle ---------------------------------------------------------------
  for (const char* name : {"candle_animated", "candle_converged"})
    for (const json& row : r["rows"]) {
      if (row["name"] != name || !row.contains("metrics")) continue;
      for (const auto& [cls, group] : row["metrics"]["classes"].items()) {
        md << "### `" << name << "`, " << cls << " frames (" << group["frames"].get<int>() << ", " << fmt(group["fps"])
           << " fps)\n\n";
        passTable(md, group);
      }
    }

  // --- Gather, dual contouring, occupancy ---------------------------------------------------------
  md << "## The gather's arithmetic\n\n";
  const json& c = r["gather_flops"];
  md << "Per sample, the lines the GPU runs for a sample that reaches S_d (shaders/maps/gather_loop.glsl: "
        "sssDrawSharedSample once for the three colour bands, x_i on the texel's plane, the projected-area "
        "division, then sssRadiosityTerm with the directional dipole per band), run in C++ with a scalar that "
        "counts each operation (app/bench_report/counted_real.h). A directional light: **"
     << fmt(c["flops_per_shared_sample"], 1) << " FLOPs** for the three bands (min "
     << c["flops_shared_min"].get<long long>() << ", max " << c["flops_shared_max"].get<long long>() << " over "
     << c["samples"].get<int>() << " samples), that is per sample and band " << fmt(c["add"], 1) << " add/sub, "
     << fmt(c["mul"], 1) << " mul, " << fmt(c["div"], 1) << " div, " << fmt(c["special"], 1)
     << " special functions (exp, log, sqrt, sin, cos) = **" << fmt(c["flops_mean"], 1) << " FLOPs** ("
     << fmt(c["other_not_flops"], 1) << " comparisons, min/max/abs not counted).";
  if (c.contains("point_light"))
    md << " A point light in a cup (the stereographic look-up and area ratio): **"
       << fmt(c["point_light"]["flops_per_shared_sample"], 1) << " FLOPs** for the three bands, **"
       << fmt(c["point_light"]["flops_mean"], 1) << "** per band.";
  md << " Only the G-buffer look-ups (texture fetches) are not counted, and `probe maps` counts every sample "
        "as an evaluation, samples that miss the object included: the rate below is FLOPs of full "
        "directional samples × all samples, an upper bound of the arithmetic done.\n\n";
  md << "| gather | maps [ms] | samples/s | FLOP/s | of FP32 peak |\n|---|---:|---:|---:|---:|\n";
  for (const char* name : {"fragment", "compute"})
    if (g["runs"].contains(name)) {
      const json& run = g["runs"][name];
      md << "| " << name << " | " << fmt(run["maps_ms"]) << " | " << si(run["evaluations_per_s"]) << " | "
         << si(run["flops_per_s"]) << " | " << pct(run["share_of_fp32_peak"]) << " |\n";
    }
  md << "\n## Dual contouring\n\n";
  md << "Cells = (res − 1)³ per extraction; `field.extract` is the GPU's passes (docs/presets.md), by either "
        "`field.extraction`: compute shaders or geometry shaders with transform feedback. The "
        "lattice is filled each frame before it (`field.sample`, in the frame's wall time): on the GPU for a blob, "
        "sampled on the CPU and uploaded for a candle or mesh field.\n\n";
  md << "| lattice | extraction | extract GPU [ms] | cells/s | triangles | triangles/s | frame fps |\n"
        "|---:|---|---:|---:|---:|---:|---:|\n";
  for (const json& d : fig["dual_contouring"])
    md << "| " << d["res"].get<int>() << "³ | " << d.value("extraction", std::string("geometry")) << " | "
       << fmt(d["extract_gpu_ms"], 3) << " | " << si(d["cells_per_s"]) << " | "
       << si(d["triangles"]) << " | " << si(d["triangles_per_s"]) << " | " << fmt(d["frame_fps"]) << " |\n";
  md << "\n## Cached against no-cache by occupancy\n\n";
  md << "| method | fov [°] | occupancy | wall [ms] | GPU [ms] |\n|---|---:|---:|---:|---:|\n";
  for (const auto& [method, runs] : occ["runs"].items())
    for (const json& p : runs)
      md << "| " << method << " | " << fmt(p["fov_deg"], 0) << " | " << pct(p["occupancy"]) << " | " << fmt(p["wall_ms"])
         << " | " << fmt(p["gpu_total_ms"]) << " |\n";
  md << "\n";
  for (const auto& [method, f] : occ["fits"].items())
    md << "- " << method << ": wall ≈ " << fmt(f["intercept_ms"], 1) << " ms + " << fmt(f["ms_per_occupancy"].get<double>() / 100.0, 2)
       << " ms per 1% of occupancy\n";
  md << "\n## Commands\n\n";
  for (const json& row : r["rows"]) md << "- `" << str(row["name"]) << "`: `" << str(row["command"]) << "`\n";
  return md.str();
}

}  // namespace tallow::bench_report
