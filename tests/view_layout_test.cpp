// Where the view window puts the panel and the picture (app/view/view_layout.h), the keys it takes
// as hotkeys (app/view/view_hotkeys.h) and the names it saves under (app/view/numbered_file.h).
#include "app/view/view_layout.h"

#include <gtest/gtest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>

#include "app/view/numbered_file.h"
#include "app/view/view_hotkeys.h"
#include "support/temp_dir.h"

namespace tallow::app {
namespace {

TEST(ViewLayout, ThePictureNeverLiesUnderThePanelAndKeepsItsAspect) {
  // Windows wide and tall, panels narrow and wide, images of every shape: the picture stays in the
  // viewport right of the panel, whole, centred, its aspect within a pixel's rounding.
  for (const int windowW : {300, 740, 1600})
    for (const int windowH : {200, 480, 1000})
      for (const int panelW : {0, 260, 420})
        for (const auto& [imageW, imageH] : {std::pair{320, 180}, std::pair{320, 240}, std::pair{64, 512}, std::pair{1920, 1080}}) {
          const ViewLayout l = layoutView(windowW, windowH, panelW, imageW, imageH);
          SCOPED_TRACE(testing::Message() << windowW << "x" << windowH << " panel " << panelW << " image " << imageW
                                          << "x" << imageH);
          EXPECT_FALSE(l.image.overlaps(l.panel));
          EXPECT_GE(l.image.x, std::min(panelW, windowW));
          EXPECT_LE(l.image.x + l.image.width, windowW);
          EXPECT_GE(l.image.y, 0);
          EXPECT_LE(l.image.y + l.image.height, windowH);
          if (l.image.empty()) continue;
          // Fits one side exactly (it fills the viewport as far as the aspect allows).
          const int viewportW = windowW - std::min(panelW, windowW);
          EXPECT_TRUE(l.image.width == viewportW || l.image.height == windowH);
          // Aspect: w/h against the image's, within the rounding of either side to a pixel.
          const double aspect = static_cast<double>(imageW) / imageH;
          EXPECT_NEAR(static_cast<double>(l.image.width) / l.image.height, aspect,
                      aspect * (1.0 / l.image.width + 1.0 / l.image.height) + 1e-12);
          // Centred: the margins either side differ by at most one pixel.
          EXPECT_LE(std::abs((l.image.x - l.viewport.x) - (l.viewport.x + l.viewport.width - l.image.x - l.image.width)), 1);
        }
}

TEST(ViewLayout, AnImageThatFitsIsShownPixelForPixel) {
  // The window the view opens for a 320x240 image: the panel's 420 px, then the image at scale 1.
  const ViewLayout l = layoutView(740, 480, 420, 320, 240);
  EXPECT_EQ(l.panel.x, 0);
  EXPECT_EQ(l.panel.width, 420);
  EXPECT_EQ(l.panel.height, 480);
  EXPECT_EQ(l.image.x, 420);
  EXPECT_EQ(l.image.y, 120);
  EXPECT_EQ(l.image.width, 320);
  EXPECT_EQ(l.image.height, 240);
  EXPECT_DOUBLE_EQ(l.scale, 1.0);
  // The panel hidden (F1): the whole window is the viewport and the image is enlarged to fill it.
  const ViewLayout hidden = layoutView(740, 480, 0, 320, 240);
  EXPECT_TRUE(hidden.panel.empty());
  EXPECT_EQ(hidden.image.width, 640);
  EXPECT_EQ(hidden.image.height, 480);
  EXPECT_EQ(hidden.image.x, 50);
  // A panel as wide as the window leaves nothing to draw into.
  EXPECT_TRUE(layoutView(400, 300, 400, 320, 240).image.empty());
}

TEST(ViewHotkeys, KeysAndModifiers) {
  EXPECT_EQ(hotkeyOf(GLFW_KEY_SPACE, 0, false), Hotkey::PlayPause);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_LEFT, 0, false), Hotkey::StepBack);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_RIGHT, 0, true), Hotkey::StepForward) << "held: steps on";
  EXPECT_EQ(hotkeyOf(GLFW_KEY_R, 0, false), Hotkey::ResetCamera);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_S, 0, false), Hotkey::Screenshot);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_S, 0, true), std::nullopt) << "held: one screenshot";
  EXPECT_EQ(hotkeyOf(GLFW_KEY_Z, GLFW_MOD_CONTROL, false), Hotkey::Undo);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT, false), Hotkey::Redo);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_Y, GLFW_MOD_CONTROL, false), Hotkey::Redo);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_Z, 0, false), std::nullopt) << "z alone is no hotkey";
  EXPECT_EQ(hotkeyOf(GLFW_KEY_R, GLFW_MOD_CONTROL, false), std::nullopt);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_S, GLFW_MOD_ALT, false), std::nullopt);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_F1, 0, false), Hotkey::TogglePanel);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_ESCAPE, 0, false), Hotkey::Quit);
  EXPECT_EQ(hotkeyOf(GLFW_KEY_Q, 0, false), std::nullopt);
}

TEST(NumberedFile, NeverOverwritesAndCountsOnFromTheLargest) {
  test::TempDir dir;
  const std::string base = (dir.path() / "tallow-blob").string();
  EXPECT_EQ(nextNumberedFile(base, ".png"), dir.path() / "tallow-blob-0001.png");
  dir.write("tallow-blob-0001.png", "x");
  dir.write("tallow-blob-0007.png", "x");
  dir.write("tallow-blob-0009.exr", "x");       // another extension: its own count
  dir.write("tallow-blob-x12.png", "x");        // not a number
  dir.write("tallow-blobby-0050.png", "x");     // another base
  EXPECT_EQ(nextNumberedFile(base, ".png"), dir.path() / "tallow-blob-0008.png");
  EXPECT_EQ(nextNumberedFile(base, ".exr"), dir.path() / "tallow-blob-0010.exr");
  dir.write("tallow-blob-9999.png", "x");
  EXPECT_EQ(nextNumberedFile(base, ".png"), dir.path() / "tallow-blob-10000.png");
}

}  // namespace
}  // namespace tallow::app
