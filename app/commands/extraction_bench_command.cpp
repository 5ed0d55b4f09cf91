#include "app/commands/extraction_bench_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "app/commands/frame_stats.h"
#include "app/commands/provenance.h"
#include "app/commands/progress.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "geometry/blob_field.h"
#include "geometry/candle_field.h"
#include "geometry/cpu_mesher.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/grid_sampler.h"
#include "gpu/atomic_file.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"

namespace tallow::app {
namespace {

constexpr double kBlobTimeS = 2.5;     ///< blobs apart and merging (at t = 0 they coincide)
constexpr double kCandleTimeS = 10.0;  ///< half-way: cup, wick and drips formed

std::unique_ptr<geometry::ScalarField> makeField(const std::string& name) {
  if (name == "blob") return std::make_unique<geometry::BlobField>(kBlobTimeS);
  if (name == "candle") return std::make_unique<geometry::CandleField>(kCandleTimeS);
  throw InputError("--fields: unknown field \"" + name + "\" (expected blob or candle)");
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// time(256³)/time(128³) of `key` for one field's rows, null when either resolution is missing.
nlohmann::json ratio(const nlohmann::json& rows, const char* key) {
  const nlohmann::json *r128 = nullptr, *r256 = nullptr;
  for (const auto& r : rows) {
    if (r["res"] == 128) r128 = &r;
    if (r["res"] == 256) r256 = &r;
  }
  if (!r128 || !r256 || (*r128)[key].get<double>() <= 0.0) return nullptr;
  return (*r256)[key].get<double>() / (*r128)[key].get<double>();
}

}  // namespace

int runProbeExtraction(const ProbeExtractionOptions& o) {
  if (o.out.empty()) throw InputError("probe extraction: --out FILE.json is required");
  checkOutputFile("--out", o.out, {".json"});  // before the work, not after it
  if (o.fields.empty()) throw InputError("--fields: give at least one of blob, candle");
  for (const auto& f : o.fields)
    if (f != "blob" && f != "candle") throw InputError("--fields: unknown field \"" + f + "\" (expected blob or candle)");
  if (o.resolutions.empty()) throw InputError("--res: give at least one resolution");
  for (int n : o.resolutions)
    if (n < 16 || n > 256) throw InputError("--res: " + std::to_string(n) + " is outside [16, 256]");
  if (o.repeats < 1 || o.repeats > 100) throw InputError("--repeats: must be in [1, 100]");

  gpu::ContextOptions contextOptions;
  contextOptions.backend = gpu::parseGlBackend(o.gl);
  const auto context = gpu::GlContext::create(contextOptions);
  const gpu::ShaderLibrary library;

  nlohmann::json fields = nlohmann::json::array();
  Progress progress("probe extraction", "case", static_cast<int>(o.fields.size() * o.resolutions.size()));
  int done = 0;
  for (const auto& name : o.fields) {
    const auto field = makeField(name);
    nlohmann::json rows = nlohmann::json::array();
    for (int n : o.resolutions) {
      auto t0 = std::chrono::steady_clock::now();
      const geometry::SampledLattice lattice = geometry::sampleField(*field, n);
      const double sampleMs = msSince(t0);

      geometry::GpuDualContouring dc(library, n);
      std::vector<double> uploadMs, gpuMs, wallMs, cpuMs;
      dc.upload(lattice);  // warm-up: first upload, first extraction
      dc.extract();
      glFinish();
      for (int r = 0; r < o.repeats; ++r) {
        t0 = std::chrono::steady_clock::now();
        dc.upload(lattice);
        glFinish();
        uploadMs.push_back(msSince(t0));
        t0 = std::chrono::steady_clock::now();
        dc.extract();
        glFinish();
        wallMs.push_back(msSince(t0));
        gpuMs.push_back(dc.lastExtractionMs());
      }
      dc.checkOverflow();
      const std::size_t gpuTriangles = dc.triangleCount();

      std::size_t cpuTriangles = geometry::meshOnCpu(lattice, *field).triangles.size();  // warm-up
      for (int r = 0; r < o.repeats; ++r) {
        t0 = std::chrono::steady_clock::now();
        cpuTriangles = geometry::meshOnCpu(lattice, *field).triangles.size();
        cpuMs.push_back(msSince(t0));
      }

      const double gpuMedian = median(gpuMs), wallMedian = median(wallMs), cpuMedian = median(cpuMs);
      auto perSecond = [](std::size_t triangles, double ms) { return ms > 0.0 ? static_cast<double>(triangles) / (ms * 1e-3) : 0.0; };
      rows.push_back({{"res", n},
                      {"sample_cpu_ms", sampleMs},
                      {"gpu_upload_ms", median(uploadMs)},
                      {"gpu_extract_ms", gpuMedian},
                      {"gpu_extract_wall_ms", wallMedian},
                      {"gpu_triangles", gpuTriangles},
                      {"gpu_vertices", dc.vertexCount()},
                      {"gpu_triangles_per_s", perSecond(gpuTriangles, gpuMedian)},
                      {"gpu_wall_triangles_per_s", perSecond(gpuTriangles, wallMedian)},
                      {"active_blocks", dc.activeBlockCount()},
                      {"blocks", dc.blockCount()},
                      {"gpu_buffer_bytes", dc.bufferBytes()},
                      {"cpu_mesh_ms", cpuMedian},
                      {"cpu_triangles", cpuTriangles},
                      {"cpu_triangles_per_s", perSecond(cpuTriangles, cpuMedian)}});
      char line[256];
      std::snprintf(line, sizeof line,
                    "%-6s %3d³  sample %8.2f ms  gpu %8.2f ms (wall %8.2f)  cpu %8.2f ms  triangles gpu %zu cpu %zu",
                    name.c_str(), n, sampleMs, gpuMedian, wallMedian, cpuMedian, gpuTriangles, cpuTriangles);
      progress.print(line, stdout);
      progress.update(++done);
    }
    fields.push_back({{"field", name},
                      {"time_s", name == "blob" ? kBlobTimeS : kCandleTimeS},
                      {"rows", rows},
                      {"ratio_256_128",
                       {{"gpu_extract", ratio(rows, "gpu_extract_ms")},
                        {"gpu_extract_wall", ratio(rows, "gpu_extract_wall_ms")},
                        {"cpu_mesh", ratio(rows, "cpu_mesh_ms")}}}});
  }
  const nlohmann::json result = {
      {"fields", fields},
      {"repeats", o.repeats},
      {"block_cells", geometry::GpuDualContouring::kBlockCells},
      {"placement", std::string(geometry::vertexPlacementName(geometry::kDefaultPlacement))},
      {"gpu",
       glJson(*context)},
      {"notes",
       "medians of `repeats` runs after one warm-up; gpu_extract_ms from GL_TIMESTAMP queries around extract(), "
       "gpu_extract_wall_ms is extract() + glFinish() on the CPU clock; upload excluded from both; cpu_mesh_ms is "
       "OpenVDB volumeToMesh plus per-vertex field gradients on the same lattice"}};
  gpu::writeTextFileAtomically(o.out, result.dump(2) + "\n");
  return 0;
}

}  // namespace tallow::app
