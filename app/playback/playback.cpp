#include "app/playback/playback.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tallow::app {

double cappedStep(double wallS, double maxStepS) {
  const double step = std::max(wallS, 0.0);
  return maxStepS > 0.0 ? std::min(step, maxStepS) : step;
}

Playback::Playback(double startS, double durationS, bool loop)
    : durationS_(durationS), loop_(loop), raw_(startS), anchorTime_(startS) {}

void Playback::reanchor() {
  anchorTime_ = raw_;
  anchorFrame_ = frame_;
}

void Playback::play() {
  if (playing_) return;
  // Playing from the end of a finished, non-looping animation starts it again.
  if (!loop_ && durationS_ > 0.0 && raw_ >= durationS_) raw_ = 0.0;
  playing_ = true;
  reanchor();
}

void Playback::pause() {
  playing_ = false;
  reanchor();
}

void Playback::setSpeed(double speed) {
  if (!std::isfinite(speed)) throw std::invalid_argument("speed must be a finite number");
  speed_ = speed;
  reanchor();
}

void Playback::seek(double t) {
  if (!std::isfinite(t)) throw std::invalid_argument("time must be a finite number");
  raw_ = t;
  reanchor();
}

void Playback::advance(double seconds) {
  if (playing_) raw_ += seconds * speed_;
}

void Playback::setFrame(int frame, double fps) {
  frame_ = frame;
  // (frame − anchor) / fps first, as capture computed start + i / fps: speed 1 adds no rounding.
  if (playing_) raw_ = anchorTime_ + (frame - anchorFrame_) / fps * speed_;
}

double Playback::time() const {
  if (durationS_ <= 0.0) return raw_;
  if (loop_) {
    const double t = std::fmod(raw_, durationS_);
    return t < 0.0 ? t + durationS_ : t;
  }
  return std::clamp(raw_, 0.0, durationS_);
}

}  // namespace tallow::app
