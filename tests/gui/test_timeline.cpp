// Timeline, track view and playback clock: stepping, Home/End, shortcuts, wall-clock playback rate,
// looping, track painting and scrubbing.
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QSlider>
#include <QTest>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "gui_test_support.h"
#include "playback_clock.h"
#include "timeline_widget.h"
#include "track_view.h"

using namespace motionstyle;

class TimelineTest : public QObject {
  Q_OBJECT

 private slots:
  void clockIgnoresInvalidRatesAndClampsEarlyTimes() {
    PlaybackClock clock;
    clock.setRate(-5.0, 0.0);  // invalid: the defaults stay
    QCOMPARE(clock.fps(), 30.0);
    QCOMPARE(clock.speed(), 1.0);
    clock.setRate(120.0, 0.5);
    clock.start(10, 100.0);
    QCOMPARE(clock.frameAt(99.0), 10LL);  // before the start: the start frame
    QCOMPARE(clock.frameAt(100.0), 10LL);
    QCOMPARE(clock.frameAt(101.0), 70LL);  // 1 s * 120 fps * 0.5
  }

  void wrapFrameLoopsOrClamps() {
    QCOMPARE(wrapFrame(0, 0, true), 0);
    QCOMPARE(wrapFrame(12, 10, true), 2);
    QCOMPARE(wrapFrame(-1, 10, true), 9);
    QCOMPARE(wrapFrame(12, 10, false), 9);
    QCOMPARE(wrapFrame(-3, 10, false), 0);
  }

  void formatsTimeAsMinutesSecondsMillis() {
    QCOMPARE(TimelineWidget::formatTime(0.0), QStringLiteral("00:00.000"));
    QCOMPARE(TimelineWidget::formatTime(61.5), QStringLiteral("01:01.500"));
    QCOMPARE(TimelineWidget::formatTime(-2.0), QStringLiteral("00:00.000"));
    QCOMPARE(TimelineWidget::formatTime(5.0 / 120.0), QStringLiteral("00:00.042"));
  }

  void emptyTimelineDoesNotPlay() {
    TimelineWidget timeline;
    timeline.play();
    QVERIFY(!timeline.isPlaying());
    timeline.stepForward();
    QCOMPARE(timeline.frame(), 0);
  }

  void stepsClampAndWrap() {
    TimelineWidget timeline;
    timeline.setFrameCount(100);
    timeline.setFrameRate(30.0);
    QSignalSpy changed(&timeline, &TimelineWidget::frameChanged);
    timeline.stepForward();
    QCOMPARE(timeline.frame(), 1);
    QCOMPARE(changed.count(), 1);
    QCOMPARE(changed.last().at(0).toInt(), 1);
    timeline.stepBackward();
    timeline.stepBackward();  // looping (the default): wraps to the end
    QCOMPARE(timeline.frame(), 99);
    timeline.setLooping(false);
    timeline.stepForward();
    QCOMPARE(timeline.frame(), 99);
    timeline.goToStart();
    QCOMPARE(timeline.frame(), 0);
    timeline.goToEnd();
    QCOMPARE(timeline.frame(), 99);
    timeline.setFrame(500);
    QCOMPARE(timeline.frame(), 99);
    timeline.setFrameCount(50);  // shrinking clamps the current frame
    QCOMPARE(timeline.frame(), 49);
    QCOMPARE(timeline.trackView()->frameCount(), 50);
    QCOMPARE(timeline.trackView()->playhead(), 49);
  }

  void keyboardShortcutsDriveTheTransport() {
    TimelineWidget timeline;
    timeline.setFrameCount(100);
    timeline.setFrameRate(30.0);
    timeline.resize(900, 160);
    timeline.show();
    timeline.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&timeline));
    QTest::keyClick(&timeline, Qt::Key_Right);
    QTest::keyClick(&timeline, Qt::Key_Right);
    QCOMPARE(timeline.frame(), 2);
    QTest::keyClick(&timeline, Qt::Key_Left);
    QCOMPARE(timeline.frame(), 1);
    QTest::keyClick(&timeline, Qt::Key_End);
    QCOMPARE(timeline.frame(), 99);
    QTest::keyClick(&timeline, Qt::Key_Home);
    QCOMPARE(timeline.frame(), 0);
    QTest::keyClick(&timeline, Qt::Key_Space);
    QVERIFY(timeline.isPlaying());
    QTest::keyClick(&timeline, Qt::Key_Space);
    QVERIFY(!timeline.isPlaying());
  }

  void playbackFollowsWallClock_data() {
    QTest::addColumn<double>("fps");
    QTest::addColumn<double>("speed");
    QTest::newRow("30 fps, 1x") << 30.0 << 1.0;
    QTest::newRow("120 fps, 0.5x") << 120.0 << 0.5;
    QTest::newRow("30 fps, 2x") << 30.0 << 2.0;
  }

  void playbackFollowsWallClock() {
    QFETCH(double, fps);
    QFETCH(double, speed);
    TimelineWidget timeline;
    timeline.setFrameCount(10'000);
    timeline.setFrameRate(fps);
    timeline.setSpeed(speed);
    QCOMPARE(timeline.speed(), speed);
    // Every frame shown must be the one due at the moment it is shown, however late the event loop
    // runs (a loaded machine skips frames, it must not slow the motion down).
    QElapsedTimer wall;
    std::vector<std::pair<double, int>> shown;  // (seconds since play, frame)
    connect(&timeline, &TimelineWidget::frameChanged, this,
            [&](int frame) { shown.emplace_back(static_cast<double>(wall.nsecsElapsed()) / 1e9, frame); });
    wall.start();
    timeline.play();
    QTest::qWait(500);
    timeline.pause();
    QVERIFY2(shown.size() >= 5, qPrintable(QStringLiteral("only %1 frames shown in 0.5 s").arg(shown.size())));
    for (const auto& [seconds, frame] : shown) {
      const double due = seconds * fps * speed;
      QVERIFY2(frame <= due + 1.0 && frame >= due - 1.5,
               qPrintable(QStringLiteral("frame %1 shown at %2 s, due %3").arg(frame).arg(seconds).arg(due)));
    }
    const double elapsed = static_cast<double>(wall.nsecsElapsed()) / 1e9;
    QVERIFY(timeline.frame() <= elapsed * fps * speed + 1.0);
    QVERIFY(timeline.frame() >= 0.5 * elapsed * fps * speed);  // it did advance through the half second
  }

  void nonLoopingPlaybackStopsOnTheLastFrame() {
    TimelineWidget timeline;
    timeline.setFrameCount(6);
    timeline.setFrameRate(60.0);
    timeline.setLooping(false);
    QSignalSpy playing(&timeline, &TimelineWidget::playingChanged);
    timeline.play();
    QTRY_VERIFY_WITH_TIMEOUT(!timeline.isPlaying(), 2000);
    QCOMPARE(timeline.frame(), 5);
    QCOMPARE(playing.count(), 2);  // started, stopped
    timeline.play();               // at the end: replays from the start
    QVERIFY(timeline.isPlaying());
    QVERIFY(timeline.frame() < 5);
  }

  void loopingPlaybackWraps() {
    TimelineWidget timeline;
    timeline.setFrameCount(5);
    timeline.setFrameRate(100.0);
    QSignalSpy changed(&timeline, &TimelineWidget::frameChanged);
    timeline.play();
    QTest::qWait(300);  // ~30 frames through a 5-frame clip
    timeline.pause();
    QVERIFY(timeline.isLooping());
    bool wrapped = false;
    for (int i = 1; i < changed.count(); ++i)
      wrapped = wrapped || changed.at(i).at(0).toInt() < changed.at(i - 1).at(0).toInt();
    QVERIFY2(wrapped, "looping playback never went back to an earlier frame");
  }

  void speedIsClampedToTheSupportedRange() {
    TimelineWidget timeline;
    timeline.setSpeed(10.0);
    QCOMPARE(timeline.speed(), 2.0);
    timeline.setSpeed(0.0);
    QCOMPARE(timeline.speed(), 0.25);
  }

  void trackPaintingEmitsAsTheStrokeGrowsAndOnRelease() {
    TrackView tracks;
    tracks.setFrameCount(100);
    QCOMPARE(tracks.addBoolTrack(QStringLiteral("Left foot"), Qt::yellow), 0);
    QCOMPARE(tracks.addBoolTrack(QStringLiteral("Right foot"), Qt::cyan, std::vector<bool>(100, true)), 1);
    tracks.resize(84 + 6 + 500, tracks.sizeHint().height());  // 5 px per frame
    tracks.show();
    QVERIFY(QTest::qWaitForWindowExposed(&tracks));
    QSignalSpy edited(&tracks, &TrackView::trackEdited);

    const int y0 = tracks.boolTrackRect(0).center().y();
    const auto x = [&](int frame) { return static_cast<int>(tracks.xForFrame(frame)); };
    QCOMPARE(tracks.frameAt(x(10)), 10);
    QTest::mousePress(&tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(10), y0));
    QTest::mouseMove(&tracks, QPoint(x(30), y0));  // a fast drag: frames in between are painted too
    QCOMPARE(edited.count(), 1);                     // while the hand is on it: the result can follow
    QTest::mouseMove(&tracks, QPoint(x(20), y0));   // back inside the stroke: nothing new
    QCOMPARE(edited.count(), 1);
    QTest::mouseRelease(&tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(20), y0));
    QCOMPARE(edited.count(), 2);                     // and the whole stroke on release
    for (const QList<QVariant>& edit : edited) {
      QCOMPARE(edit.at(0).toInt(), 0);
      QCOMPARE(edit.at(1).toInt(), 10);
      QCOMPARE(edit.at(2).toInt(), 30);
      QCOMPARE(edit.at(3).toBool(), true);
    }
    const auto& left = tracks.boolValues(0);
    QVERIFY(!left[9]);
    for (int f = 10; f <= 30; ++f) QVERIFY(left[static_cast<size_t>(f)]);
    QVERIFY(!left[31]);

    // On a frame that is set, the stroke clears.
    const int y1 = tracks.boolTrackRect(1).center().y();
    QTest::mouseClick(&tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(50), y1));
    QCOMPARE(edited.count(), 3);  // a click: the release only
    QCOMPARE(edited.at(2).at(3).toBool(), false);
    QVERIFY(!tracks.boolValues(1)[50]);
    QVERIFY(tracks.boolValues(1)[49]);

    // Read-only tracks ignore strokes.
    tracks.setEditable(false);
    QTest::mouseClick(&tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(70), y0));
    QCOMPARE(edited.count(), 3);
    QVERIFY(!tracks.boolValues(0)[70]);
  }

  // A contact the clean-up does not hold is drawn hatched (not as a held one), and a press on it paints
  // "on" (holds it) where a press on a held contact would clear it.
  void anUnheldContactIsHatchedAndAPressHoldsIt() {
    TrackView tracks;
    tracks.setFrameCount(100);
    tracks.addBoolTrack(QStringLiteral("Left foot"), Qt::yellow, std::vector<bool>(100, true));
    tracks.resize(84 + 6 + 500, tracks.sizeHint().height());  // 5 px per frame
    tracks.show();
    QVERIFY(QTest::qWaitForWindowExposed(&tracks));
    std::vector<bool> unheld(100, false);
    for (int f = 40; f < 60; ++f) unheld[static_cast<size_t>(f)] = true;
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, tracks.setUnheldFrames(1, unheld));
    const auto x = [&](int frame) { return static_cast<int>(tracks.xForFrame(frame)); };
    const int y = tracks.boolTrackRect(0).center().y();
    const QImage held_look = tracks.grab().toImage();
    tracks.setUnheldFrames(0, unheld, QStringLiteral("not held"));
    QCOMPARE(tracks.unheldFrames(0).size(), size_t{100});
    const QImage unheld_look = tracks.grab().toImage();
    QCOMPARE(unheld_look.pixel(x(20), y), held_look.pixel(x(20), y));  // a held contact: as before
    bool differs = false;  // the hatch: some pixels of the unheld run are not the track's colour
    for (int dx = -2; dx <= 2; ++dx) differs = differs || unheld_look.pixel(x(50) + dx, y) != held_look.pixel(x(50) + dx, y);
    QVERIFY(differs);
    QSignalSpy edited(&tracks, &TrackView::trackEdited);
    QTest::mouseClick(&tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(50), y));
    QCOMPARE(edited.count(), 1);
    QCOMPARE(edited.at(0).at(3).toBool(), true);  // held, not cleared
    QVERIFY(tracks.boolValues(0)[50]);
    QTest::mouseClick(&tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(20), y));
    QCOMPARE(edited.at(1).at(3).toBool(), false);  // a held contact still clears
    tracks.setUnheldFrames(0, {});
    QVERIFY(tracks.unheldFrames(0).empty());
  }

  // A contact the clean-up lifts with the style is drawn raised (the bar's lower half cleared; the top
  // as before), explained by its own tool tip, and a press on it toggles it off as on any contact; an
  // unheld frame stays drawn as unheld.
  void aLiftedContactIsDrawnRaised() {
    TrackView tracks;
    tracks.setFrameCount(100);
    tracks.addBoolTrack(QStringLiteral("Left foot"), Qt::yellow, std::vector<bool>(100, true));
    tracks.resize(84 + 6 + 500, tracks.sizeHint().height());  // 5 px per frame
    tracks.show();
    QVERIFY(QTest::qWaitForWindowExposed(&tracks));
    std::vector<bool> lifted(100, false);
    for (int f = 40; f < 60; ++f) lifted[static_cast<size_t>(f)] = true;
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, tracks.setLiftedFrames(1, lifted));
    const auto x = [&](int frame) { return static_cast<int>(tracks.xForFrame(frame)); };
    const QRect row = tracks.boolTrackRect(0);
    const int upper = row.top() + row.height() / 4 + 1, lower = row.top() + 3 * row.height() / 4;
    const QImage on_look = tracks.grab().toImage();
    tracks.setLiftedFrames(0, lifted, QStringLiteral("lifted"));
    QCOMPARE(tracks.liftedFrames(0).size(), size_t{100});
    const QImage lifted_look = tracks.grab().toImage();
    QCOMPARE(lifted_look.pixel(x(20), lower), on_look.pixel(x(20), lower));  // not lifted: as before
    QCOMPARE(lifted_look.pixel(x(50), upper), on_look.pixel(x(50), upper));  // the raised bar's top
    QVERIFY(lifted_look.pixel(x(50), lower) != on_look.pixel(x(50), lower));  // cleared under it
    std::vector<bool> unheld(100, false);
    unheld[50] = true;
    tracks.setUnheldFrames(0, unheld);
    const QImage unheld_look = tracks.grab().toImage();
    bool hatched = false;  // hatched instead: the bar's top no longer the track's colour throughout
    for (int dx = -2; dx <= 2; ++dx) hatched = hatched || unheld_look.pixel(x(50) + dx, upper) != lifted_look.pixel(x(50) + dx, upper);
    QVERIFY(hatched);
    QSignalSpy edited(&tracks, &TrackView::trackEdited);
    QTest::mouseClick(&tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(45), row.center().y()));
    QCOMPARE(edited.count(), 1);
    QCOMPARE(edited.at(0).at(3).toBool(), false);  // a lifted contact clears as any other
    tracks.setLiftedFrames(0, {});
    QVERIFY(tracks.liftedFrames(0).empty());
  }

  void floatTracksStackBelowTheBooleanOnes() {
    TrackView tracks;
    tracks.setFrameCount(50);
    tracks.addBoolTrack(QStringLiteral("Left foot"), Qt::yellow);
    const int height_without = tracks.sizeHint().height();
    QCOMPARE(tracks.addFloatTrack(QStringLiteral("Skate"), Qt::blue), 0);
    QCOMPARE(tracks.addFloatTrack(QStringLiteral("Bone"), Qt::gray), 1);
    QCOMPARE(tracks.floatTrackCount(), 2);
    QCOMPARE(tracks.sizeHint().height(), height_without + 2 * (TrackView::kFloatRowHeight + 2));
    tracks.resize(600, tracks.sizeHint().height());
    QVERIFY(tracks.floatTrackRect(0).top() > tracks.boolTrackRect(0).bottom());
    QVERIFY(tracks.floatTrackRect(1).top() > tracks.floatTrackRect(0).bottom());
    QVERIFY(tracks.floatTrackRect(1).bottom() < tracks.sizeHint().height());
    // Values follow the frame count: short input is padded with the minimum, long input cut.
    tracks.setFloatValues(0, {3.0f, 4.0f}, 1.0f, 5.0f);
    QCOMPARE(tracks.floatValues(0).size(), size_t{50});
    QCOMPARE(tracks.floatValues(0)[1], 4.0f);
    QCOMPARE(tracks.floatValues(0)[2], 1.0f);
    tracks.setFloatValues(1, std::vector<float>(80, 2.0f), 0.0f, 1.0f);
    QCOMPARE(tracks.floatValues(1).size(), size_t{50});
    tracks.setFrameCount(60);
    QCOMPARE(tracks.floatValues(0).size(), size_t{60});
    QCOMPARE(tracks.floatValues(0)[59], 1.0f);
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, tracks.setFloatValues(2, {}, 0.0f, 1.0f));
    tracks.clearTracks();
    QCOMPARE(tracks.floatTrackCount(), 0);
  }

  // A long clip has many frames per pixel: each pixel column shows the highest value of its frames, so a
  // one-frame spike (a foot skating for one frame of a 36,000-frame take) stays visible.
  void aOneFrameSpikeInALongTrackIsDrawn() {
    TrackView tracks;
    tracks.setFrameCount(36000);
    tracks.addFloatTrack(QStringLiteral("Skate"), QColor(40, 160, 255));
    tracks.resize(700, tracks.sizeHint().height());
    std::vector<float> values(36000, 0.0f);
    const int spike = 20011;
    values[static_cast<size_t>(spike)] = 10.0f;
    tracks.setFloatValues(0, values, 0.0f, 10.0f);
    const QImage image = tracks.grab().toImage();
    const QRect row = tracks.floatTrackRect(0);
    // The highest row of the track that the curve reaches, near x and far from it.
    const auto topOfCurve = [&](int x) {
      const QRgb background = image.pixel(x, row.top() + 1);
      for (int y = row.top() + 1; y < row.bottom(); ++y)
        if (image.pixel(x, y) != background) return y;
      return row.bottom();
    };
    const int x = static_cast<int>(tracks.xForFrame(spike));
    int highest = row.bottom();
    for (int dx = -1; dx <= 1; ++dx) highest = std::min(highest, topOfCurve(x + dx));
    QVERIFY2(highest < row.top() + row.height() / 3, qPrintable(QStringLiteral("the spike reaches row %1 of %2-%3")
                                                                    .arg(highest).arg(row.top()).arg(row.bottom())));
    QVERIFY(topOfCurve(static_cast<int>(tracks.xForFrame(5000))) > row.bottom() - 4);  // flat elsewhere
  }

  void rulerScrubsTheTimeline() {
    TimelineWidget timeline;
    timeline.setFrameCount(200);
    timeline.resize(1000, 180);
    timeline.show();
    QVERIFY(QTest::qWaitForWindowExposed(&timeline));
    TrackView* tracks = timeline.trackView();
    const QPoint target(static_cast<int>(tracks->xForFrame(150)), tracks->rulerRect().center().y());
    QTest::mouseClick(tracks, Qt::LeftButton, Qt::NoModifier, target);
    QCOMPARE(timeline.frame(), 150);
    QCOMPARE(tracks->playhead(), 150);
  }

  // A click on the scrub bar beside its handle jumps there (QSlider's own click steps one page, ten
  // frames, towards it), and the same press drags on from there.
  void clickingTheScrubBarJumpsToThatFrame() {
    TimelineWidget timeline;
    timeline.setFrameCount(401);
    timeline.resize(1000, 180);
    timeline.show();
    QVERIFY(QTest::qWaitForWindowExposed(&timeline));
    auto* slider = timeline.findChild<QSlider*>(QStringLiteral("ScrubSlider"));
    QVERIFY(slider != nullptr);
    const int y = slider->height() / 2;
    // The handle's centre runs from half a handle in from the left end to half a handle from the right.
    const auto x = [&](double share) { return static_cast<int>(std::lround(8 + share * (slider->width() - 16))); };
    QTest::mouseClick(slider, Qt::LeftButton, Qt::NoModifier, QPoint(x(0.75), y));
    QVERIFY2(std::abs(timeline.frame() - 300) <= 8, qPrintable(QString::number(timeline.frame())));
    QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, QPoint(x(0.25), y));
    QVERIFY2(std::abs(timeline.frame() - 100) <= 8, qPrintable(QString::number(timeline.frame())));
    QTest::mouseMove(slider, QPoint(x(0.5), y));
    QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, QPoint(x(0.5), y));
    QVERIFY2(std::abs(timeline.frame() - 200) <= 8, qPrintable(QString::number(timeline.frame())));
  }

  void screenshot() {
    TimelineWidget timeline;
    timeline.setFrameCount(720);
    timeline.setFrameRate(120.0);
    TrackView* tracks = timeline.trackView();
    std::vector<bool> left(720);
    std::vector<bool> right(720);
    std::vector<float> quality(720);
    for (size_t f = 0; f < 720; ++f) {
      left[f] = (f / 60) % 2 == 0;
      right[f] = (f / 60) % 2 == 1 || f % 60 < 10;
      quality[f] = 0.5f + 0.4f * static_cast<float>(std::sin(static_cast<double>(f) / 50.0));
    }
    tracks->addBoolTrack(QStringLiteral("Left foot"), QColor(240, 170, 60), left);
    tracks->addBoolTrack(QStringLiteral("Right foot"), QColor(90, 200, 220), right);
    tracks->setFloatValues(tracks->addFloatTrack(QStringLiteral("Skate cm/s"), QColor(120, 170, 230)), quality, 0.0f, 1.0f);
    std::vector<float> bone_error(quality.rbegin(), quality.rend());
    tracks->setFloatValues(tracks->addFloatTrack(QStringLiteral("Raw bone cm"), QColor(170, 170, 175)), bone_error, 0.0f, 1.0f);
    timeline.setFrame(250);
    timeline.resize(1200, timeline.sizeHint().height());
    timeline.show();
    QVERIFY(QTest::qWaitForWindowExposed(&timeline));
    QVERIFY(!test::saveScreenshot(timeline.grab().toImage(), QStringLiteral("timeline")).isEmpty());
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(TimelineTest)
#include "test_timeline.moc"
