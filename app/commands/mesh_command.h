#pragma once
// `tallow mesh`: the triangles the renderer draws for a preset's field objects at time t, in world
// units, as one binary PLY or an OBJ (all field objects concatenated), or with --frames N the
// animation as a numbered sequence NAME_0000.ply … (or .obj) at --fps, what DCC tools import as a
// mesh sequence, normals included. Each field is sampled exactly as the
// renderer samples it (sss::FieldSource::sample) and isosurfaced by the GPU dual contouring, or,
// with --cpu, by OpenVDB's volumeToMesh on the same lattice.
#include <string>
#include <vector>

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
  std::string out;            ///< MESH.ply or MESH.obj (with frames: the sequence's base name)
  int frames = 0;             ///< > 0: a numbered sequence of this many meshes from timeS on
  double fps = 30.0;          ///< the sequence's frames per second
};

/// The files of a sequence of `frames` meshes named after `out` (MESH.ply → MESH_0000.ply, …; at
/// least 4 digits, more when frames need them).
std::vector<std::string> meshSequenceFiles(const std::string& out, int frames);

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
