#pragma once
// The view window's render thread (issue 40): a frame takes seconds on llvmpipe, so an
// interactive window renders on a thread of its own, in a GL context that shares the window's
// textures, while the window's thread keeps drawing the panel and the last complete picture and
// answers every key, click and slider at once. The window posts a job (the configuration, the
// time, the debug view) whenever the thread is free; the thread renders it into one of three
// pictures (one shown, one finished and not yet taken, one being drawn) and hands back the
// picture, the frame's timings and the renderer's summary (app/view/view_session.h).
//
// The thread owns every object of the renderer (vertex arrays, framebuffers and queries are not
// shared between contexts) and builds a new renderer when the job's scene generation changes (a
// preset loaded in the panel). Runs with --frames or --script stay in lockstep on one thread, so
// that their frames are the same on every machine (app/view/view_command.cpp).
#include <array>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "app/view/view_canvas.h"
#include "app/view/view_layout.h"
#include "app/view/view_session.h"
#include "gpu/gl_context.h"
#include "gpu/image.h"
#include "gpu/shader_library.h"
#include "sss/debug_view.h"
#include "sss/debug_view_pass.h"
#include "sss/renderer.h"

namespace tallow::app {

struct RenderJob {
  int generation = 0;  ///< ViewSession::generation: another one builds a new renderer
  Config config;
  double timeS = 0.0;
  bool playing = true;  ///< the clock's state, recorded with the frame
  bool holdRefinement = false;  ///< input moved since the last job: a preview (Renderer::holdRefinement)
  sss::DebugView debug;
  std::vector<std::string> radianceFiles;  ///< .exr screenshots of this frame, written after it
  std::string presetName;                  ///< named in the EXR files
  /// --stats: the frame's GPU times read before the result is handed back (the render thread
  /// waits for them; the window's thread never does) and the triangles counted.
  bool measure = false;
};

struct RenderResult {
  int generation = 0;
  ViewSession::Frame frame;
  RenderSummary summary;
  bool playing = true;  ///< as in the job
  bool preview = false;  ///< the job's holdRefinement
  Config config;  ///< the configuration rendered (the last that rendered, where the job's was refused)
  std::string debugNote;           ///< why the debug view shows the final image instead
  std::optional<std::size_t> triangles;
  std::vector<std::string> wrote;  ///< radiance files written
  std::string error;               ///< a radiance file could not be written, or a scene not built
  int slot = -1;                   ///< the picture (none when the scene could not be built)
  GLuint texture = 0;              ///< its texture, shared with the window's context
  int width = 0, height = 0;
};

class RenderWorker {
 public:
  /// Starts the thread with a context shared with `window`'s (made here, on the window's thread).
  /// Throws gpu::ContextError when the backend has no shared contexts.
  RenderWorker(const gpu::GlContext& window, const gpu::ShaderLibrary& shaders, std::optional<gpu::Image> reference);
  /// Waits for the frame in flight, then ends the thread and frees its GL objects.
  ~RenderWorker();
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;

  /// A job is queued or rendering, or its result not yet taken.
  bool busy() const;
  /// Queues the next frame; the worker must not be busy().
  void post(RenderJob job);
  /// The finished frame, once (nothing while it renders). Its picture is what present() shows from
  /// now on. Rethrows what the thread could not handle (a GL or shader error).
  std::optional<RenderResult> take();
  /// Waits until the job in flight is done (the window closing with --stats records the last frame).
  void finish();
  /// Clears the window and copies the picture of the last result taken into `layout.image`
  /// (the background alone before the first).
  void present(const ViewLayout& layout, int windowW, int windowH);

 private:
  static constexpr int kSlots = 3;
  void run();
  RenderResult render(RenderJob& job);
  int freeSlot();

  const gpu::ShaderLibrary& shaders_;
  std::optional<gpu::Image> reference_;
  std::unique_ptr<gpu::GlContext> context_;

  // Shared between the threads, under mutex_.
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<RenderJob> job_;
  bool rendering_ = false;
  std::optional<RenderResult> result_;
  std::exception_ptr failure_;
  bool stop_ = false;
  int shownSlot_ = -1;  ///< the window's thread shows this picture
  /// The window's last copy of each picture: the render thread waits for it before drawing there.
  std::array<GLsync, kSlots> released_{};

  // The render thread's alone.
  std::unique_ptr<sss::Renderer> renderer_;
  std::unique_ptr<sss::DebugViewPass> debugPass_;
  int generation_ = 0;  ///< of the scene renderer_ was built for (0: none)
  Config lastGood_;     ///< the last configuration that rendered
  /// Made and freed on the render thread (framebuffer names are its context's).
  std::unique_ptr<std::array<ViewCanvas, kSlots>> pictures_;
  int lastSlot_ = -1;

  // The window's thread's alone: framebuffers (not shared) reading the pictures' textures.
  struct Reader {
    gpu::Framebuffer framebuffer;
    GLuint texture = 0;  ///< attached (a resized picture is a new texture)
  };
  std::array<Reader, kSlots> readers_;
  int shownWidth_ = 0, shownHeight_ = 0;

  std::thread thread_;
};

}  // namespace tallow::app
