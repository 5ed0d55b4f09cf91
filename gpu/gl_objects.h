#pragma once
// Move-only owners of OpenGL names (buffers, textures, framebuffers, vertex arrays, queries,
// transform feedback objects): copy is deleted, moves are noexcept, the destructor deletes.
// Everything uses GL 4.5 direct state access, so creating or filling an object never disturbs
// the bindings of the pass that is running.
#include <glad/gl.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tallow::gpu {

/// The driver answered an allocation (a buffer's or texture's storage) with GL_OUT_OF_MEMORY.
/// what() is one line naming the object and its size, e.g. `GPU out of memory allocating a
/// 4096x4096x8 GL_RGBA32F 2D array texture (2.7 GiB)`.
class GpuOutOfMemory : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The kinds of GL object the owners below hold, for GlObjectTally.
enum class GlObjectKind { Buffer, Texture, Framebuffer, VertexArray, Query, TransformFeedback, Sampler, Count };

/// How many GL objects of each kind the owners below have created and deleted in this process:
/// what a test of "nothing created per frame" (issue 39) compares before and after a frame.
struct GlObjectTally {
  std::size_t created[static_cast<int>(GlObjectKind::Count)] = {};
  std::size_t deleted[static_cast<int>(GlObjectKind::Count)] = {};
  std::size_t createdOf(GlObjectKind k) const { return created[static_cast<int>(k)]; }
  std::size_t deletedOf(GlObjectKind k) const { return deleted[static_cast<int>(k)]; }
  /// Creations and deletions of every kind since `before`, as "framebuffer +2 -2, buffer +1 -1"
  /// (empty when none).
  std::string since(const GlObjectTally& before) const;
};
/// The tally so far.
GlObjectTally glObjectTally();

namespace detail {
void countGlObject(GlObjectKind kind, bool created);

/// Owns one GL name; Traits::destroy(GLuint) deletes it.
template <class Traits>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {
    if (id_) countGlObject(Traits::kKind, true);
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  GlName(GlName&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlName& operator=(GlName&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  ~GlName() { reset(); }
  void reset() {
    if (id_) {
      Traits::destroy(id_);
      countGlObject(Traits::kKind, false);
    }
    id_ = 0;
  }
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }

 private:
  GLuint id_ = 0;
};

struct BufferTraits {
  static constexpr GlObjectKind kKind = GlObjectKind::Buffer;
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
  static constexpr GlObjectKind kKind = GlObjectKind::Texture;
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
  static constexpr GlObjectKind kKind = GlObjectKind::Framebuffer;
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct SamplerTraits {
  static constexpr GlObjectKind kKind = GlObjectKind::Sampler;
  static void destroy(GLuint id) { glDeleteSamplers(1, &id); }
};
struct VertexArrayTraits {
  static constexpr GlObjectKind kKind = GlObjectKind::VertexArray;
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct QueryTraits {
  static constexpr GlObjectKind kKind = GlObjectKind::Query;
  static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct TransformFeedbackTraits {
  static constexpr GlObjectKind kKind = GlObjectKind::TransformFeedback;
  static void destroy(GLuint id) { glDeleteTransformFeedbacks(1, &id); }
};
}  // namespace detail

class Buffer {
 public:
  Buffer() = default;
  /// Immutable storage (glNamedBufferStorage) of `bytes`, optionally filled from `data`. Throws
  /// GpuOutOfMemory when the driver has no room for it, std::runtime_error on any other GL error.
  Buffer(std::size_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
  GLuint id() const { return name_.id(); }
  std::size_t size() const { return size_; }
  void upload(std::size_t offset, std::size_t bytes, const void* data);
  void download(std::size_t offset, std::size_t bytes, void* out) const;
  /// Holds `bytes` from `data` afterwards: uploaded in place when it has that size already (the
  /// per-frame path: no object created, issue 39), otherwise made anew with the default flags.
  void assign(std::size_t bytes, const void* data);

 private:
  detail::GlName<detail::BufferTraits> name_;
  std::size_t size_ = 0;
};

/// A texture of any target with immutable storage. The factories throw GpuOutOfMemory when the
/// driver has no room for the storage, std::runtime_error on any other GL error it raises.
class Texture {
 public:
  Texture() = default;
  static Texture create2D(GLenum format, int width, int height, int levels = 1);
  static Texture create2DArray(GLenum format, int width, int height, int layers, int levels = 1);
  static Texture create3D(GLenum format, int width, int height, int depth, int levels = 1);
  static Texture createCube(GLenum format, int size, int levels = 1);
  /// `cubes` cube maps, i.e. 6 × cubes layer-faces.
  static Texture createCubeArray(GLenum format, int size, int cubes, int levels = 1);

  GLuint id() const { return name_.id(); }
  /// Unique among the textures this process made (never reused, unlike GL's names): what tells a
  /// TargetFramebuffer that an attachment is another texture under a recycled name.
  std::uint64_t serial() const { return serial_; }
  GLenum target() const { return target_; }
  GLenum format() const { return format_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int depth() const { return depth_; }  ///< depth (3D), layers (arrays), layer-faces (cube arrays), 6 (cube)
  int levels() const { return levels_; }
  std::size_t bytes() const;  ///< GPU memory of all levels, estimated from the format
  /// bytes() of a texture of this shape before it exists (the memory budget's figure).
  static std::size_t bytesFor(GLenum target, GLenum format, int width, int height, int depth, int levels);

  void setFilter(GLenum minFilter, GLenum magFilter);
  void setWrap(GLenum wrap);
  void setBorderColor(float r, float g, float b, float a);
  /// Depth textures: sample with hardware comparison (sampler*Shadow) when `enabled`.
  void setDepthCompare(bool enabled);
  void generateMipmaps();
  void bind(GLuint unit) const { glBindTextureUnit(unit, name_.id()); }

 private:
  static Texture make(GLenum target, GLenum format, int w, int h, int d, int levels);
  detail::GlName<detail::TextureTraits> name_;
  std::uint64_t serial_ = 0;
  GLenum target_ = 0, format_ = 0;
  int width_ = 0, height_ = 0, depth_ = 1, levels_ = 1;
};

class Framebuffer {
 public:
  Framebuffer();
  GLuint id() const { return name_.id(); }
  /// Attaches `level` of `texture`; `layer` < 0 attaches all layers (layered rendering).
  void attachColor(int index, const Texture& texture, int level = 0, int layer = -1);
  void attachDepth(const Texture& texture, int level = 0, int layer = -1);
  /// Draws into colour attachments 0..count-1 (none: depth only).
  void setDrawBuffers(int count);
  /// Throws std::runtime_error naming `what` and the status when incomplete.
  void checkComplete(const std::string& what) const;
  void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, name_.id()); }

 private:
  detail::GlName<detail::FramebufferTraits> name_;
};

/// A pass's render target, made once and pointed at the textures the pass draws into: the same
/// attachments again cost nothing, other ones (a swap, a reallocation) are re-attached and checked
/// once — no GL object is created or deleted per frame (issue 39). An attached texture stays alive
/// in the driver after its owner drops it, so an owner that frees its textures for good calls
/// release().
class TargetFramebuffer {
 public:
  struct Attachment {
    const Texture* texture = nullptr;  ///< null: nothing at this attachment point
    int level = 0;
    int layer = -1;  ///< < 0: all layers (layered rendering)
  };
  /// Colour attachments 0..colours.size() − 1 (drawn into, in that order) and `depth`; checked
  /// complete when anything changed (`what` names the target in the error). Returns the target.
  const Framebuffer& attach(std::initializer_list<Attachment> colours, Attachment depth, const std::string& what);
  /// Detaches everything (the framebuffer itself stays).
  void release();

 private:
  struct Bound {
    GLuint id = 0;
    std::uint64_t serial = 0;
    int level = 0, layer = -1;
    bool operator==(const Bound& o) const {
      return id == o.id && serial == o.serial && level == o.level && layer == o.layer;
    }
  };
  std::unique_ptr<Framebuffer> fb_;  ///< made at the first attach (a GL context is current then)
  std::vector<Bound> colours_;
  Bound depth_;
};

/// A G-buffer's target (the light, map and VPL-cube G-buffers): `position` and `normal` as colour
/// attachments 0 and 1 and `depth`, all layers, in `target`; checked complete when they changed
/// (`what` names it in the error), both colours cleared to 0 and the depth to `clearDepth`, and bound
/// for drawing.
void bindGBuffer(TargetFramebuffer& target, const Texture& position, const Texture& normal, const Texture& depth,
                 float clearDepth, const std::string& what);

class VertexArray {
 public:
  VertexArray();
  GLuint id() const { return name_.id(); }
  /// Float attribute `index` read from `buffer` at `offset` with `stride`, `components` wide.
  void setAttribute(GLuint index, const Buffer& buffer, std::size_t offset, int stride, int components);
  void setIndexBuffer(const Buffer& buffer);
  void bind() const { glBindVertexArray(name_.id()); }

 private:
  detail::GlName<detail::VertexArrayTraits> name_;
};

class Query {
 public:
  Query() = default;
  explicit Query(GLenum target);
  GLuint id() const { return name_.id(); }
  GLenum target() const { return target_; }
  bool resultAvailable() const;
  GLuint64 result() const;  ///< waits for the result

 private:
  detail::GlName<detail::QueryTraits> name_;
  GLenum target_ = 0;
};

/// A sampler object: how a unit samples its texture, overriding the texture's own parameters (a
/// depth texture read as values where its own compare mode makes it a shadow sampler).
class Sampler {
 public:
  Sampler();
  GLuint id() const { return name_.id(); }
  void set(GLenum parameter, GLint value) { glSamplerParameteri(name_.id(), parameter, value); }
  void bind(GLuint unit) const { glBindSampler(unit, name_.id()); }
  /// Back to the texture's own parameters on `unit`.
  static void unbind(GLuint unit) { glBindSampler(unit, 0); }

 private:
  detail::GlName<detail::SamplerTraits> name_;
};

class TransformFeedback {
 public:
  TransformFeedback();
  GLuint id() const { return name_.id(); }
  void bindBuffer(GLuint index, const Buffer& buffer);

 private:
  detail::GlName<detail::TransformFeedbackTraits> name_;
};

/// A fence after the commands issued so far (glFenceSync): the CPU asks, without waiting, whether
/// the GPU has finished them, before reading back what they wrote (no stall).
class Fence {
 public:
  Fence() = default;
  static Fence insert();
  Fence(Fence&& o) noexcept : sync_(o.sync_) { o.sync_ = nullptr; }
  Fence& operator=(Fence&& o) noexcept;
  Fence(const Fence&) = delete;
  Fence& operator=(const Fence&) = delete;
  ~Fence();
  bool empty() const { return sync_ == nullptr; }
  /// True once the GPU passed the fence; never waits (flushes, so that it will pass).
  bool signaled() const;
  /// Waits until the GPU has passed the fence (at once if it has).
  void wait() const;

 private:
  GLsync sync_ = nullptr;
};

/// The end of a compute step: image units 0 … images − 1 and texture units 0 … textures − 1 left
/// unbound and no program in use, so that no binding leaks into the next pass.
void unbindComputeState(int images, int textures);

}  // namespace tallow::gpu
