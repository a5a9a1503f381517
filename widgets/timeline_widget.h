#pragma once
// TimelineWidget: transport controls for a clip: play/pause, loop, speed (0.25x - 2x), frame stepping,
// a scrubbing slider, the frame number and time (mm:ss.fff), and a TrackView beneath for per-frame
// tracks (foot contacts, quality).
//
// Playback is driven by a QTimer but the frame shown is computed from elapsed wall time
// (PlaybackClock), so speed is right even when a frame renders slowly: frames are skipped, never
// slowed.
//
// Shortcuts (active while the timeline's window is): Space play/pause, Left/Right step one frame,
// Home/End first/last frame.

#include <QWidget>

#include <memory>

class QElapsedTimer;

namespace motionstyle {

class TrackView;

class TimelineWidget : public QWidget {
  Q_OBJECT

 public:
  explicit TimelineWidget(QWidget* parent = nullptr);
  ~TimelineWidget() override;

  // Number of frames (>= 0) and their rate in frames per second (> 0; others are ignored). Setting the
  // count clamps the current frame and pauses playback when it becomes 0.
  void setFrameCount(int frames);
  void setFrameRate(double fps);
  int frameCount() const;
  double frameRate() const;

  int frame() const;
  bool isPlaying() const;
  bool isLooping() const;
  double speed() const;  // playback speed factor, 1 = real time

  TrackView* trackView() const;

  // "mm:ss.fff" for a time in seconds (negative clamps to 0).
  static QString formatTime(double seconds);

 public slots:
  void setFrame(int frame);  // clamped; emits frameChanged when it changes
  void play();
  void pause();
  void togglePlay();
  void stepForward();   // pauses, then one frame later (wraps when looping)
  void stepBackward();  // pauses, then one frame earlier (wraps when looping)
  void goToStart();
  void goToEnd();
  void setLooping(bool loop);
  void setSpeed(double speed);  // clamped to [0.25, 2]

 signals:
  void frameChanged(int frame);
  void playingChanged(bool playing);

 private:
  void onTick();
  void refreshDisplay();
  void restartClock();

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace motionstyle
