#pragma once
// The animation clock of `view` and `capture`: play, pause, seek, speed and loop over a preset's
// animation. Time advances either by wall-clock seconds (the window) or by whole frames at a fixed
// rate (capture, and view --fps), in which case frame i of an unchanged run is at
// start + i / fps exactly, as capture always computed it.
namespace tallow::app {

/// The window's wall-clock step: `wallS` seconds, at most `maxStepS` (issue 40: with frames of
/// seconds, following wall time would jump through the animation; capped, a slow machine plays
/// slower instead). `maxStepS` 0: no cap. A negative `wallS` (a clock that went back) is 0.
double cappedStep(double wallS, double maxStepS);
/// The default cap: one frame of capture's default 30 fps.
inline constexpr double kDefaultMaxStepS = 1.0 / 30.0;

class Playback {
 public:
  /// `durationS` 0: a static scene (time still runs; nothing wraps or stops).
  Playback(double startS, double durationS, bool loop);

  bool playing() const { return playing_; }
  void play();
  void pause();
  double speed() const { return speed_; }
  /// Seconds of animation per second of playback; must be finite (any sign; 0 holds still).
  void setSpeed(double speed);
  bool loop() const { return loop_; }
  void setLoop(bool loop) { loop_ = loop; }
  double durationS() const { return durationS_; }

  /// Jumps to animation time t (the unwrapped clock restarts there).
  void seek(double t);
  /// Wall-clock step: the clock moves by seconds × speed while playing.
  void advance(double seconds);
  /// Fixed-rate step: the clock is at the time of frame `frame` of a sequence at `fps` frames per
  /// second, counted from the last seek, play, pause or speed change.
  void setFrame(int frame, double fps);

  /// The clock without wrapping (capture's frame times).
  double rawTime() const { return raw_; }
  /// The time to render: with a duration, wrapped into [0, duration) when looping, else held at
  /// duration once reached (the animation's last state); the raw clock otherwise.
  double time() const;

 private:
  void reanchor();

  double durationS_;
  bool loop_;
  bool playing_ = true;
  double speed_ = 1.0;
  double raw_;
  // setFrame's origin: the clock and frame number when playing, speed or position last changed.
  double anchorTime_;
  int anchorFrame_ = 0;
  int frame_ = 0;
};

}  // namespace tallow::app
