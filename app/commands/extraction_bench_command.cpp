#include "app/commands/extraction_bench_command.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

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

      // Both stages of passes 2 and 4 (field.extraction), the default's figures first in the row.
      struct PathTimes {
        double uploadMs = 0.0, gpuMs = 0.0, wallMs = 0.0;
        std::size_t triangles = 0, vertices = 0, activeBlocks = 0, blocks = 0, bufferBytes = 0;
      };
      auto timePath = [&](geometry::ExtractionPath path) {
        geometry::GpuDualContouring dc(library, n, geometry::kDefaultPlacement, geometry::NormalSource::LatticeGradient,
                                       path);
        std::vector<double> uploadMs, gpuMs, wallMs;
        dc.upload(lattice);  // warm-up: first upload, first extraction
        dc.extract();
        glFinish();
        for (int r = 0; r < o.repeats; ++r) {
          auto start = std::chrono::steady_clock::now();
          dc.upload(lattice);
          glFinish();
          uploadMs.push_back(msSince(start));
          start = std::chrono::steady_clock::now();
          dc.extract();
          glFinish();
          wallMs.push_back(msSince(start));
          gpuMs.push_back(dc.lastExtractionMs());
        }
        dc.checkOverflow();
        return PathTimes{median(uploadMs), median(gpuMs),        median(wallMs),       dc.triangleCount(),
                         dc.vertexCount(), dc.activeBlockCount(), dc.blockCount(),   dc.bufferBytes()};
      };
      const geometry::ExtractionPath other = geometry::kDefaultExtraction == geometry::ExtractionPath::Compute
                                                 ? geometry::ExtractionPath::GeometryShader
                                                 : geometry::ExtractionPath::Compute;
      const PathTimes main = timePath(geometry::kDefaultExtraction), second = timePath(other);
      const std::size_t gpuTriangles = main.triangles;
      nlohmann::json paths = nlohmann::json::object();
      for (const auto& [path, times] : {std::pair{geometry::kDefaultExtraction, main}, std::pair{other, second}})
        paths[std::string(geometry::extractionPathName(path))] = {{"gpu_extract_ms", times.gpuMs},
                                                                  {"gpu_extract_wall_ms", times.wallMs},
                                                                  {"gpu_triangles", times.triangles},
                                                                  {"gpu_vertices", times.vertices}};

      std::vector<double> cpuMs;
      std::size_t cpuTriangles = geometry::meshOnCpu(lattice, *field).triangles.size();  // warm-up
      for (int r = 0; r < o.repeats; ++r) {
        t0 = std::chrono::steady_clock::now();
        cpuTriangles = geometry::meshOnCpu(lattice, *field).triangles.size();
        cpuMs.push_back(msSince(t0));
      }

      const double gpuMedian = main.gpuMs, wallMedian = main.wallMs, cpuMedian = median(cpuMs);
      auto perSecond = [](std::size_t triangles, double ms) { return ms > 0.0 ? static_cast<double>(triangles) / (ms * 1e-3) : 0.0; };
      rows.push_back({{"res", n},
                      {"sample_cpu_ms", sampleMs},
                      {"gpu_upload_ms", main.uploadMs},
                      {"gpu_extract_ms", gpuMedian},
                      {"gpu_extract_wall_ms", wallMedian},
                      {"gpu_triangles", gpuTriangles},
                      {"gpu_vertices", main.vertices},
                      {"gpu_triangles_per_s", perSecond(gpuTriangles, gpuMedian)},
                      {"gpu_wall_triangles_per_s", perSecond(gpuTriangles, wallMedian)},
                      {"active_blocks", main.activeBlocks},
                      {"blocks", main.blocks},
                      {"gpu_buffer_bytes", main.bufferBytes},
                      {"extraction", std::string(geometry::extractionPathName(geometry::kDefaultExtraction))},
                      {"paths", paths},
                      {"cpu_mesh_ms", cpuMedian},
                      {"cpu_triangles", cpuTriangles},
                      {"cpu_triangles_per_s", perSecond(cpuTriangles, cpuMedian)}});
      char line[256];
      std::snprintf(line, sizeof line,
                    "%-6s %3d³  sample %8.2f ms  gpu %8.2f ms (wall %8.2f; %s %8.2f)  cpu %8.2f ms  triangles gpu %zu cpu %zu",
                    name.c_str(), n, sampleMs, gpuMedian, wallMedian,
                    std::string(geometry::extractionPathName(other)).c_str(), second.gpuMs, cpuMedian, gpuTriangles,
                    cpuTriangles);
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
       "medians of `repeats` runs after one warm-up; gpu_* figures are the default extraction path's (`extraction`), "
       "`paths` has both (field.extraction); gpu_extract_ms from GL_TIMESTAMP queries around extract(), "
       "gpu_extract_wall_ms is extract() + glFinish() on the CPU clock; upload excluded from both; cpu_mesh_ms is "
       "OpenVDB volumeToMesh plus per-vertex field gradients on the same lattice"}};
  gpu::writeTextFileAtomically(o.out, result.dump(2) + "\n");
  return 0;
}

}  // namespace tallow::app
