#include "app/commands/mesh_command.h"

#include <algorithm>
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
#include "geometry/obj_writer.h"
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

namespace {

/// --res applied to the loaded scene (one line on a bad value).
void applyRes(const MeshOptions& options, LoadedScene& loaded) {
  if (options.res == 0) return;
  try {
    parameterRegistry(loaded.materials).set(loaded.config, "field.res", options.res);
  } catch (const InputError& e) {
    throw InputError(std::string("--res: ") + e.what());
  }
}

/// Every field object of `loaded` at t in world units, contoured by `shaders` (null: on the CPU).
geometry::TriangleMesh worldMesh(const LoadedScene& loaded, const std::vector<PlacedField>& fields, double timeS,
                                 const gpu::ShaderLibrary* shaders) {
  const sss::FieldMeshes parts = meshEachField(fields, loaded.config.render, timeS, shaders);
  geometry::TriangleMesh world;
  for (const PlacedField& f : fields) appendWorld(world, parts.at(f.objectIndex), f.model);
  if (world.triangles.empty())  // e.g. a --set that moved everything out of the lattice
    throw InputError("the field objects of preset " + quote(loaded.presetName) + " have no surface at t = " +
                     std::to_string(timeS) + " s");
  return world;
}

}  // namespace

geometry::TriangleMesh meshFields(const MeshOptions& options, LoadedScene& loaded) {
  checkTime("--time", options.timeS);
  applyRes(options, loaded);
  const std::vector<PlacedField> fields = placeFields(loaded.config.scene, loaded.presetName);
  std::unique_ptr<MeshingContext> meshing;
  if (!options.cpu) meshing = std::make_unique<MeshingContext>(options.gl, options.scene.shaderDir);
  return worldMesh(loaded, fields, options.timeS, meshing ? meshing->shaders.get() : nullptr);
}

namespace {

/// What the model of each candle field says of itself at t, as PLY comments (`comment tallow.candle
/// NAME key value …`, field units): what scripts/results_melt.py compares its measurements of the
/// mesh with.
std::vector<std::string> modelComments(double timeS, const LoadedScene& loaded) {
  std::vector<std::string> comments;
  for (const sss::SceneObject& o : loaded.config.scene.objects) {
    if (o.shape != sss::ShapeKind::Field) continue;
    const std::optional<geometry::CandleField> candle = sss::candleOf(o.field, timeS);
    if (!candle) continue;
    const geometry::CandleField& c = *candle;
    char line[512];
    std::snprintf(line, sizeof line,
                  "tallow.candle %s t %.9g rim_height %.9g pool_y %.9g pool_radius %.9g pool_depth %.9g "
                  "drips_started %d drips_frozen %d drip_volume %.9g puddle_volume %.9g puddle_area %.9g "
                  "volume_target %.9g",
                  o.name.empty() ? "candle" : o.name.c_str(), timeS, c.rimHeight(), c.poolY(), c.poolRadius(),
                  c.poolDepth(), c.dripsStarted(), c.dripsFrozen(), c.dripVolume(), c.puddleVolume(), c.puddleArea(),
                  c.volumeTarget());
    std::string text = line;
    for (char& ch : text)
      if (ch == '\n' || ch == '\r') ch = ' ';
    comments.push_back(text);
  }
  return comments;
}

/// Writes `mesh` as PLY or OBJ by the file's extension.
void writeMesh(const std::filesystem::path& file, const geometry::TriangleMesh& mesh,
               const std::vector<std::string>& comments) {
  if (file.extension() == ".obj") geometry::writeObj(file, mesh, comments);
  else geometry::writePly(file, mesh, comments);
}

}  // namespace

std::vector<std::string> meshSequenceFiles(const std::string& out, int frames) {
  const std::filesystem::path base(out);
  const std::filesystem::path stem = base.parent_path() / base.stem();
  const int digits = std::max(4, static_cast<int>(std::to_string(std::max(frames - 1, 0)).size()));
  std::vector<std::string> files;
  for (int i = 0; i < frames; ++i) {
    std::string number = std::to_string(i);
    number.insert(0, static_cast<std::size_t>(digits) - std::min<std::size_t>(number.size(), digits), '0');
    files.push_back(stem.string() + "_" + number + base.extension().string());
  }
  return files;
}

int runMesh(const MeshOptions& options) {
  if (options.out.empty()) throw InputError("mesh: --out MESH.ply is required");
  const std::filesystem::path out(options.out);
  if (out.extension() != ".ply" && out.extension() != ".obj")
    throw InputError("--out: " + options.out + " is neither MESH.ply nor MESH.obj");
  if (options.frames < 0) throw InputError("--frames: must not be negative");
  if (options.frames > 0) checkFps("--fps", options.fps);
  checkTime("--time", options.timeS);
  const std::vector<std::string> files =
      options.frames > 0 ? meshSequenceFiles(options.out, options.frames) : std::vector<std::string>{options.out};
  // The folder is created as capture's --out is.
  for (const std::string& f : files) checkOutputFileInNewFolder("--out", f, {".ply", ".obj"});
  LoadedScene loaded = loadScene(options.scene);
  applyRes(options, loaded);
  const std::vector<PlacedField> fields = placeFields(loaded.config.scene, loaded.presetName);
  std::unique_ptr<MeshingContext> meshing;  // one context for the whole sequence
  if (!options.cpu) meshing = std::make_unique<MeshingContext>(options.gl, options.scene.shaderDir);
  for (std::size_t i = 0; i < files.size(); ++i) {
    // Frame i of the sequence at t + i / fps (the times capture uses).
    const double t = options.frames > 0 ? options.timeS + static_cast<double>(i) / options.fps : options.timeS;
    const geometry::TriangleMesh mesh = worldMesh(loaded, fields, t, meshing ? meshing->shaders.get() : nullptr);
    // The folder once the first mesh is made (a scene without a surface leaves none behind).
    if (const std::filesystem::path folder = out.parent_path(); i == 0 && !folder.empty())
      std::filesystem::create_directories(folder);
    writeMesh(files[i], mesh, modelComments(t, loaded));
    std::printf("tallow: t = %g s: %zu triangle(s), %zu vertices (%s) -> %s\n", t, mesh.triangles.size(),
                mesh.positions.size(), options.cpu ? "OpenVDB volumeToMesh" : "GPU dual contouring", files[i].c_str());
  }
  return 0;
}

}  // namespace tallow::app
