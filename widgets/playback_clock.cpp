#include "playback_clock.h"

#include <algorithm>
#include <cmath>

namespace motionstyle {

void PlaybackClock::setRate(double fps, double speed) {
  if (fps > 0.0 && std::isfinite(fps)) fps_ = fps;
  if (speed > 0.0 && std::isfinite(speed)) speed_ = speed;
}

void PlaybackClock::start(int frame, double now_seconds) {
  start_frame_ = frame;
  start_seconds_ = now_seconds;
}

long long PlaybackClock::frameAt(double now_seconds) const {
  const double elapsed = std::max(0.0, now_seconds - start_seconds_);
  // A tiny epsilon so that exactly k frame periods land on frame k despite rounding.
  return start_frame_ + static_cast<long long>(std::floor(elapsed * fps_ * speed_ + 1e-9));
}

int wrapFrame(long long frame, int frames, bool loop) {
  if (frames <= 0) return 0;
  if (loop) {
    const long long wrapped = frame % frames;
    return static_cast<int>(wrapped < 0 ? wrapped + frames : wrapped);
  }
  return static_cast<int>(std::clamp<long long>(frame, 0, frames - 1));
}

}  // namespace motionstyle
