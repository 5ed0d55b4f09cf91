// RAII GL objects, read-back and GPU timers on a real (llvmpipe) context.
#include <gtest/gtest.h>

#include "gpu/gl_context.h"
#include "gpu/gl_objects.h"
#include "gpu/gpu_timer.h"
#include "gpu/readback.h"

namespace tallow {
namespace {

class GlObjects : public ::testing::Test {
 protected:
  void SetUp() override { context_ = gpu::GlContext::create(gpu::ContextOptions{}); }
  std::unique_ptr<gpu::GlContext> context_;
};

GLint levelParameter(const gpu::Texture& t, GLenum name) {
  GLint v = 0;
  glGetTextureLevelParameteriv(t.id(), 0, name, &v);
  return v;
}

TEST_F(GlObjects, TexturesOfEveryTargetHaveTheRequestedShape) {
  const auto t2 = gpu::Texture::create2D(GL_RGBA16F, 64, 32, 3);
  EXPECT_EQ(levelParameter(t2, GL_TEXTURE_WIDTH), 64);
  EXPECT_EQ(levelParameter(t2, GL_TEXTURE_HEIGHT), 32);
  EXPECT_EQ(levelParameter(t2, GL_TEXTURE_INTERNAL_FORMAT), GL_RGBA16F);
  GLint levels = 0;
  glGetTextureParameteriv(t2.id(), GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
  EXPECT_EQ(levels, 3);
  EXPECT_EQ(t2.bytes(), (64u * 32 + 32 * 16 + 16 * 8) * 8);

  const auto a = gpu::Texture::create2DArray(GL_R32F, 16, 16, 5);
  EXPECT_EQ(levelParameter(a, GL_TEXTURE_DEPTH), 5);
  const auto v = gpu::Texture::create3D(GL_R16F, 8, 4, 2);
  EXPECT_EQ(levelParameter(v, GL_TEXTURE_DEPTH), 2);
  const auto c = gpu::Texture::createCube(GL_DEPTH_COMPONENT32F, 32);
  EXPECT_EQ(c.target(), static_cast<GLenum>(GL_TEXTURE_CUBE_MAP));
  EXPECT_EQ(levelParameter(c, GL_TEXTURE_WIDTH), 32);
  const auto ca = gpu::Texture::createCubeArray(GL_DEPTH_COMPONENT32F, 16, 3);
  EXPECT_EQ(levelParameter(ca, GL_TEXTURE_DEPTH), 18);  // layer-faces
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlObjects, MoveTransfersOwnershipAndDestructionDeletes) {
  GLuint name = 0;
  {
    gpu::Texture a = gpu::Texture::create2D(GL_RGBA8, 4, 4);
    name = a.id();
    ASSERT_TRUE(glIsTexture(name));
    gpu::Texture b = std::move(a);
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is what we test
    EXPECT_EQ(b.id(), name);
    EXPECT_TRUE(glIsTexture(name));
  }
  EXPECT_FALSE(glIsTexture(name));

  GLuint buffer = 0;
  {
    gpu::Buffer b(256);
    buffer = b.id();
    EXPECT_TRUE(glIsBuffer(buffer));
  }
  EXPECT_FALSE(glIsBuffer(buffer));
}

TEST_F(GlObjects, BufferUploadAndDownloadRoundTrip) {
  const std::vector<float> data = {1.0f, -2.5f, 3.25f, 1e-7f};
  gpu::Buffer b(data.size() * sizeof(float), data.data());
  std::vector<float> back(4);
  b.download(0, back.size() * sizeof(float), back.data());
  EXPECT_EQ(back, data);
  const float replacement = 42.0f;
  b.upload(2 * sizeof(float), sizeof(float), &replacement);
  b.download(0, back.size() * sizeof(float), back.data());
  EXPECT_EQ(back[2], 42.0f);
}

TEST_F(GlObjects, FloatAndByteTargetsReadBackTopRowFirst) {
  auto f = gpu::Texture::create2D(GL_RGBA32F, 3, 2);
  gpu::Framebuffer fb;
  fb.attachColor(0, f);
  fb.setDrawBuffers(1);
  fb.checkComplete("float target");
  // Fill the bottom row (GL row 0) with one value and the top row with another.
  const std::vector<float> rows = {0.125f, -3.0f, 1e6f, 1.0f, 0.125f, -3.0f, 1e6f, 1.0f, 0.125f, -3.0f, 1e6f, 1.0f,
                                   2.0f,   0.5f,  0.0f, 1.0f, 2.0f,   0.5f,  0.0f, 1.0f, 2.0f,   0.5f,  0.0f, 1.0f};
  glTextureSubImage2D(f.id(), 0, 0, 0, 3, 2, GL_RGBA, GL_FLOAT, rows.data());
  const gpu::Image image = gpu::readColor(fb, 0, 3, 2);
  EXPECT_EQ(image.at(1, 0), glm::vec4(2.0f, 0.5f, 0.0f, 1.0f));      // top row = GL row 1
  EXPECT_EQ(image.at(2, 1), glm::vec4(0.125f, -3.0f, 1e6f, 1.0f));  // exact, negative and large kept

  auto b = gpu::Texture::create2D(GL_RGBA8, 2, 1);
  const unsigned char bytes[8] = {255, 128, 0, 255, 1, 2, 3, 4};
  glTextureSubImage2D(b.id(), 0, 0, 0, 2, 1, GL_RGBA, GL_UNSIGNED_BYTE, bytes);
  const gpu::Image bi = gpu::readTexture(b);
  EXPECT_FLOAT_EQ(bi.at(0, 0).g, 128.0f / 255.0f);
  EXPECT_FLOAT_EQ(bi.at(1, 0).a, 4.0f / 255.0f);
}

TEST_F(GlObjects, IncompleteFramebufferNamesItself) {
  gpu::Framebuffer fb;
  fb.setDrawBuffers(1);  // colour attachment 0 drawn but nothing attached
  try {
    fb.checkComplete("probe");
    FAIL() << "expected an incomplete framebuffer";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("probe: framebuffer incomplete", 0), 0u) << e.what();
  }
}

TEST_F(GlObjects, TimerReportsPassesInTheOrderTheyBegan) {
  gpu::GpuTimer timer;
  for (int frame = 0; frame < 2; ++frame) {  // the second frame reuses the query pool
    const std::uint64_t number = timer.beginFrame();
    {
      gpu::GpuScope outer(timer, "outer");
      gpu::GpuScope inner(timer, "inner");
      glClear(GL_COLOR_BUFFER_BIT);
    }
    const auto t = timer.times(number, true);
    ASSERT_TRUE(t.has_value());
    ASSERT_EQ(t->size(), 2u);
    EXPECT_GE((*t)[0], (*t)[1]);  // "outer" first; nested: the outer scope contains the inner one
    EXPECT_GE((*t)[1], 0.0);
  }
}

}  // namespace
}  // namespace tallow
