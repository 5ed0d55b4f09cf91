#include "app/view_command.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "app/capture_command.h"
#include "app/input_error.h"
#include "sss/renderer.h"

namespace tallow::app {

int runView(const ViewOptions& options) {
  if (!gpu::displayAvailable()) {
    std::fprintf(stderr, "tallow: no display; capturing %s into %s/ instead\n",
                 options.scene.preset.empty() ? defaultPresetName().c_str() : options.scene.preset.c_str(),
                 options.fallbackOutDir.c_str());
    CaptureOptions capture;
    capture.scene = options.scene;
    capture.outDir = options.fallbackOutDir;
    return runCapture(capture);
  }
  LoadedScene loaded = loadScene(options.scene);
  Config& config = loaded.config;

  gpu::ContextOptions contextOptions;
  contextOptions.backend = gpu::GlBackend::Glfw;
  contextOptions.windowWidth = config.render.width;
  contextOptions.windowHeight = config.render.height;
  contextOptions.title = "Tallow — " + loaded.presetName;
  auto context = gpu::GlContext::create(contextOptions);
  GLFWwindow* window = context->window();
  const gpu::ShaderLibrary shaders = makeShaderLibrary(options.scene.shaderDir);
  sss::Renderer renderer(shaders, config.scene, config.render);
  if (options.scene.explain)
    for (const auto& p : sss::Renderer::plan(config.scene, config.render))
      std::printf("pass %-20s %s\n", p.name.c_str(), p.reason.c_str());

  const auto start = std::chrono::steady_clock::now();
  for (int frame = 0; !glfwWindowShouldClose(window) && (options.frames == 0 || frame < options.frames); ++frame) {
    glfwPollEvents();
    if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    if (width == 0 || height == 0) continue;  // minimised
    config.render.width = width;
    config.render.height = height;
    double t = config.scene.startS + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double duration = config.scene.durationS;
    if (duration > 0.0) t = config.scene.loop ? std::fmod(t, duration) : std::min(t, duration);
    renderer.render(config.scene, config.render, t);
    renderer.display(0, width, height, config.render.toneMap);
    glfwSwapBuffers(window);
  }
  return 0;
}

}  // namespace tallow::app
