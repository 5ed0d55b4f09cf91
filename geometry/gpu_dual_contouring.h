#pragma once
// GPU dual contouring (surface nets after Gibson 1998, as the radiosity-maps paper §4 cites) of a
// lattice of field samples in a GL_R32F 3D texture, filled either by upload() of a SampledLattice
// sampled on the CPU (still mesh fields) or on the GPU by fillOnGpu() with a compute program that
// evaluates the field itself (the blob and the candle: GpuBlobField, GpuCandleField,
// shaders/fields/lattice.comp; a melting mesh: GpuMeltField, shaders/fields/mesh_melt_lattice.comp;
// no CPU lattice, no upload). Four passes, all on the GPU, the middle ones in geometry shaders
// with transform feedback or in compute shaders (ExtractionPath, field.extraction; same records,
// same buffers, same triangles: DualContouringPaths.* compares them):
//   1. classify.comp: blocks of kBlockCells³ cells whose samples straddle 0 → active-block list +
//      indirect draw command (instances = active blocks);
//   2. cells.vert + vertices.geom: one vertex per surface patch of each sign-changing cell (usually
//      one patch, up to four where a face is ambiguous, see shaders/dual_contouring/patches.glsl),
//      placed by `VertexPlacement`: the mean of the patch's edge crossings, or the minimum of the
//      probabilistic quadric of their tangent planes kept in the cell (qef.glsl); normal from the
//      texture's gradient, or with NormalSource::BlobGradient / CandleGradient from the field's
//      analytic gradient (shaders/fields/blob.glsl, candle.glsl; uniforms set on normalProgram()),
//      captured by transform feedback;
//   3. index_map.comp: first vertex of each cell (emission order) → GL_R32I 3D index map,
//      dispatched indirectly;
//   4. cells.vert + quads.geom: two triangles per sign-changing edge, outward winding, captured by
//      transform feedback into the mesh buffer, drawn with glDrawTransformFeedback.
// With ExtractionPath::Compute, passes 2 and 4 are vertices.comp and quads.comp (one work group per
// active block, dispatched indirectly), which reserve their records' places with atomics; pass 2
// writes the index map itself (no pass 3), and the mesh is drawn by glDrawArraysIndirect from the
// count pass 4 leaves. The per-cell work is one source for both (cell_vertices.glsl, cell_quads.glsl).
// Nothing is read back in extract() or draw(); the query-based accessors are for tests and stats.
#include "geometry/extraction_path.h"
#include "geometry/grid_sampler.h"
#include "geometry/triangle_mesh.h"
#include "geometry/vertex_placement.h"
#include "gpu/gl_objects.h"
#include "gpu/program.h"
#include "gpu/shader_library.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace tallow::geometry {

/// Where pass 2 takes the vertex normals from.
enum class NormalSource {
  LatticeGradient,  ///< central differences of the texture: any field
  BlobGradient,     ///< the blob's analytic gradient at the vertex (GpuBlobField sets its uniforms)
  CandleGradient,   ///< the candle's analytic gradient at the vertex (GpuCandleField sets its uniforms)
};

class GpuDualContouring {
 public:
  static constexpr int kBlockCells = 4;  ///< block edge in cells: 64 points per block instance
  /// Vertex capacity = min(kMaxPatchesPerCell · cells, kVerticesPerFaceCell · (n − 1)²): a closed surface inside the
  /// lattice crosses O(n²) cells; 24 is 4× the cube's six faces, room for folded blob shapes.
  static constexpr std::size_t kVerticesPerFaceCell = 24;
  /// A cell holds at most 4 separate patches of surface (4 corners cut off), one vertex each.
  static constexpr std::size_t kMaxPatchesPerCell = 4;
  /// Triangles per vertex: a closed quad mesh has ~1 quad (2 triangles) per vertex (Euler); 3 is slack.
  static constexpr std::size_t kTrianglesPerVertex = 3;
  /// Total buffer memory cap; a lattice that would need more throws at construction. 512³ (the
  /// device bench's largest lattice, field.res's maximum) needs 1.66 GiB of buffers.
  static constexpr std::size_t kMaxBufferBytes = std::size_t{2} << 30;

  /// Builds the programs and sizes every buffer for n³ samples (n ≥ 2), placing vertices by
  /// `placement`. Needs a current GL 4.5 context. Throws std::runtime_error when the buffers would
  /// exceed kMaxBufferBytes.
  GpuDualContouring(const gpu::ShaderLibrary& library, int samplesPerAxis,
                    VertexPlacement placement = kDefaultPlacement,
                    NormalSource normals = NormalSource::LatticeGradient,
                    ExtractionPath path = kDefaultExtraction);

  /// Copies `lattice` into the GL_R32F 3D texture (n must match the constructor's).
  void upload(const SampledLattice& lattice);
  /// Fills the texture on the GPU: dispatches `fill` (a compute program with local size 4³ whose
  /// field uniforms the caller has set) over the n³ samples with the texture bound as image unit 0
  /// (`uLattice`, r32f) and uSamples, uOrigin, uCellSize set; sample s sits at origin + cellSize·s
  /// as in SampledLattice. Ends with the barrier that makes the writes visible to extract().
  void fillOnGpu(gpu::Program& fill, glm::dvec3 origin, double cellSize);
  /// Runs the four passes on the uploaded lattice; no CPU read-back, no stall.
  void extract();
  /// The vertex pass's program (pass 2, either stage): with NormalSource::BlobGradient / CandleGradient the
  /// field's uniforms (shaders/fields/blob_uniforms.glsl, candle_uniforms.glsl) must be set here
  /// before extract().
  gpu::Program& normalProgram() { return vertices_; }
  NormalSource normalSource() const { return normals_; }
  ExtractionPath path() const { return path_; }
  std::size_t uploadCount() const { return uploads_; }  ///< upload() calls so far
  std::size_t gpuFillCount() const { return gpuFills_; }  ///< fillOnGpu() calls so far
  /// Draws the last extraction as GL_TRIANGLES with the caller's program bound (attribute 0:
  /// position in world units, 1: unit normal), `instances` times (gl_InstanceID): by
  /// glDrawTransformFeedbackInstanced, or on the compute path by glDrawArraysIndirect from a command
  /// per instance count (its vertex count copied on the GPU after each extraction).
  void draw(int instances = 1) const;

  // --- Read-back (tests, `tallow mesh`, stats); each waits for the GPU. ---
  /// The last extraction as an indexed mesh (vertices shared by vertex-buffer index); throws
  /// std::runtime_error when a buffer overflowed.
  TriangleMesh readBack() const;
  std::size_t triangleCount() const;   ///< triangles stored by pass 4
  /// triangleCount without a wait: nullopt while the GPU has not finished the extraction.
  std::optional<std::size_t> triangleCountIfAvailable() const;
  std::size_t vertexCount() const;     ///< vertices stored by pass 2
  std::size_t activeBlockCount() const;
  std::size_t blockCount() const { return static_cast<std::size_t>(blocks_) * blocks_ * blocks_; }
  /// GPU time of the last extract() from GL_TIMESTAMP queries (llvmpipe's first GL_TIME_ELAPSED
  /// of a context reads garbage, so the pair of timestamps is used instead).
  double lastExtractionMs() const;
  /// The n³ values of the texture (x fastest, as SampledLattice::values), however it was filled.
  std::vector<float> readLattice() const;
  /// Throws std::runtime_error (one line) when the last extraction dropped vertices or triangles.
  void checkOverflow() const;
  /// Whether the last extract() dropped vertices or triangles (its buffers were too small): nothing
  /// while its counts are not available yet and `wait` is false; with `wait`, waits for them.
  std::optional<bool> overflowed(bool wait) const;
  /// Primitives the last extraction generated, written or not (waits): what the buffers must hold.
  std::size_t generatedVertices() const;
  std::size_t generatedTriangles() const;
  /// Sizes the vertex buffer for `vertices` (the triangle buffer for kTrianglesPerVertex times as
  /// many); the next extract() fills them. Throws std::runtime_error beyond kMaxBufferBytes.
  void setVertexCapacity(std::size_t vertices);
  /// The smallest doubling of the capacities that holds the last extraction's generated counts
  /// (waits for them), within kMaxBufferBytes; false when none does (the buffers stay).
  bool growToFit();

  int samplesPerAxis() const { return n_; }
  std::size_t vertexCapacity() const { return vertexCapacity_; }
  std::size_t triangleCapacity() const { return triangleCapacity_; }
  std::size_t bufferBytes() const;     ///< GPU memory of buffers, texture and index map
  VertexPlacement placement() const { return placement_; }

 private:
  /// What the last extraction made and stored: on the geometry-shader path its transform-feedback
  /// queries, on the compute path its counters, copied after it and fenced.
  struct Counts {
    std::size_t verticesMade = 0, verticesStored = 0, trianglesMade = 0, trianglesStored = 0;
  };
  /// The counts, waiting for them with `wait`, otherwise nullopt while the GPU has not finished.
  std::optional<Counts> counts(bool wait) const;
  void runGeometryShaderPasses();
  void runComputePasses();

  int n_ = 0, blocks_ = 0;
  ExtractionPath path_ = kDefaultExtraction;
  VertexPlacement placement_ = kDefaultPlacement;
  NormalSource normals_ = NormalSource::LatticeGradient;
  std::size_t vertexCapacity_ = 0, triangleCapacity_ = 0;
  glm::vec3 origin_{0.0f};
  float cellSize_ = 0.0f;
  bool uploaded_ = false;  ///< the texture holds a lattice (uploaded or filled on the GPU)
  std::size_t uploads_ = 0, gpuFills_ = 0;

  void setLatticeFrame(glm::dvec3 origin, double cellSize);

  gpu::Program classify_, vertices_, indexMap_, quads_;
  gpu::Texture field_, indices_;
  gpu::Buffer activeBlocks_, patchTable_, drawCommand_, vertexCounter_, vertexBuffer_, meshBuffer_;
  gpu::TransformFeedback vertexFeedback_, meshFeedback_;
  gpu::VertexArray emptyVao_, meshVao_;
  /// Bound while passes 2 and 4 draw with the rasteriser discarding: a draw needs a complete
  /// framebuffer even then, and a surfaceless EGL context has no default one
  /// (GL_INVALID_FRAMEBUFFER_OPERATION, nothing extracted), so this one has no attachments and a
  /// 1×1 default size (GL 4.3).
  gpu::Framebuffer discardTarget_;
  gpu::Query vertexGenerated_, vertexWritten_, meshGenerated_, meshWritten_, timerStart_, timerStop_;
  // Compute path: the mesh's draw command and triangle counter, their copy with the vertex counter
  // for read-back, and the fence after the copy; the instance count in the command.
  gpu::Buffer meshCounts_, countsCopy_;
  mutable gpu::Buffer drawCommands_;  ///< draw() makes a command at an instance count's first use
  gpu::Fence countsReady_;
  mutable std::vector<int> slotInstances_;  ///< the instance count of each draw command in drawCommands_
  /// The draw command for `instances` (made at its first use).
  std::size_t commandSlot(int instances) const;
  std::size_t extractedVertexCapacity_ = 0;  ///< the vertex buffer's capacity at the last compute extraction
};

}  // namespace tallow::geometry
