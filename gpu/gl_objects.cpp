#include "gpu/gl_objects.h"

#include <atomic>
#include <stdexcept>

#include "gpu/byte_size.h"

namespace tallow::gpu {

namespace {
constexpr int kKinds = static_cast<int>(GlObjectKind::Count);
// Relaxed atomics: a count, read by tests between frames; GL objects are made on one thread, but a
// worker may release one.
std::atomic<std::size_t> gCreated[kKinds];
std::atomic<std::size_t> gDeleted[kKinds];
constexpr const char* kKindNames[kKinds] = {"buffer", "texture", "framebuffer", "vertex array", "query",
                                            "transform feedback", "sampler"};
}  // namespace

void detail::countGlObject(GlObjectKind kind, bool created) {
  (created ? gCreated : gDeleted)[static_cast<int>(kind)].fetch_add(1, std::memory_order_relaxed);
}

GlObjectTally glObjectTally() {
  GlObjectTally t;
  for (int k = 0; k < kKinds; ++k) {
    t.created[k] = gCreated[k].load(std::memory_order_relaxed);
    t.deleted[k] = gDeleted[k].load(std::memory_order_relaxed);
  }
  return t;
}

std::string GlObjectTally::since(const GlObjectTally& before) const {
  std::string out;
  for (int k = 0; k < kKinds; ++k) {
    const std::size_t made = created[k] - before.created[k], gone = deleted[k] - before.deleted[k];
    if (made == 0 && gone == 0) continue;
    if (!out.empty()) out += ", ";
    out += std::string(kKindNames[k]) + " +" + std::to_string(made) + " -" + std::to_string(gone);
  }
  return out;
}

namespace {

/// GL keeps one pending flag per kind of error, so a few reads clear them all; the cap keeps a
/// lost context (which may report GL_CONTEXT_LOST on every call) from looping.
constexpr int kMaxPendingErrors = 16;

/// Errors raised before an allocation are not its own: they are dropped, so that the read after
/// it sees the allocation's error alone. Release builds look at nothing else, and debug builds
/// have printed them through KHR_debug already.
void clearPendingErrors() {
  for (int i = 0; i < kMaxPendingErrors && glGetError() != GL_NO_ERROR; ++i) {
  }
}

/// GL_OUT_OF_MEMORY after an allocation becomes GpuOutOfMemory, in every build: without it the
/// object would exist without storage and the failure would surface later as an incomplete
/// framebuffer or a black frame. Other errors keep their old course (checkLimits names the sizes
/// a driver refuses with GL_INVALID_VALUE before anything is allocated).
void checkAllocation(const std::string& what, std::size_t bytes) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  clearPendingErrors();
  if (error == GL_OUT_OF_MEMORY)
    throw GpuOutOfMemory("GPU out of memory allocating " + what + " (" + formatBytes(bytes) + ")");
}

const char* formatName(GLenum format) {
  switch (format) {
    case GL_R8: return "GL_R8";
    case GL_RG8: return "GL_RG8";
    case GL_RG8UI: return "GL_RG8UI";
    case GL_R16F: return "GL_R16F";
    case GL_RGBA8: return "GL_RGBA8";
    case GL_SRGB8_ALPHA8: return "GL_SRGB8_ALPHA8";
    case GL_R32F: return "GL_R32F";
    case GL_RG16F: return "GL_RG16F";
    case GL_R32UI: return "GL_R32UI";
    case GL_RGBA32UI: return "GL_RGBA32UI";
    case GL_R32I: return "GL_R32I";
    case GL_DEPTH_COMPONENT16: return "GL_DEPTH_COMPONENT16";
    case GL_DEPTH_COMPONENT24: return "GL_DEPTH_COMPONENT24";
    case GL_DEPTH_COMPONENT32F: return "GL_DEPTH_COMPONENT32F";
    case GL_DEPTH24_STENCIL8: return "GL_DEPTH24_STENCIL8";
    case GL_R11F_G11F_B10F: return "GL_R11F_G11F_B10F";
    case GL_RGBA16F: return "GL_RGBA16F";
    case GL_RG32F: return "GL_RG32F";
    case GL_RGB32F: return "GL_RGB32F";
    case GL_RGBA32F: return "GL_RGBA32F";
    default: return "format";
  }
}

const char* targetName(GLenum target) {
  switch (target) {
    case GL_TEXTURE_2D: return "2D texture";
    case GL_TEXTURE_2D_ARRAY: return "2D array texture";
    case GL_TEXTURE_3D: return "3D texture";
    case GL_TEXTURE_CUBE_MAP: return "cube map";
    case GL_TEXTURE_CUBE_MAP_ARRAY: return "cube map array";
    default: return "texture";
  }
}

}  // namespace

Buffer::Buffer(std::size_t bytes, const void* data, GLbitfield flags) : size_(bytes) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  name_ = detail::GlName<detail::BufferTraits>(id);
  clearPendingErrors();
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
  checkAllocation("a buffer", bytes);
}

void Buffer::upload(std::size_t offset, std::size_t bytes, const void* data) {
  glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

void Buffer::assign(std::size_t bytes, const void* data) {
  if (id() && size_ == bytes) {
    if (bytes > 0) upload(0, bytes, data);
    return;
  }
  *this = Buffer(bytes, data);
}

void Buffer::download(std::size_t offset, std::size_t bytes, void* out) const {
  glGetNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), out);
}

Texture Texture::make(GLenum target, GLenum format, int w, int h, int d, int levels) {
  Texture t;
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  t.name_ = detail::GlName<detail::TextureTraits>(id);
  static std::atomic<std::uint64_t> serials{0};
  t.serial_ = ++serials;
  t.target_ = target;
  t.format_ = format;
  t.width_ = w;
  t.height_ = h;
  t.depth_ = d;
  t.levels_ = levels;
  clearPendingErrors();
  switch (target) {
    case GL_TEXTURE_2D:
    case GL_TEXTURE_CUBE_MAP: glTextureStorage2D(id, levels, format, w, h); break;
    default: glTextureStorage3D(id, levels, format, w, h, d); break;
  }
  const int layers = target == GL_TEXTURE_CUBE_MAP ? 6 : d;
  // Appended piece by piece: `"x" + std::string&&` trips GCC 12's false -Wrestrict (bug 105651).
  std::string what = "a ";
  what += std::to_string(w);
  what += 'x';
  what += std::to_string(h);
  if (layers > 1) {
    what += 'x';
    what += std::to_string(layers);
  }
  what += ' ';
  what += formatName(format);
  what += ' ';
  what += targetName(target);
  checkAllocation(what, bytesFor(target, format, w, h, layers, levels));
  t.setFilter(levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR, GL_LINEAR);
  t.setWrap(GL_CLAMP_TO_EDGE);
  return t;
}

Texture Texture::create2D(GLenum format, int width, int height, int levels) {
  return make(GL_TEXTURE_2D, format, width, height, 1, levels);
}
Texture Texture::create2DArray(GLenum format, int width, int height, int layers, int levels) {
  return make(GL_TEXTURE_2D_ARRAY, format, width, height, layers, levels);
}
Texture Texture::create3D(GLenum format, int width, int height, int depth, int levels) {
  return make(GL_TEXTURE_3D, format, width, height, depth, levels);
}
Texture Texture::createCube(GLenum format, int size, int levels) {
  Texture t = make(GL_TEXTURE_CUBE_MAP, format, size, size, 1, levels);
  t.depth_ = 6;
  return t;
}
Texture Texture::createCubeArray(GLenum format, int size, int cubes, int levels) {
  return make(GL_TEXTURE_CUBE_MAP_ARRAY, format, size, size, 6 * cubes, levels);
}

namespace {
std::size_t bytesPerTexel(GLenum format) {
  switch (format) {
    case GL_R8: return 1;
    case GL_RG8: case GL_RG8UI: case GL_R16F: case GL_DEPTH_COMPONENT16: return 2;
    case GL_DEPTH_COMPONENT24: return 3;  // typically padded to 4
    case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_R32F: case GL_RG16F: case GL_R32UI: case GL_R32I:
    case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_R11F_G11F_B10F: return 4;
    case GL_RGBA16F: case GL_RG32F: return 8;
    case GL_RGB32F: return 12;
    case GL_RGBA32F: case GL_RGBA32UI: return 16;
    default: return 4;
  }
}
}  // namespace

std::size_t Texture::bytes() const { return bytesFor(target_, format_, width_, height_, depth_, levels_); }

std::size_t Texture::bytesFor(GLenum target, GLenum format, int width, int height, int depth, int levels) {
  std::size_t total = 0;
  std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height), d = static_cast<std::size_t>(depth);
  for (int level = 0; level < levels; ++level) {
    total += w * h * d * bytesPerTexel(format);
    w = w > 1 ? w / 2 : 1;
    h = h > 1 ? h / 2 : 1;
    if (target == GL_TEXTURE_3D) d = d > 1 ? d / 2 : 1;
  }
  return total;
}

void Texture::setFilter(GLenum minFilter, GLenum magFilter) {
  glTextureParameteri(id(), GL_TEXTURE_MIN_FILTER, static_cast<GLint>(minFilter));
  glTextureParameteri(id(), GL_TEXTURE_MAG_FILTER, static_cast<GLint>(magFilter));
}

void Texture::setWrap(GLenum wrap) {
  glTextureParameteri(id(), GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
  glTextureParameteri(id(), GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
  glTextureParameteri(id(), GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap));
}

void Texture::setBorderColor(float r, float g, float b, float a) {
  const float c[4] = {r, g, b, a};
  glTextureParameterfv(id(), GL_TEXTURE_BORDER_COLOR, c);
}

void Texture::setDepthCompare(bool enabled) {
  glTextureParameteri(id(), GL_TEXTURE_COMPARE_MODE, enabled ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
  glTextureParameteri(id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
}

void Texture::generateMipmaps() { glGenerateTextureMipmap(id()); }

Framebuffer::Framebuffer() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  name_ = detail::GlName<detail::FramebufferTraits>(id);
}

void Framebuffer::attachColor(int index, const Texture& texture, int level, int layer) {
  const GLenum point = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(index);
  if (layer < 0) glNamedFramebufferTexture(id(), point, texture.id(), level);
  else glNamedFramebufferTextureLayer(id(), point, texture.id(), level, layer);
}

void Framebuffer::attachDepth(const Texture& texture, int level, int layer) {
  if (layer < 0) glNamedFramebufferTexture(id(), GL_DEPTH_ATTACHMENT, texture.id(), level);
  else glNamedFramebufferTextureLayer(id(), GL_DEPTH_ATTACHMENT, texture.id(), level, layer);
}

void Framebuffer::setDrawBuffers(int count) {
  if (count == 0) {
    glNamedFramebufferDrawBuffer(id(), GL_NONE);
    glNamedFramebufferReadBuffer(id(), GL_NONE);
    return;
  }
  GLenum buffers[8];
  for (int i = 0; i < count && i < 8; ++i) buffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
  glNamedFramebufferDrawBuffers(id(), count, buffers);
  glNamedFramebufferReadBuffer(id(), GL_COLOR_ATTACHMENT0);
}

void Framebuffer::checkComplete(const std::string& what) const {
  const GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return;
  const char* text = "unknown status";
  switch (status) {
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: text = "incomplete attachment"; break;
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: text = "missing attachment"; break;
    case GL_FRAMEBUFFER_UNSUPPORTED: text = "unsupported format combination"; break;
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: text = "incomplete layer targets"; break;
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: text = "incomplete multisample"; break;
    default: break;
  }
  throw std::runtime_error(what + ": framebuffer incomplete (" + text + ")");
}

const Framebuffer& TargetFramebuffer::attach(std::initializer_list<Attachment> colours, Attachment depth,
                                             const std::string& what) {
  if (!fb_) fb_ = std::make_unique<Framebuffer>();
  const auto bound = [](const Attachment& a) {
    return a.texture ? Bound{a.texture->id(), a.texture->serial(), a.level, a.layer} : Bound{};
  };
  bool changed = colours.size() != colours_.size() || !(bound(depth) == depth_);
  for (std::size_t i = 0; !changed && i < colours.size(); ++i) changed = !(bound(colours.begin()[i]) == colours_[i]);
  if (!changed) return *fb_;
  // Detach colours no longer drawn, then point every attachment at its texture.
  for (std::size_t i = colours.size(); i < colours_.size(); ++i)
    glNamedFramebufferTexture(fb_->id(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), 0, 0);
  colours_.clear();
  int index = 0;
  for (const Attachment& a : colours) {
    if (a.texture) fb_->attachColor(index, *a.texture, a.level, a.layer);
    else glNamedFramebufferTexture(fb_->id(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(index), 0, 0);
    colours_.push_back(bound(a));
    ++index;
  }
  if (depth.texture) fb_->attachDepth(*depth.texture, depth.level, depth.layer);
  else glNamedFramebufferTexture(fb_->id(), GL_DEPTH_ATTACHMENT, 0, 0);
  depth_ = bound(depth);
  fb_->setDrawBuffers(static_cast<int>(colours.size()));
  fb_->checkComplete(what);
  return *fb_;
}

void TargetFramebuffer::release() {
  if (!fb_) return;
  for (std::size_t i = 0; i < colours_.size(); ++i)
    glNamedFramebufferTexture(fb_->id(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), 0, 0);
  glNamedFramebufferTexture(fb_->id(), GL_DEPTH_ATTACHMENT, 0, 0);
  colours_.clear();
  depth_ = Bound{};
}

void bindGBuffer(TargetFramebuffer& target, const Texture& position, const Texture& normal, const Texture& depth,
                 float clearDepth, const std::string& what) {
  const Framebuffer& fb = target.attach({{&position}, {&normal}}, {&depth}, what);
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(fb.id(), GL_COLOR, 0, zero);
  glClearNamedFramebufferfv(fb.id(), GL_COLOR, 1, zero);
  glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &clearDepth);
  fb.bind();
}

VertexArray::VertexArray() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  name_ = detail::GlName<detail::VertexArrayTraits>(id);
}

void VertexArray::setAttribute(GLuint index, const Buffer& buffer, std::size_t offset, int stride, int components) {
  glEnableVertexArrayAttrib(id(), index);
  glVertexArrayVertexBuffer(id(), index, buffer.id(), static_cast<GLintptr>(offset), stride);
  glVertexArrayAttribFormat(id(), index, components, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(id(), index, index);
}

void VertexArray::setIndexBuffer(const Buffer& buffer) { glVertexArrayElementBuffer(id(), buffer.id()); }

Query::Query(GLenum target) : target_(target) {
  GLuint id = 0;
  switch (target) {
    // GL_ARB_pipeline_statistics_query's targets: Mesa 22.3 refuses them in glCreateQueries
    // (GL_INVALID_ENUM, id 0) but not in glBeginQuery, so the name is generated and becomes a
    // query object at its first glBeginQuery (every use here begins it before asking for results).
    case GL_VERTICES_SUBMITTED_ARB: case GL_PRIMITIVES_SUBMITTED_ARB: case GL_VERTEX_SHADER_INVOCATIONS_ARB:
    case GL_TESS_CONTROL_SHADER_PATCHES_ARB: case GL_TESS_EVALUATION_SHADER_INVOCATIONS_ARB:
    case GL_GEOMETRY_SHADER_INVOCATIONS: case GL_GEOMETRY_SHADER_PRIMITIVES_EMITTED_ARB:
    case GL_FRAGMENT_SHADER_INVOCATIONS_ARB: case GL_COMPUTE_SHADER_INVOCATIONS_ARB:
    case GL_CLIPPING_INPUT_PRIMITIVES_ARB: case GL_CLIPPING_OUTPUT_PRIMITIVES_ARB:
      glGenQueries(1, &id);
      break;
    default:
      glCreateQueries(target, 1, &id);
  }
  name_ = detail::GlName<detail::QueryTraits>(id);
}

bool Query::resultAvailable() const {
  GLint available = 0;
  glGetQueryObjectiv(id(), GL_QUERY_RESULT_AVAILABLE, &available);
  return available != 0;
}

GLuint64 Query::result() const {
  GLuint64 value = 0;
  glGetQueryObjectui64v(id(), GL_QUERY_RESULT, &value);
  return value;
}

Sampler::Sampler() {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  name_ = detail::GlName<detail::SamplerTraits>(id);
}

TransformFeedback::TransformFeedback() {
  GLuint id = 0;
  glCreateTransformFeedbacks(1, &id);
  name_ = detail::GlName<detail::TransformFeedbackTraits>(id);
}

void TransformFeedback::bindBuffer(GLuint index, const Buffer& buffer) {
  glTransformFeedbackBufferBase(id(), index, buffer.id());
}

Fence Fence::insert() {
  Fence f;
  f.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  return f;
}

Fence& Fence::operator=(Fence&& o) noexcept {
  if (this != &o) {
    if (sync_) glDeleteSync(sync_);
    sync_ = o.sync_;
    o.sync_ = nullptr;
  }
  return *this;
}

Fence::~Fence() {
  if (sync_) glDeleteSync(sync_);
}

bool Fence::signaled() const {
  if (!sync_) return false;
  const GLenum r = glClientWaitSync(sync_, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
  return r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED;
}

void Fence::wait() const {
  if (!sync_) return;
  GLbitfield flags = GL_SYNC_FLUSH_COMMANDS_BIT;
  for (;;) {
    const GLenum r = glClientWaitSync(sync_, flags, 1'000'000'000);  // 1 s a try
    if (r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED) return;
    if (r == GL_WAIT_FAILED) throw std::runtime_error("glClientWaitSync failed");
    flags = 0;  // flushed once already
  }
}

void unbindComputeState(int images, int textures) {
  for (int u = 0; u < images; ++u) glBindImageTexture(static_cast<GLuint>(u), 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
  for (int u = 0; u < textures; ++u) glBindTextureUnit(static_cast<GLuint>(u), 0);
  glUseProgram(0);
}

}  // namespace tallow::gpu
