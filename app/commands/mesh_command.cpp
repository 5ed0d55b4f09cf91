#include "app/commands/mesh_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands/field_command.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/params.h"
#include "geometry/candle_field.h"
#include "geometry/cpu_mesher.h"
#include "geometry/gpu_dual_contouring.h"
#include "geometry/ply_writer.h"
#include "gpu/gl_context.h"
#include "sss/field_objects.h"
#include "sss/field_source.h"

namespace tallow::app {
namespace {

/// Appends `part` (field units) to `out` moved into world units by `model`.
void appendWorld(geometry::TriangleMesh& out, const geometry::TriangleMesh& part, const glm::dmat4& model) {
  const auto offset = static_cast<std::uint32_t>(out.positions.size());
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(model)));
  for (const glm::vec3& p : part.positions) out.positions.emplace_back(model * glm::dvec4(glm::dvec3(p), 1.0));
  for (const glm::vec3& n : part.normals) out.normals.emplace_back(glm::normalize(normalMatrix * glm::dvec3(n)));
  for (const auto& t : part.triangles) out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace

namespace {

/// Each of `fields` at time t as the renderer draws it, in the field's units: contoured by the GPU
/// (a current context and `shaders`), or with `cpu` by OpenVDB's volumeToMesh on the same lattice.
sss::FieldMeshes meshEachField(const std::vector<PlacedField>& fields, const sss::RenderSettings& render,
                               double timeS, const gpu::ShaderLibrary* shaders) {
  sss::FieldMeshes meshes;
  for (const PlacedField& f : fields) {
    geometry::TriangleMesh part;
    if (!shaders) {
      part = geometry::meshOnCpu(f.source.sample(timeS, render.fieldRes), *f.source.at(timeS));
    } else {
      // As the renderer: blob and candle evaluated on the GPU with analytic normals, a melting mesh
      // from its NanoVDB grids and the melt at t, still meshes uploaded; with field.evaluate=cpu
      // every lattice sampled on the CPU and uploaded.
      const auto dc = sss::makeFieldExtractor(*shaders, f.source, sss::fieldMeshingOf(render));
      const std::unique_ptr<sss::GpuFieldFill> onGpu = render.fieldOnGpu ? f.source.gpuFill(*shaders) : nullptr;
      sss::putFieldLattice(f.source, timeS, *dc, onGpu.get());
      dc->extract();
      part = dc->readBack();
    }
    if (part.normals.size() != part.positions.size()) geometry::computeVertexNormals(part);
    meshes.emplace(f.objectIndex, std::move(part));
  }
  return meshes;
}

/// A hidden context of `backend` and the shaders of `shaderDir`, current until destroyed.
struct MeshingContext {
  MeshingContext(const std::string& backend, const std::string& shaderDir) {
    gpu::ContextOptions contextOptions;
    contextOptions.backend = gpu::parseGlBackend(backend);
    contextOptions.visible = false;
    context = gpu::GlContext::create(contextOptions);
    shaders = std::make_unique<gpu::ShaderLibrary>(makeShaderLibrary(shaderDir));
  }
  std::unique_ptr<gpu::GlContext> context;
  std::unique_ptr<gpu::ShaderLibrary> shaders;
};

}  // namespace

sss::FieldMeshes drawnFieldMeshes(const LoadedScene& loaded, const std::string& shaderDir, double timeS,
                                  const std::string& gl) {
  const sss::Scene& scene = loaded.config.scene;
  if (!sss::FieldObjects::any(scene)) return {};
  const MeshingContext meshing(gl, shaderDir);
  return meshEachField(placeFields(scene, loaded.presetName), loaded.config.render, timeS, meshing.shaders.get());
}

geometry::TriangleMesh meshFields(const MeshOptions& options, LoadedScene& loaded) {
  checkTime("--time", options.timeS);
  if (options.res != 0) {
    try {
      parameterRegistry(loaded.materials).set(loaded.config, "field.res", options.res);
    } catch (const InputError& e) {
      throw InputError(std::string("--res: ") + e.what());
    }
  }
  const std::vector<PlacedField> fields = placeFields(loaded.config.scene, loaded.presetName);
  std::unique_ptr<MeshingContext> meshing;
  if (!options.cpu) meshing = std::make_unique<MeshingContext>(options.gl, options.scene.shaderDir);
  const sss::FieldMeshes parts =
      meshEachField(fields, loaded.config.render, options.timeS, meshing ? meshing->shaders.get() : nullptr);
  geometry::TriangleMesh world;
  for (const PlacedField& f : fields) appendWorld(world, parts.at(f.objectIndex), f.model);
  if (world.triangles.empty())  // e.g. a --set that moved everything out of the lattice
    throw InputError("the field objects of preset " + quote(loaded.presetName) + " have no surface at t = " +
                     std::to_string(options.timeS) + " s");
  return world;
}

namespace {

/// What the model of each candle field says of itself at t, as PLY comments (`comment tallow.candle
/// NAME key value …`, field units): what scripts/results_melt.py compares its measurements of the
/// mesh with.
std::vector<std::string> modelComments(const MeshOptions& options, const LoadedScene& loaded) {
  std::vector<std::string> comments;
  for (const sss::SceneObject& o : loaded.config.scene.objects) {
    if (o.shape != sss::ShapeKind::Field) continue;
    const std::optional<geometry::CandleField> candle = sss::candleOf(o.field, options.timeS);
    if (!candle) continue;
    const geometry::CandleField& c = *candle;
    char line[512];
    std::snprintf(line, sizeof line,
                  "tallow.candle %s t %.9g rim_height %.9g pool_y %.9g pool_radius %.9g pool_depth %.9g "
                  "drips_started %d drips_frozen %d drip_volume %.9g puddle_volume %.9g puddle_area %.9g "
                  "volume_target %.9g",
                  o.name.empty() ? "candle" : o.name.c_str(), options.timeS, c.rimHeight(), c.poolY(), c.poolRadius(),
                  c.poolDepth(), c.dripsStarted(), c.dripsFrozen(), c.dripVolume(), c.puddleVolume(), c.puddleArea(),
                  c.volumeTarget());
    std::string text = line;
    for (char& ch : text)
      if (ch == '\n' || ch == '\r') ch = ' ';
    comments.push_back(text);
  }
  return comments;
}

}  // namespace

int runMesh(const MeshOptions& options) {
  if (options.out.empty()) throw InputError("mesh: --out MESH.ply is required");
  const std::filesystem::path out(options.out);
  checkOutputFile("--out", out);
  LoadedScene loaded = loadScene(options.scene);
  const geometry::TriangleMesh mesh = meshFields(options, loaded);
  geometry::writePly(out, mesh, modelComments(options, loaded));
  std::printf("tallow: %zu triangle(s), %zu vertices (%s) -> %s\n", mesh.triangles.size(), mesh.positions.size(),
              options.cpu ? "OpenVDB volumeToMesh" : "GPU dual contouring", options.out.c_str());
  return 0;
}

}  // namespace tallow::app
