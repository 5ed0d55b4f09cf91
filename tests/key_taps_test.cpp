// A key tapped between two frames of Dear ImGui 1.86 is held down for one frame (gpu/key_taps.h).
#include "gpu/key_taps.h"

#include <gtest/gtest.h>

#include <set>

namespace tallow::gpu {
namespace {

TEST(KeyTaps, AKeyPressedAndReleasedBetweenFramesIsHeldOnce) {
  KeyTaps taps;
  std::set<int> down;  // the backend's view: keys down at the start of the frame
  const auto isDown = [&down](int key) { return down.count(key) > 0; };
  // Enter tapped during a slow frame: pressed, released, both before the next frame starts.
  taps.pressed(257);
  EXPECT_EQ(taps.tapsToHold(isDown), std::vector<int>({257}));
  EXPECT_TRUE(taps.tapsToHold(isDown).empty()) << "held for one frame only";
  // A key still held when the frame starts is the backend's: nothing to hold.
  taps.pressed(65);
  down.insert(65);
  EXPECT_TRUE(taps.tapsToHold(isDown).empty());
  // Two taps of one key between frames: one frame down (ImGui 1.86 sees one press); two keys: both,
  // in the order pressed.
  taps.pressed(259);
  taps.pressed(258);
  taps.pressed(259);
  EXPECT_EQ(taps.tapsToHold(isDown), std::vector<int>({259, 258}));
}

}  // namespace
}  // namespace tallow::gpu
