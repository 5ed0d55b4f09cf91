#include "app/view/render_worker.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <stdexcept>

namespace tallow::app {

namespace {
/// How long either thread waits for the other's use of a picture to finish on the GPU before
/// going on regardless (a frame longer than this is a driver that hangs, not a slow one).
constexpr GLuint64 kPictureWaitNs = 60'000'000'000ull;

/// Waits on the calling thread until the commands before `sync` are done, then deletes it.
void waitAndDelete(GLsync& sync) {
  if (!sync) return;
  glClientWaitSync(sync, GL_SYNC_FLUSH_COMMANDS_BIT, kPictureWaitNs);
  glDeleteSync(sync);
  sync = nullptr;
}
}  // namespace

RenderWorker::RenderWorker(const gpu::GlContext& window, const gpu::ShaderLibrary& shaders,
                           std::optional<gpu::Image> reference)
    : shaders_(shaders), reference_(std::move(reference)), context_(window.createShared()) {
  thread_ = std::thread([this] { run(); });
}

RenderWorker::~RenderWorker() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
    job_.reset();  // not started: dropped; in flight: finished first
  }
  wake_.notify_all();
  thread_.join();
  for (GLsync& s : released_)
    if (s) glDeleteSync(s);
  context_.reset();  // the shared window, destroyed on the thread that made it (GLFW's rule)
  // readers_ go with the members, in the window's context (current on this thread).
}

bool RenderWorker::busy() const {
  const std::lock_guard lock(mutex_);
  return job_.has_value() || rendering_ || result_.has_value();
}

void RenderWorker::post(RenderJob job) {
  {
    const std::lock_guard lock(mutex_);
    if (job_ || rendering_ || result_) throw std::logic_error("RenderWorker::post: a frame is still in flight");
    job_ = std::move(job);
  }
  wake_.notify_all();
}

std::optional<RenderResult> RenderWorker::take() {
  std::optional<RenderResult> result;
  {
    const std::lock_guard lock(mutex_);
    if (failure_) std::rethrow_exception(failure_);
    if (!result_) return std::nullopt;
    result = std::move(result_);
    result_.reset();
    if (result->slot < 0) return result;  // no picture: the one shown stays
    const int previous = shownSlot_;
    shownSlot_ = result->slot;
    if (previous >= 0 && previous != shownSlot_) {
      // The render thread may draw into the previous picture once this thread's copies of it are done.
      if (released_[previous]) glDeleteSync(released_[previous]);
      released_[previous] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    }
  }
  glFlush();  // the fence reaches the GPU, so that the render thread's wait on it ends
  Reader& reader = readers_[result->slot];
  if (reader.texture != result->texture) {
    glNamedFramebufferTexture(reader.framebuffer.id(), GL_COLOR_ATTACHMENT0, result->texture, 0);
    reader.texture = result->texture;
  }
  shownWidth_ = result->width;
  shownHeight_ = result->height;
  return result;
}

void RenderWorker::finish() {
  std::unique_lock lock(mutex_);
  wake_.wait(lock, [this] { return !job_ && !rendering_; });
  if (failure_) std::rethrow_exception(failure_);
}

void RenderWorker::present(const ViewLayout& layout, int windowW, int windowH) {
  int slot = -1;
  {
    const std::lock_guard lock(mutex_);
    slot = shownSlot_;
  }
  presentPicture(slot >= 0 ? readers_[slot].framebuffer.id() : 0, shownWidth_, shownHeight_, layout, windowW, windowH);
}

int RenderWorker::freeSlot() {
  // Neither the picture shown nor one finished and not yet taken (which will be shown next).
  const std::lock_guard lock(mutex_);
  for (int i = 1; i <= kSlots; ++i) {
    const int s = (lastSlot_ + i) % kSlots;
    if (s != shownSlot_ && !(result_ && result_->slot == s)) return s;
  }
  throw std::logic_error("RenderWorker: no free picture");
}

RenderResult RenderWorker::render(RenderJob& job) {
  RenderResult result;
  result.generation = job.generation;
  result.playing = job.playing;
  result.preview = job.holdRefinement;
  if (!renderer_ || job.generation != generation_) {
    renderer_.reset();  // the old scene's GPU memory freed before the new one fills it
    generation_ = job.generation;
    try {
      renderer_ = std::make_unique<sss::Renderer>(shaders_, job.config.scene, job.config.render);
    } catch (const std::invalid_argument& e) {
      result.error = e.what();
      return result;
    }
    lastGood_ = job.config;
  }
  if (!renderer_) {
    result.error = "this scene could not be built (see above); load another preset";
    return result;
  }
  if (job.holdRefinement) renderer_->holdRefinement();
  result.config = job.config;  // the configuration rendered: the job's, or the last good one if refused
  result.frame = renderOrLastGood(*renderer_, result.config, lastGood_, job.timeS);
  ViewSession::Frame& frame = result.frame;
  const Config& shown = result.config;
  if (job.measure) {
    renderer_->resolveTimings(frame.gpu, true);
    frame.shown = renderer_->latestTimings();  // with this frame's times, now read
    result.triangles = renderer_->triangleCount();
  } else {
    result.triangles = renderer_->triangleCountIfAvailable();
  }
  result.summary = summarize(*renderer_, shown, job.timeS);

  const int slot = freeSlot();
  {
    GLsync released = nullptr;
    {
      const std::lock_guard lock(mutex_);
      std::swap(released, released_[slot]);
    }
    waitAndDelete(released);  // the window's last copy of this picture is done
  }
  ViewCanvas& picture = (*pictures_)[slot];
  const GLuint target = picture.target(shown.render.width, shown.render.height);
  result.debugNote = debugPass_->render(job.debug, *renderer_, shown.scene, shown.render, target,
                                        shown.render.width, shown.render.height);
  // The picture complete before the window's thread copies it (its context does not see this one's
  // commands otherwise).
  GLsync drawn = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  waitAndDelete(drawn);
  result.slot = slot;
  result.texture = picture.texture();
  result.width = picture.width();
  result.height = picture.height();
  lastSlot_ = slot;

  for (const std::string& file : job.radianceFiles) {
    try {
      writeRadiance(file, *renderer_, job.presetName, job.timeS);
      result.wrote.push_back(file);
    } catch (const std::exception& e) {
      result.error = e.what();
    }
  }
  return result;
}

void RenderWorker::run() {
  try {
    context_->makeCurrent();
    pictures_ = std::make_unique<std::array<ViewCanvas, kSlots>>();
    debugPass_ = std::make_unique<sss::DebugViewPass>(shaders_);
    if (reference_) debugPass_->setReference(*reference_);
    for (;;) {
      RenderJob job;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return stop_ || job_.has_value(); });
        if (!job_) break;  // stopped
        job = std::move(*job_);
        job_.reset();
        rendering_ = true;
      }
      RenderResult result = render(job);
      {
        const std::lock_guard lock(mutex_);
        result_ = std::move(result);
        rendering_ = false;
      }
      wake_.notify_all();
      glfwPostEmptyEvent();  // the window's thread, waiting for events, takes the picture at once
    }
  } catch (...) {
    const std::lock_guard lock(mutex_);
    failure_ = std::current_exception();
    rendering_ = false;
    job_.reset();
  }
  wake_.notify_all();
  glfwPostEmptyEvent();
  // Every GL object of this thread, freed in its own context.
  renderer_.reset();
  debugPass_.reset();
  pictures_.reset();
  glfwMakeContextCurrent(nullptr);
}

}  // namespace tallow::app
