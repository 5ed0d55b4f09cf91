// The animation clock of view and capture (app/playback/playback.h).
#include "app/playback/playback.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tallow::app {
namespace {

TEST(Playback, FixedRateFramesAreExactlyCapturesTimes) {
  // Capture has always put frame i at start + i / fps; an unchanged run must keep those times to
  // the bit (stats.json and the reference images depend on them).
  Playback clock(12.0, 20.0, false);
  for (int i = 0; i < 120; ++i) {
    clock.setFrame(i, 30.0);
    EXPECT_EQ(clock.rawTime(), 12.0 + i / 30.0) << i;
  }
}

TEST(Playback, PauseHoldsAndPlayContinuesFromThere) {
  Playback clock(0.0, 0.0, true);
  clock.setFrame(3, 10.0);
  EXPECT_DOUBLE_EQ(clock.time(), 0.3);
  clock.pause();
  for (int i = 4; i < 8; ++i) {
    clock.setFrame(i, 10.0);
    EXPECT_DOUBLE_EQ(clock.time(), 0.3) << "paused at frame 3, frame " << i;
  }
  clock.play();  // during frame 7: frame 8 is one step later
  clock.setFrame(8, 10.0);
  EXPECT_DOUBLE_EQ(clock.time(), 0.4);
  clock.advance(1.0);  // wall-clock steps add seconds × speed
  EXPECT_DOUBLE_EQ(clock.time(), 1.4);
}

TEST(Playback, ASlowFrameAdvancesTheClockByAtMostTheCap) {
  // Issue 40: frames of 11.6 s took the candle from t = 12 s to its end in one frame.
  EXPECT_DOUBLE_EQ(cappedStep(11.6, kDefaultMaxStepS), 1.0 / 30.0);
  EXPECT_DOUBLE_EQ(cappedStep(0.01, kDefaultMaxStepS), 0.01);  // a fast machine follows wall time
  EXPECT_DOUBLE_EQ(cappedStep(11.6, 0.0), 11.6);               // 0: no cap
  EXPECT_DOUBLE_EQ(cappedStep(-0.5, kDefaultMaxStepS), 0.0);   // a clock that went back moves nothing
  Playback clock(12.0, 20.0, false);
  for (int i = 0; i < 10; ++i) clock.advance(cappedStep(11.6, 0.05));
  EXPECT_NEAR(clock.time(), 12.5, 1e-12) << "ten slow frames at a 0.05 s cap play half a second";
}

TEST(Playback, SeekAndSpeedReanchorTheFrameCount) {
  Playback clock(0.0, 0.0, true);
  clock.setFrame(5, 10.0);
  clock.seek(2.0);
  EXPECT_DOUBLE_EQ(clock.time(), 2.0);
  clock.setFrame(6, 10.0);
  EXPECT_DOUBLE_EQ(clock.time(), 2.1);
  clock.setSpeed(0.5);
  clock.setFrame(8, 10.0);
  EXPECT_DOUBLE_EQ(clock.time(), 2.1 + 2 * 0.05);
  EXPECT_THROW(clock.setSpeed(std::nan("")), std::invalid_argument);
  EXPECT_THROW(clock.seek(INFINITY), std::invalid_argument);
}

TEST(Playback, LoopWrapsAndOnceHoldsTheEnd) {
  Playback looping(0.0, 13.0, true);
  looping.seek(27.5);
  EXPECT_DOUBLE_EQ(looping.time(), 1.5);  // 27.5 − 2 × 13
  looping.seek(-1.0);
  EXPECT_DOUBLE_EQ(looping.time(), 12.0);
  EXPECT_DOUBLE_EQ(looping.rawTime(), -1.0);

  Playback once(12.0, 20.0, false);
  once.advance(30.0);
  EXPECT_DOUBLE_EQ(once.time(), 20.0) << "held at the end";
  once.pause();
  once.play();  // play at the end of a finished animation starts it again
  EXPECT_DOUBLE_EQ(once.time(), 0.0);
  once.setLoop(true);
  once.advance(25.0);
  EXPECT_DOUBLE_EQ(once.time(), 5.0);
}

}  // namespace
}  // namespace tallow::app
