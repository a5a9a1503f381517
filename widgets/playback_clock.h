#pragma once
// PlaybackClock: which frame is due at a given wall-clock time. Playback derives the frame from the
// time elapsed since it started instead of counting timer ticks, so a slow render drops frames rather
// than slowing the motion down (an animator judges timing; it must be right).

namespace motionstyle {

class PlaybackClock {
 public:
  // Rate of the clip in frames per second (> 0) and the playback speed factor (> 0, 1 = real time).
  // Changing the rate does not move the start: call start() again to continue from the current frame.
  void setRate(double fps, double speed);
  double fps() const { return fps_; }
  double speed() const { return speed_; }

  // Playback (re)starts at `frame` at wall time `now_seconds`.
  void start(int frame, double now_seconds);

  // The frame due at `now_seconds`: start frame + floor(elapsed seconds * fps * speed), neither wrapped
  // nor clamped (see wrapFrame). Times before the start give the start frame.
  long long frameAt(double now_seconds) const;

 private:
  double fps_ = 30.0;
  double speed_ = 1.0;
  int start_frame_ = 0;
  double start_seconds_ = 0.0;
};

// Maps an unbounded frame into [0, frames): modulo when looping, else clamped to the last frame.
// frames <= 0 gives 0.
int wrapFrame(long long frame, int frames, bool loop);

}  // namespace motionstyle
