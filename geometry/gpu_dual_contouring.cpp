#include "geometry/gpu_dual_contouring.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace tallow::geometry {
namespace {

constexpr GLuint kWorkGroup = 64;                        ///< local_size_x of both compute passes
constexpr int kVertexStride = 8 * sizeof(float);  ///< position, normal, cell, bits (int bits)
constexpr int kMeshStride = 7 * sizeof(float);    ///< position, normal, vertex index (int bits)
/// Compute path: quads.comp's MeshCounts (corners stored, 3 unused words, triangles made), padded to 8 words.
constexpr std::size_t kMeshCountsWords = 8;
/// Compute path: draw commands {count, instances, 0, 0}, one per instance count the callers draw
/// with (1, K maps, 6 cube faces, …), each command's count copied on the GPU after every extraction.
constexpr std::size_t kDrawCommandSlots = 8;
constexpr std::size_t kDrawCommandBytes = 4 * sizeof(GLuint);
/// Compute path's read-back copy: vertices made, corners drawn, triangles made.
constexpr std::size_t kCountsCopyWords = 4;
constexpr GLuint kPointsPerBlock = GpuDualContouring::kBlockCells * GpuDualContouring::kBlockCells *
                                   GpuDualContouring::kBlockCells;

std::string blockDefine() { return "BLOCK_CELLS " + std::to_string(GpuDualContouring::kBlockCells); }

GLuint groupsFor(std::size_t items) { return static_cast<GLuint>((items + kWorkGroup - 1) / kWorkGroup); }

/// Bytes of the vertex and triangle buffers for `vertices` (kTrianglesPerVertex triangles each).
std::size_t outputBytes(std::size_t vertices) {
  return vertices * kVertexStride + GpuDualContouring::kTrianglesPerVertex * vertices * 3 * kMeshStride;
}

}  // namespace

GpuDualContouring::GpuDualContouring(const gpu::ShaderLibrary& library, int samplesPerAxis, VertexPlacement placement,
                                     NormalSource normals, ExtractionPath path)
    : n_(samplesPerAxis), path_(path), placement_(placement), normals_(normals) {
  if (n_ < 2) throw std::runtime_error("GpuDualContouring: need at least 2 samples per axis, got " + std::to_string(n_));
  const std::size_t cells = static_cast<std::size_t>(n_ - 1);
  blocks_ = (n_ - 1 + kBlockCells - 1) / kBlockCells;
  const std::size_t vertices = std::min(kMaxPatchesPerCell * cells * cells * cells, kVerticesPerFaceCell * cells * cells);
  if (outputBytes(vertices) > kMaxBufferBytes)
    throw std::runtime_error("GpuDualContouring: " + std::to_string(n_) + "^3 lattice needs " +
                             std::to_string(outputBytes(vertices) >> 20) + " MiB of buffers, over the " +
                             std::to_string(kMaxBufferBytes >> 20) + " MiB cap");

  const std::vector<std::string> defines{blockDefine()};
  std::vector<std::string> vertexDefines = defines;
  if (placement_ == VertexPlacement::Qef) vertexDefines.emplace_back("DC_QEF");
  if (normals_ == NormalSource::BlobGradient) vertexDefines.emplace_back("DC_BLOB_NORMALS");
  if (normals_ == NormalSource::CandleGradient) vertexDefines.emplace_back("DC_CANDLE_NORMALS");
  const bool compute = path_ == ExtractionPath::Compute;
  classify_ = gpu::Program(library, {{{GL_COMPUTE_SHADER, "dual_contouring/classify.comp"}}, defines});
  if (compute) {
    vertices_ = gpu::Program(library, {{{GL_COMPUTE_SHADER, "dual_contouring/vertices.comp"}}, vertexDefines});
    quads_ = gpu::Program(library, {{{GL_COMPUTE_SHADER, "dual_contouring/quads.comp"}}, defines});
  } else {
    vertices_ = gpu::Program(library, {{{GL_VERTEX_SHADER, "dual_contouring/cells.vert"},
                                        {GL_GEOMETRY_SHADER, "dual_contouring/vertices.geom"}},
                                       vertexDefines, {"tfPosition", "tfNormal", "tfCell", "tfBits"}});
    indexMap_ = gpu::Program(library, {{{GL_COMPUTE_SHADER, "dual_contouring/index_map.comp"}}, defines});
    quads_ = gpu::Program(library, {{{GL_VERTEX_SHADER, "dual_contouring/cells.vert"},
                                     {GL_GEOMETRY_SHADER, "dual_contouring/quads.geom"}},
                                    defines, {"tfPosition", "tfNormal", "tfVertex"}});
  }
  // The patches of every sign configuration, by the shaders' own cellPatches(): built once here.
  patchTable_ = gpu::Buffer(256 * sizeof(GLuint));
  {
    gpu::Program table(library, {{{GL_COMPUTE_SHADER, "dual_contouring/patch_table.comp"}}, defines});
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, patchTable_.id());
    table.use();
    glDispatchCompute(256 / kWorkGroup, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(0);
  }

  glNamedFramebufferParameteri(discardTarget_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
  glNamedFramebufferParameteri(discardTarget_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
  discardTarget_.checkComplete("dual contouring's attachment-less framebuffer");
  field_ = gpu::Texture::create3D(GL_R32F, n_, n_, n_);
  field_.setFilter(GL_LINEAR, GL_LINEAR);
  field_.setWrap(GL_CLAMP_TO_EDGE);
  indices_ = gpu::Texture::create3D(GL_R32I, n_ - 1, n_ - 1, n_ - 1);
  activeBlocks_ = gpu::Buffer(blockCount() * sizeof(GLuint));
  drawCommand_ = gpu::Buffer(4 * sizeof(GLuint));
  vertexCounter_ = gpu::Buffer(4 * sizeof(GLuint));
  vertexGenerated_ = gpu::Query(GL_PRIMITIVES_GENERATED);
  vertexWritten_ = gpu::Query(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  meshGenerated_ = gpu::Query(GL_PRIMITIVES_GENERATED);
  meshWritten_ = gpu::Query(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  timerStart_ = gpu::Query(GL_TIMESTAMP);
  timerStop_ = gpu::Query(GL_TIMESTAMP);
  meshCounts_ = gpu::Buffer(kMeshCountsWords * sizeof(GLuint));
  drawCommands_ = gpu::Buffer(kDrawCommandSlots * kDrawCommandBytes);
  countsCopy_ = gpu::Buffer(kCountsCopyWords * sizeof(GLuint));

  for (gpu::Program* p : {&classify_, &vertices_, &quads_}) {
    p->set("uField", 0);
    p->set("uSamples", n_);
    p->set("uBlocks", blocks_);
  }
  if (!compute) indexMap_.set("uSamples", n_);
  setVertexCapacity(vertices);
}

void GpuDualContouring::setVertexCapacity(std::size_t vertices) {
  if (vertices == 0 || outputBytes(vertices) > kMaxBufferBytes)
    throw std::runtime_error("GpuDualContouring: buffers for " + std::to_string(vertices) + " vertices exceed the " +
                             std::to_string(kMaxBufferBytes >> 20) + " MiB cap");
  vertexCapacity_ = vertices;
  triangleCapacity_ = kTrianglesPerVertex * vertices;
  vertexBuffer_ = gpu::Buffer(vertexCapacity_ * kVertexStride);
  meshBuffer_ = gpu::Buffer(triangleCapacity_ * 3 * kMeshStride);
  vertexFeedback_.bindBuffer(0, vertexBuffer_);
  meshFeedback_.bindBuffer(0, meshBuffer_);
  meshVao_.setAttribute(0, meshBuffer_, 0, kMeshStride, 3);
  meshVao_.setAttribute(1, meshBuffer_, 3 * sizeof(float), kMeshStride, 3);
  for (gpu::Program* p : {&indexMap_, &quads_, &vertices_})
    if (p->id() != 0 && p->location("uCapacity") >= 0)
      glProgramUniform1ui(p->id(), p->location("uCapacity"), static_cast<GLuint>(vertexCapacity_));
  if (path_ == ExtractionPath::Compute)
    glProgramUniform1ui(quads_.id(), quads_.location("uTriangleCapacity"), static_cast<GLuint>(triangleCapacity_));
}

std::optional<GpuDualContouring::Counts> GpuDualContouring::counts(bool wait) const {
  if (path_ == ExtractionPath::Compute) {
    if (countsReady_.empty()) return Counts{};
    if (!wait && !countsReady_.signaled()) return std::nullopt;
    countsReady_.wait();
    std::array<GLuint, kCountsCopyWords> c{};
    countsCopy_.download(0, sizeof(c), c.data());
    // c: vertices made, corners drawn, triangles made (vertices.comp, quads.comp).
    return Counts{c[0], std::min<std::size_t>(c[0], extractedVertexCapacity_), c[2], c[1] / 3};
  }
  for (const gpu::Query* q : {&vertexGenerated_, &vertexWritten_, &meshGenerated_, &meshWritten_})
    if (!wait && !q->resultAvailable()) return std::nullopt;
  return Counts{vertexGenerated_.result(), vertexWritten_.result(), meshGenerated_.result(), meshWritten_.result()};
}

std::optional<bool> GpuDualContouring::overflowed(bool wait) const {
  const std::optional<Counts> c = counts(wait);
  if (!c) return std::nullopt;
  return c->verticesMade > c->verticesStored || c->trianglesMade > c->trianglesStored;
}

std::size_t GpuDualContouring::generatedVertices() const { return counts(true)->verticesMade; }
std::size_t GpuDualContouring::generatedTriangles() const { return counts(true)->trianglesMade; }

bool GpuDualContouring::growToFit() {
  // The triangles are counted only as far as the vertices they index were stored: after a vertex
  // overflow the triangle count is a lower bound, so the next extraction is checked again.
  const std::size_t need = std::max(generatedVertices(), (generatedTriangles() + kTrianglesPerVertex - 1) / kTrianglesPerVertex);
  std::size_t vertices = vertexCapacity_;
  while (vertices < need) vertices *= 2;
  if (vertices == vertexCapacity_ || outputBytes(vertices) > kMaxBufferBytes) return false;
  setVertexCapacity(vertices);
  return true;
}

void GpuDualContouring::upload(const SampledLattice& lattice) {
  if (lattice.n != n_)
    throw std::runtime_error("GpuDualContouring::upload: lattice has " + std::to_string(lattice.n) +
                             " samples per axis, built for " + std::to_string(n_));
  glTextureSubImage3D(field_.id(), 0, 0, 0, 0, n_, n_, n_, GL_RED, GL_FLOAT, lattice.values.data());
  setLatticeFrame(lattice.origin, lattice.cellSize);
  ++uploads_;
}

void GpuDualContouring::fillOnGpu(gpu::Program& fill, glm::dvec3 origin, double cellSize) {
  constexpr GLuint kFillGroup = 4;  // local_size of the fill programs (fields/lattice.comp): 4³
  setLatticeFrame(origin, cellSize);
  fill.set("uSamples", n_);
  fill.set("uOrigin", origin_);
  fill.set("uCellSize", cellSize_);
  glBindImageTexture(0, field_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
  fill.use();
  const GLuint groups = (static_cast<GLuint>(n_) + kFillGroup - 1) / kFillGroup;
  glDispatchCompute(groups, groups, groups);
  glUseProgram(0);
  // extract() reads the texture through samplers (texelFetch, texture); readLattice() and a later
  // upload() through texture commands.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  ++gpuFills_;
}

void GpuDualContouring::setLatticeFrame(glm::dvec3 origin, double cellSize) {
  origin_ = glm::vec3(origin);
  cellSize_ = static_cast<float>(cellSize);
  for (gpu::Program* p : {&vertices_, &quads_}) {
    p->set("uOrigin", origin_);
    p->set("uCellSize", cellSize_);
  }
  uploaded_ = true;
}

std::vector<float> GpuDualContouring::readLattice() const {
  const std::size_t count = static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_) * static_cast<std::size_t>(n_);
  std::vector<float> values(count);
  glGetTextureImage(field_.id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(count * sizeof(float)), values.data());
  return values;
}

void GpuDualContouring::extract() {
  if (!uploaded_) throw std::runtime_error("GpuDualContouring::extract: upload() or fillOnGpu() a lattice first");
  glQueryCounter(timerStart_.id(), GL_TIMESTAMP);
  // Geometry shaders draw {count, instances, first, base}; compute dispatches from its second word
  // on, {instances, 1, 1}.
  const bool compute = path_ == ExtractionPath::Compute;
  const std::array<GLuint, 4> drawReset{kPointsPerBlock, 0, compute ? 1u : 0u, compute ? 1u : 0u};
  const std::array<GLuint, 4> counterReset{0, 0, 1, 1};  // vertices, groups x, y, z
  drawCommand_.upload(0, sizeof(drawReset), drawReset.data());
  vertexCounter_.upload(0, sizeof(counterReset), counterReset.data());
  field_.bind(0);

  // 1. Classify blocks.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, activeBlocks_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, drawCommand_.id());
  classify_.use();
  glDispatchCompute(groupsFor(blockCount()), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);

  if (compute)
    runComputePasses();
  else
    runGeometryShaderPasses();
  glQueryCounter(timerStop_.id(), GL_TIMESTAMP);
}

void GpuDualContouring::runComputePasses() {
  extractedVertexCapacity_ = vertexCapacity_;  // what "stored" means for these counts, whatever is resized later
  const std::array<GLuint, kMeshCountsWords> countsReset{};
  meshCounts_.upload(0, sizeof(countsReset), countsReset.data());
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, drawCommand_.id());
  constexpr GLintptr kBlocksWord = sizeof(GLuint);  // {instances, 1, 1}: one work group per active block

  // 2. Vertices, and each cell's first one into the index map.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, vertexCounter_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, vertexBuffer_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, patchTable_.id());
  glBindImageTexture(0, indices_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32I);
  vertices_.use();
  glDispatchComputeIndirect(kBlocksWord);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  // 4. Triangles → mesh buffer, and the draw command's vertex count.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, meshBuffer_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, meshCounts_.id());
  glBindImageTexture(0, indices_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32I);
  quads_.use();
  glDispatchComputeIndirect(kBlocksWord);
  glMemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                  GL_BUFFER_UPDATE_BARRIER_BIT);

  // Every draw command's vertex count, on the GPU.
  for (std::size_t slot = 0; slot < slotInstances_.size(); ++slot)
    glCopyNamedBufferSubData(meshCounts_.id(), drawCommands_.id(), 0, static_cast<GLintptr>(slot * kDrawCommandBytes),
                             sizeof(GLuint));
  // The counts for read-back (tests, stats, overflow): copied, fenced, read when the fence passed.
  glCopyNamedBufferSubData(vertexCounter_.id(), countsCopy_.id(), 0, 0, sizeof(GLuint));
  glCopyNamedBufferSubData(meshCounts_.id(), countsCopy_.id(), 0, sizeof(GLuint), sizeof(GLuint));
  glCopyNamedBufferSubData(meshCounts_.id(), countsCopy_.id(), 4 * sizeof(GLuint), 2 * sizeof(GLuint), sizeof(GLuint));
  countsReady_ = gpu::Fence::insert();
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  gpu::unbindComputeState(1, 1);
}

void GpuDualContouring::runGeometryShaderPasses() {
  // 2. Vertices of the active blocks' sign-changing cells.
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, discardTarget_.id());
  glEnable(GL_RASTERIZER_DISCARD);
  emptyVao_.bind();
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, drawCommand_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, vertexCounter_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, patchTable_.id());
  vertices_.use();
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, vertexFeedback_.id());
  glBeginQuery(GL_PRIMITIVES_GENERATED, vertexGenerated_.id());
  glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, vertexWritten_.id());
  glBeginTransformFeedback(GL_POINTS);
  glDrawArraysIndirect(GL_POINTS, nullptr);
  glEndTransformFeedback();
  glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  glEndQuery(GL_PRIMITIVES_GENERATED);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);

  // 3. Index map, one invocation per captured vertex (indirect dispatch from the counter).
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, vertexBuffer_.id());
  glBindImageTexture(0, indices_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32I);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, vertexCounter_.id());
  indexMap_.use();
  glDispatchComputeIndirect(sizeof(GLuint));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

  // 4. Quads of the sign-changing edges → mesh buffer.
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, activeBlocks_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, vertexCounter_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, vertexBuffer_.id());
  glBindImageTexture(0, indices_.id(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32I);
  quads_.use();
  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, meshFeedback_.id());
  glBeginQuery(GL_PRIMITIVES_GENERATED, meshGenerated_.id());
  glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, meshWritten_.id());
  glBeginTransformFeedback(GL_TRIANGLES);
  glDrawArraysIndirect(GL_POINTS, nullptr);
  glEndTransformFeedback();
  glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
  glEndQuery(GL_PRIMITIVES_GENERATED);

  glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
  glBindVertexArray(0);
  glDisable(GL_RASTERIZER_DISCARD);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);  // the default, as every pass leaves it (asked for nothing)
}

void GpuDualContouring::draw(int instances) const {
  meshVao_.bind();
  if (path_ == ExtractionPath::Compute) {
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, drawCommands_.id());
    glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(commandSlot(instances) * kDrawCommandBytes));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  } else {
    glDrawTransformFeedbackInstanced(GL_TRIANGLES, meshFeedback_.id(), instances);
  }
  glBindVertexArray(0);
}

std::size_t GpuDualContouring::commandSlot(int instances) const {
  const auto found = std::find(slotInstances_.begin(), slotInstances_.end(), instances);
  if (found != slotInstances_.end()) return static_cast<std::size_t>(found - slotInstances_.begin());
  // A new instance count: its command, once; later extractions copy its count with the others'.
  // Past the slots (never so far: 1, K and 6 are the counts drawn), the last slot is rewritten.
  const std::size_t slot = std::min(slotInstances_.size(), kDrawCommandSlots - 1);
  if (slot == slotInstances_.size()) slotInstances_.push_back(instances);
  slotInstances_[slot] = instances;
  const std::array<GLuint, 4> command{0, static_cast<GLuint>(instances), 0, 0};
  drawCommands_.upload(slot * kDrawCommandBytes, sizeof(command), command.data());
  glCopyNamedBufferSubData(meshCounts_.id(), drawCommands_.id(), 0, static_cast<GLintptr>(slot * kDrawCommandBytes),
                           sizeof(GLuint));
  return slot;
}

void GpuDualContouring::checkOverflow() const {
  const Counts c = *counts(true);
  if (c.verticesMade > c.verticesStored)
    throw std::runtime_error("GpuDualContouring: vertex buffer overflow (" + std::to_string(c.verticesMade) +
                             " vertices > capacity " + std::to_string(vertexCapacity_) + ")");
  if (c.trianglesMade > c.trianglesStored)
    throw std::runtime_error("GpuDualContouring: mesh buffer overflow (" + std::to_string(c.trianglesMade) +
                             " triangles > capacity " + std::to_string(triangleCapacity_) + ")");
}

std::size_t GpuDualContouring::triangleCount() const { return counts(true)->trianglesStored; }
std::optional<std::size_t> GpuDualContouring::triangleCountIfAvailable() const {
  const std::optional<Counts> c = counts(false);
  if (!c) return std::nullopt;
  return c->trianglesStored;
}
std::size_t GpuDualContouring::vertexCount() const { return counts(true)->verticesStored; }
double GpuDualContouring::lastExtractionMs() const {
  return static_cast<double>(timerStop_.result() - timerStart_.result()) * 1e-6;
}

std::size_t GpuDualContouring::activeBlockCount() const {
  std::array<GLuint, 4> command{};
  drawCommand_.download(0, sizeof(command), command.data());
  return command[1];
}

std::size_t GpuDualContouring::bufferBytes() const {
  return activeBlocks_.size() + patchTable_.size() + drawCommand_.size() + vertexCounter_.size() + vertexBuffer_.size() +
         meshBuffer_.size() + meshCounts_.size() + countsCopy_.size() + drawCommands_.size() + field_.bytes() + indices_.bytes();
}

TriangleMesh GpuDualContouring::readBack() const {
  checkOverflow();
  const std::size_t triangles = triangleCount();
  std::vector<float> data(triangles * 3 * 7);
  if (!data.empty()) meshBuffer_.download(0, data.size() * sizeof(float), data.data());
  // Weld by vertex-buffer index, which every triangle corner carries: exactly the sharing the quads
  // were built with, even where two patch vertices happen to coincide.
  TriangleMesh mesh;
  std::map<std::int32_t, std::uint32_t> welded;
  mesh.triangles.resize(triangles);
  for (std::size_t t = 0; t < triangles; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const float* v = &data[(3 * t + k) * 7];
      std::int32_t index = 0;
      std::memcpy(&index, &v[6], sizeof(index));
      const auto [it, inserted] = welded.try_emplace(index, static_cast<std::uint32_t>(mesh.positions.size()));
      if (inserted) {
        mesh.positions.emplace_back(v[0], v[1], v[2]);
        mesh.normals.emplace_back(v[3], v[4], v[5]);
      }
      mesh.triangles[t][k] = it->second;
    }
  return mesh;
}

}  // namespace tallow::geometry
