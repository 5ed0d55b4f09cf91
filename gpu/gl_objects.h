#pragma once
// Move-only owners of OpenGL names (buffers, textures, framebuffers, vertex arrays, queries,
// transform feedback objects): copy is deleted, moves are noexcept, the destructor deletes.
// Everything uses GL 4.5 direct state access, so creating or filling an object never disturbs
// the bindings of the pass that is running.
#include <glad/gl.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace tallow::gpu {

/// The driver answered an allocation (a buffer's or texture's storage) with GL_OUT_OF_MEMORY.
/// what() is one line naming the object and its size, e.g. `GPU out of memory allocating a
/// 4096x4096x8 GL_RGBA32F 2D array texture (2.7 GiB)`.
class GpuOutOfMemory : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
/// Owns one GL name; Traits::destroy(GLuint) deletes it.
template <class Traits>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
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
    if (id_) Traits::destroy(id_);
    id_ = 0;
  }
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }

 private:
  GLuint id_ = 0;
};

struct BufferTraits { static void destroy(GLuint id) { glDeleteBuffers(1, &id); } };
struct TextureTraits { static void destroy(GLuint id) { glDeleteTextures(1, &id); } };
struct FramebufferTraits { static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); } };
struct VertexArrayTraits { static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); } };
struct QueryTraits { static void destroy(GLuint id) { glDeleteQueries(1, &id); } };
struct TransformFeedbackTraits { static void destroy(GLuint id) { glDeleteTransformFeedbacks(1, &id); } };
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

/// A G-buffer's target (the light, map and VPL-cube G-buffers): `position` and `normal` as colour
/// attachments 0 and 1 and `depth`, all layers; checked complete (`what` names it in the error), both
/// colours cleared to 0 and the depth to `clearDepth`, and bound for drawing.
Framebuffer boundGBuffer(const Texture& position, const Texture& normal, const Texture& depth, float clearDepth,
                         const std::string& what);

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

 private:
  GLsync sync_ = nullptr;
};

/// The end of a compute step: image units 0 … images − 1 and texture units 0 … textures − 1 left
/// unbound and no program in use, so that no binding leaks into the next pass.
void unbindComputeState(int images, int textures);

}  // namespace tallow::gpu
