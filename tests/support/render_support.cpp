#include "support/render_support.h"

#include "app/config/setup.h"

namespace tallow::test {

RenderResult renderPreset(const std::string& preset, const std::vector<std::string>& sets, gpu::GlBackend backend) {
  app::SceneOptions options;
  options.preset = preset;
  options.sets = sets;
  const app::LoadedScene loaded = app::loadScene(options);
  gpu::ContextOptions contextOptions;
  contextOptions.backend = backend;
  contextOptions.visible = false;
  auto context = gpu::GlContext::create(contextOptions);
  const gpu::ShaderLibrary shaders;
  sss::Renderer renderer(shaders, loaded.config.scene, loaded.config.render);
  RenderResult result;
  result.timings = renderer.render(loaded.config.scene, loaded.config.render, 0.0);
  result.image = renderer.readRadiance();
  renderer.resolveTimings(result.timings);  // the read-back waited for the GPU
  result.gl = context->info();
  return result;
}

PresetSession::PresetSession(const std::string& preset, const std::vector<std::string>& sets, gpu::GlBackend backend) {
  app::SceneOptions options;
  options.preset = preset;
  options.sets = sets;
  loaded_ = app::loadScene(options);
  gpu::ContextOptions contextOptions;
  contextOptions.backend = backend;
  contextOptions.visible = false;
  context_ = gpu::GlContext::create(contextOptions);
  renderer_ = std::make_unique<sss::Renderer>(shaders_, scene(), settings());
}

gpu::Image PresetSession::render(double timeS, sss::FrameTimings* timings) {
  context_->makeCurrent();  // a test may hold several sessions: GL names are per context
  sss::FrameTimings t = renderer_->render(scene(), settings(), timeS);
  gpu::Image image = renderer_->readRadiance();
  if (timings) {
    renderer_->resolveTimings(t);  // the read-back waited for the GPU
    *timings = t;
  }
  return image;
}

sss::FrameTimings PresetSession::renderFrame(double timeS) {
  context_->makeCurrent();
  return renderer_->render(scene(), settings(), timeS);
}

std::string testScene(const std::string& name) {
  return std::string(TALLOW_TEST_SOURCE_DIR) + "/tests/data/" + name + ".json";
}

std::vector<std::string> smallFieldSets(int res, const std::string& placement) {
  return {"render.width=64", "render.height=48", "field.res=" + std::to_string(res), "sss.maps=6",
          "sss.samples=4", "sss.map_size=64", "sss.light_map_size=64", "sss.frames=1",
          "field.placement=" + placement};
}

double centreMean(const gpu::Image& image, int band) {
  double sum = 0.0;
  int n = 0;
  for (int y = image.height / 4; y < 3 * image.height / 4; ++y)
    for (int x = image.width / 4; x < 3 * image.width / 4; ++x, ++n) sum += image.at(x, y)[band];
  return sum / n;
}

}  // namespace tallow::test
