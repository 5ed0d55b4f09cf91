#pragma once
// `tallow mesh`: the triangles the renderer draws for a preset's field objects at time t, in world
// units, as one binary PLY (all field objects concatenated). Each field is sampled exactly as the
// renderer samples it (sss::FieldSource::sample) and isosurfaced by the GPU dual contouring, or,
// with --cpu, by OpenVDB's volumeToMesh on the same lattice.
#include <string>

#include "app/config/setup.h"
#include "geometry/triangle_mesh.h"
#include "sss/reference/reference_integrator.h"

namespace tallow::app {

struct MeshOptions {
  SceneOptions scene;         ///< preset and --set (size and --explain are not used)
  double timeS = 0.0;
  int res = 0;                ///< samples per axis; 0 = the preset's field.res
  bool cpu = false;           ///< OpenVDB volumeToMesh instead of the GPU
  std::string gl = "osmesa";  ///< OpenGL context for the GPU path
  std::string out;            ///< MESH.ply
};

/// The triangles the renderer draws for each field object of `loaded` at time t, by object index, in
/// the field's units (sampled as the renderer samples it, contoured by the GPU's dual contouring
/// with field.res, field.placement and field.evaluate), in a hidden context of its own (backend
/// `gl`, shaders from `shaderDir`; the caller's context, if any, is not current afterwards). Empty,
/// and no context opened, when the scene has no field object. Throws ContextError /
/// std::runtime_error with one line.
sss::FieldMeshes drawnFieldMeshes(const LoadedScene& loaded, const std::string& shaderDir, double timeS,
                                  const std::string& gl);

/// The world-space mesh of every field object of the options' preset (no file written); opens a
/// GL context unless options.cpu. Throws like runMesh.
geometry::TriangleMesh meshFields(const MeshOptions& options);

/// Returns the exit code; throws InputError / ContextError / std::runtime_error with one line on
/// failure, and then writes nothing.
int runMesh(const MeshOptions& options);

}  // namespace tallow::app
