#pragma once
// TrackView: per-frame tracks under the timeline's time axis.
//   - a ruler with frame numbers (click or drag on it to scrub),
//   - boolean tracks (e.g. left / right foot contact), editable by click-drag painting: the press
//     toggles the frame under the cursor and the drag paints that value over every frame it crosses;
//     frames marked "unheld" (on, but not acted on: a contact the clean-up does not hold) are drawn
//     hatched, and a press on one paints "on" (asks for it to be held) instead of toggling it off;
//     frames marked "lifted" (on, but the clean-up lifts the foot off the floor with the style there)
//     are drawn raised, their bar clear of the row's lower half, and toggle as any other,
//   - float tracks (quality figures per frame, e.g. foot skate) drawn as filled curves,
//   - a playhead across all of them.
// Frames are cells: frame f covers [f, f+1) of the track area's width; the playhead sits on the centre.

#include <QColor>
#include <QString>
#include <QWidget>

#include <vector>

namespace motionstyle {

class TrackView : public QWidget {
  Q_OBJECT

 public:
  static constexpr int kHeaderWidth = 84;  // the track names' column, left of the time area
  static constexpr int kRulerHeight = 20;
  static constexpr int kBoolRowHeight = 20;
  static constexpr int kFloatRowHeight = 34;

  explicit TrackView(QWidget* parent = nullptr);

  // Number of frames on the time axis (>= 0). Tracks are resized to it (new frames: false / 0).
  void setFrameCount(int frames);
  int frameCount() const { return frames_; }

  // Adds a boolean track and returns its index. `values` is resized to frameCount().
  int addBoolTrack(const QString& name, const QColor& color, std::vector<bool> values = {});
  void setBoolValues(int track, std::vector<bool> values);
  const std::vector<bool>& boolValues(int track) const;
  // Frames of a boolean track that are on but not acted on (drawn hatched; a press there paints on;
  // hovering one shows `tool_tip`). Empty: none. Resized to frameCount(); kept until set again.
  void setUnheldFrames(int track, std::vector<bool> unheld, const QString& tool_tip = {});
  const std::vector<bool>& unheldFrames(int track) const;
  // Frames of a boolean track that are on but lifted off the floor (drawn raised; hovering one shows
  // `tool_tip`; an unheld frame is drawn and explained as unheld). Empty: none. As setUnheldFrames.
  void setLiftedFrames(int track, std::vector<bool> lifted, const QString& tool_tip = {});
  const std::vector<bool>& liftedFrames(int track) const;
  int boolTrackCount() const { return static_cast<int>(bool_tracks_.size()); }

  // Adds a float track (drawn below the boolean ones) and returns its index; then its values, drawn
  // scaled to [minimum, maximum] and resized to frameCount() (new frames: minimum). A track without
  // values draws as a flat row.
  int addFloatTrack(const QString& name, const QColor& color);
  void setFloatValues(int track, std::vector<float> values, float minimum, float maximum);
  const std::vector<float>& floatValues(int track) const;
  int floatTrackCount() const { return static_cast<int>(float_tracks_.size()); }
  void clearTracks();  // removes every track

  // Whether boolean tracks can be painted with the mouse (default true).
  void setEditable(bool editable) { editable_ = editable; }

  int playhead() const { return playhead_; }

  // Geometry, in widget pixels: the frame under x (clamped; -1 without frames), the x of a frame's
  // cell centre, and the rectangle of a boolean track's row.
  int frameAt(double x) const;
  double xForFrame(int frame) const;
  QRect boolTrackRect(int track) const;
  QRect floatTrackRect(int track) const;
  QRect rulerRect() const;

  QSize sizeHint() const override;
  QSize minimumSizeHint() const override;

 public slots:
  void setPlayhead(int frame);

 signals:
  // Frames first..last (inclusive) of `track` now hold `value`: emitted while a paint stroke grows
  // (so that the result can follow the hand) and once more on release, with the whole stroke.
  void trackEdited(int track, int first_frame, int last_frame, bool value);
  // A click or drag on the ruler asks to show `frame`.
  void scrubbed(int frame);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  bool event(QEvent* event) override;  // the unheld and lifted frames' tool tips

 private:
  struct BoolTrack {
    QString name;
    QColor color;
    std::vector<bool> values;
    std::vector<bool> unheld;  // empty, or one per frame
    QString unheld_tool_tip;
    std::vector<bool> lifted;  // empty, or one per frame
    QString lifted_tool_tip;
  };
  bool isUnheld(int track, int frame) const;
  bool isLifted(int track, int frame) const;  // lifted, on and not unheld
  struct Stroke {
    int track = -1;
    bool value = false;
    int first = 0;
    int last = 0;
    int previous = 0;
  };

  QRect timeArea() const;
  void paintRuler(QPainter& painter) const;
  void paintStroke(int frame);

  int frames_ = 0;
  int playhead_ = 0;
  bool editable_ = true;
  std::vector<BoolTrack> bool_tracks_;
  struct FloatTrack {
    QString name;
    QColor color;
    std::vector<float> values;
    float minimum = 0.0f;
    float maximum = 1.0f;
  };
  std::vector<FloatTrack> float_tracks_;
  Stroke stroke_;
  bool scrubbing_ = false;
};

}  // namespace motionstyle
