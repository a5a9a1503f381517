// The viewport really renders: a real CMU clip drawn through VTK into the viewport's framebuffer
// object under Xvfb, and painted as an image. Checks the image is not blank, that pixels at the projected hips / head / ankles carry the
// role's colour while the background does not, that figures move with the frame, the layouts, and
// how long a frame takes with three figures.
#include <QElapsedTimer>
#include <QLabel>
#include <QTest>

#include <cmath>
#include <stdexcept>

#include "clip_loader.h"
#include "gui_test_support.h"
#include "mapping/canonical_joints.h"
#include "motion/kinematics.h"

using namespace motionstyle;

namespace {

int jointNamed(const LoadedClip& clip, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    const int joint = clip.motion.skeleton.find(name);
    if (joint >= 0) return joint;
  }
  return -1;
}

}  // namespace

class ViewportRenderTest : public QObject {
  Q_OBJECT

  LoadedClip cmu_;
  LoadedClip zombie_;

  // A pixel in widget coordinates -> the grabbed image (device pixels).
  static QPointF toImage(const QImage& image, QPointF widget_point) {
    return widget_point * image.devicePixelRatio();
  }

 private slots:
  void initTestCase() {
    cmu_ = loadClip(test::fixture(QStringLiteral("cmu_131_01.bvh")).toStdString());
    zombie_ = loadClip(test::fixture(QStringLiteral("zombie.bvh")).toStdString());
    QVERIFY(cmu_.frameCount() > 100);
  }

  // A figure is the body's joints in display space (figureInDisplaySpace): invalid shapes are refused;
  // a reference root above the hips is left out; every kept joint is DisplaySpace::toDisplay's, frame
  // by frame, for real rigs too.
  void aFigureIsTheBodysJointsInDisplaySpace() {
    // Bandai-like: joint 0 stays at the origin, the hips (1) carry the body 5 m away; joint 3 hangs off
    // the reference root, outside the body. Z-up inches, the floor 3 inches down.
    const std::vector<int> parents = {-1, 0, 1, 0};
    Eigen::MatrixXd file(2, 12);
    file << 0, 0, 0, 500, 0, 90, 500, 0, 10, 1, 1, 1,  //
        0, 0, 0, 510, 0, 90, 510, 0, 10, 1, 1, 1;
    DisplaySpace space;
    space.convention.axes << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // file +Z up -> +Y
    space.convention.cm_per_unit = 2.54;
    space.floor_height = 3.0;
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             figureInDisplaySpace(QString(), FigureRole::Output, {-1, 0}, bodySubtree(parents, 1), file, space));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument,
                             figureInDisplaySpace(QString(), FigureRole::Output, parents, bodySubtree({-1, 0}, 1), file, space));
    const BodySubtree body = bodySubtree(parents, 1);
    QCOMPARE(body.kept, (std::vector<int>{1, 2}));
    QCOMPARE(body.new_index, (std::vector<int>{-1, 0, 1, -1}));
    FigureData figure = figureInDisplaySpace(QString(), FigureRole::Output, parents, body, file, space);
    QCOMPARE(figure.parents, (std::vector<int>{-1, 0}));
    QCOMPARE(figure.frame_count, 2);
    QCOMPARE(figure.x(1, 0), 2.54 * 510);  // the hips are joint 0 now: placement and follow use them
    QCOMPARE(figure.y(0, 0), 2.54 * 90 - 2.54 * 3.0);
    QCOMPARE(figure.z(0, 1), 0.0);
    // The contact on the leg (2) is the figure's joint 1; one on the joint outside the body: none.
    Eigen::MatrixXi labels(2, kContactCount);
    labels << 1, 0, 0, 0, 0, 0, 0, 0;
    setBodyContacts(figure, body, {2, 2, 2, 2}, labels);
    QCOMPARE(figure.contact_joints, (std::vector<int>{1, 1, 1, 1}));
    QVERIFY(figure.inContact(0, 0) && !figure.inContact(1, 0));
    figure.validate();
    FigureData outside = figureInDisplaySpace(QString(), FigureRole::Output, parents, body, file, space);
    setBodyContacts(outside, body, {2, 2, 3, 3}, labels);
    QVERIFY(outside.contact_joints.empty());
    QCOMPARE(bodySubtree(parents, 0).kept, (std::vector<int>{0, 1, 2, 3}));  // rooted at its hips: all of it

    for (const LoadedClip* clip : {&cmu_, &zombie_}) {
      const Eigen::MatrixXd world = worldPositions(clip->motion);
      std::vector<int> rig;
      for (const Joint& joint : clip->motion.skeleton.joints) rig.push_back(joint.parent);
      const BodySubtree kept = bodySubtree(rig, (*clip->mapping)[CanonicalJoint::Hips]);
      const FigureData made = figureInDisplaySpace(clip->name, FigureRole::Output, rig, kept, world, clip->display_space);
      made.validate();
      const Eigen::MatrixXd display = clip->display_space.toDisplay(world);
      QCOMPARE(made.frame_count, clip->frameCount());
      for (int f = 0; f < made.frame_count; f += 7)
        for (size_t k = 0; k < kept.kept.size(); ++k) {
          const Eigen::Index column = 3 * kept.kept[k];
          QCOMPARE(made.x(f, static_cast<int>(k)), display(f, column));
          QCOMPARE(made.y(f, static_cast<int>(k)), display(f, column + 1));
          QCOMPARE(made.z(f, static_cast<int>(k)), display(f, column + 2));
        }
    }
  }

  void rejectsInvalidFigures() {
    SkeletonViewport viewport;
    FigureData bad = figureFromClip(cmu_, FigureRole::Content);
    bad.positions.pop_back();
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, viewport.setFigures({bad}));
    bad = figureFromClip(cmu_, FigureRole::Content);
    bad.parents[3] = 7;  // a parent after its child
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, viewport.setFigures({bad}));
    bad = figureFromClip(cmu_, FigureRole::Content);
    bad.contact_joints = {1, 2};
    bad.contacts.assign(static_cast<size_t>(bad.frame_count), 1);  // one flag per frame, two needed
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, viewport.setFigures({bad}));
    bad.contacts.assign(static_cast<size_t>(bad.frame_count) * 2, 1);
    bad.contact_joints = {1, 999};
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, viewport.setFigures({bad}));
    std::vector<FigureData> five(5, figureFromClip(cmu_, FigureRole::Content));
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, viewport.setFigures(five));
    QCOMPARE(viewport.figureCount(), 0);
    QVERIFY(!viewport.projectToWidget(0, 0, 0).has_value());
  }

  void emptyViewportShowsBackdropAndFloor() {
    SkeletonViewport viewport;
    viewport.resize(800, 500);
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    const QImage image = viewport.grabFrame();
    QCOMPARE(image.size(), QSize(800, 500) * image.devicePixelRatio());
    QVERIFY2(test::luminanceVariance(image) > 20.0, "the empty view is blank: VTK did not render");
    QVERIFY(qAlpha(image.pixel(image.width() / 2, image.height() / 2)) == 255);
    test::saveScreenshot(image, QStringLiteral("viewport_empty"));
  }

  // VTK renders only when the scene changed: repainting the widget (an overlay label, an exposed
  // region, a window being composed) shows the last frame again, and the widget's own grab() holds the
  // 3-D view (what a screenshot of the window shows).
  void aRepaintWithoutASceneChangeDoesNotRender() {
    SkeletonViewport viewport;
    viewport.resize(640, 400);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    const QImage first = viewport.grabFrame();
    const int renders = viewport.renderCount();
    QVERIFY(renders >= 1);
    viewport.setEmptyMessage(QStringLiteral("nothing yet"));  // an overlay change
    viewport.repaint();
    const QImage shown = viewport.grab().toImage();
    QCOMPARE(viewport.renderCount(), renders);
    QVERIFY2(test::luminanceVariance(shown) > 50.0, "the widget's own picture of the 3-D view is blank");
    viewport.setFrame(60);  // the scene changed: one render at the next paint
    viewport.repaint();
    viewport.repaint();
    QCOMPARE(viewport.renderCount(), renders + 1);
    QVERIFY(viewport.grabFrame() != first);
    QCOMPARE(viewport.renderCount(), renders + 1);
  }

  void contentFigureIsDrawnWhereItsJointsProject() {
    SkeletonViewport viewport;
    viewport.resize(960, 640);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    viewport.setFrame(60);
    const QImage image = viewport.grabFrame();
    QVERIFY(!test::saveScreenshot(image, QStringLiteral("viewport_cmu_content")).isEmpty());
    QVERIFY2(test::luminanceVariance(image) > 50.0, "the image is blank");

    const int hips = 0;
    const int head = jointNamed(cmu_, {"Head", "head"});
    const int left_ankle = jointNamed(cmu_, {"LeftAnkle", "LeftFoot"});
    const int right_ankle = jointNamed(cmu_, {"RightAnkle", "RightFoot"});
    QVERIFY(head > 0 && left_ankle > 0 && right_ankle > 0);
    for (const int joint : {hips, head, left_ankle, right_ankle}) {
      const auto point = viewport.projectToWidget(0, joint, 60);
      QVERIFY(point.has_value());
      QVERIFY2(viewport.rect().contains(point->toPoint()), "joint projects outside the view");
      const int green = test::countAround(image, toImage(image, *point), 3, test::isGreenish);
      QVERIFY2(green >= 5, qPrintable(QStringLiteral("joint %1 (%2) at (%3, %4): only %5 of 49 pixels are green")
                                          .arg(joint)
                                          .arg(QString::fromStdString(cmu_.motion.skeleton.joints[static_cast<size_t>(joint)].name))
                                          .arg(point->x())
                                          .arg(point->y())
                                          .arg(green)));
    }
    // The top-right corner is backdrop: not the figure's colour.
    const QPointF corner(image.width() - 3, 3);
    QCOMPARE(test::countAround(image, corner, 2, test::isGreenish), 0);
    // And no stray green far from the figure: the hips' mirror position across the view.
    const auto hip_point = viewport.projectToWidget(0, hips, 60);
    const QPointF mirrored(viewport.width() - hip_point->x() + (hip_point->x() > viewport.width() / 2 ? -150 : 150),
                           hip_point->y());
    QCOMPARE(test::countAround(image, toImage(image, mirrored), 3, test::isGreenish), 0);
  }

  void footContactsAreMarkedOnTheFloor() {
    const int left_ankle = jointNamed(cmu_, {"LeftAnkle", "LeftFoot"});
    const int right_ankle = jointNamed(cmu_, {"RightAnkle", "RightFoot"});
    const auto greenUnderFeet = [&](bool in_contact) {
      FigureData figure = figureFromClip(cmu_, FigureRole::Content);
      figure.contact_joints = {left_ankle, right_ankle};
      figure.contacts.assign(static_cast<size_t>(figure.frame_count) * 2, in_contact ? 1 : 0);
      SkeletonViewport viewport;
      viewport.resize(800, 600);
      viewport.setFigures({figure});
      viewport.show();
      if (!QTest::qWaitForWindowExposed(&viewport)) return -1;
      const QImage image = viewport.grabFrame();
      if (in_contact) test::saveScreenshot(image, QStringLiteral("viewport_contacts"));
      int green = 0;
      for (const int joint : {left_ankle, right_ankle}) {
        // The disc lies on the floor below the ankle: lower on screen, within a few tens of pixels.
        const QPointF ankle = toImage(image, *viewport.projectToWidget(0, joint, 0));
        for (int dy = 4; dy <= 48; dy += 4)
          for (int dx = -24; dx <= 24; dx += 4) green += test::isGreenish(image.pixel((ankle + QPointF(dx, dy)).toPoint()));
      }
      return green;
    };
    const int without = greenUnderFeet(false);
    const int with = greenUnderFeet(true);
    QVERIFY2(with > without + 20, qPrintable(QStringLiteral("green pixels around the feet: %1 with contacts, %2 without")
                                                 .arg(with)
                                                 .arg(without)));
  }

  void figuresMoveWithTheFrameInFixedMode() {
    SkeletonViewport viewport;
    viewport.resize(800, 500);
    viewport.setCameraMode(SkeletonViewport::CameraMode::Fixed);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    const QPointF start = *viewport.projectToWidget(0, 0, 0);
    const QPointF later = *viewport.projectToWidget(0, 0, cmu_.frameCount() - 1);
    // The CMU clip walks: its hips travel across the fixed view.
    QVERIFY2(QLineF(start, later).length() > 20.0, "the root did not move on screen");
    viewport.setFrame(cmu_.frameCount() - 1);
    const QImage image = viewport.grabFrame();
    QVERIFY(test::countAround(image, toImage(image, later), 3, test::isGreenish) >= 5);
  }

  void followCameraKeepsTheCharacterInPlace() {
    SkeletonViewport viewport;
    viewport.resize(800, 500);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    QCOMPARE(viewport.cameraMode(), SkeletonViewport::CameraMode::Follow);
    viewport.setFrame(0);
    const QPointF start = *viewport.projectToWidget(0, 0, 0);
    viewport.setFrame(cmu_.frameCount() - 1);
    const QPointF later = *viewport.projectToWidget(0, 0, cmu_.frameCount() - 1);
    // The camera moved with the hips on the floor plane; only depth/height changes remain.
    QVERIFY2(std::abs(later.x() - start.x()) < 60.0,
             qPrintable(QStringLiteral("hips moved from %1 to %2 px").arg(start.x()).arg(later.x())));
  }

  void rolesKeepTheirColoursSideBySideAndOverlaid() {
    SkeletonViewport viewport;
    viewport.resize(1100, 600);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content), figureFromClip(zombie_, FigureRole::Style)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    QCOMPARE(viewport.layout(), SkeletonViewport::Layout::SideBySide);
    QImage image = viewport.grabFrame();
    test::saveScreenshot(image, QStringLiteral("viewport_side_by_side"));
    const QPointF content_hips = *viewport.projectToWidget(0, 0, 0);
    const QPointF style_hips = *viewport.projectToWidget(1, 0, 0);
    QVERIFY2(QLineF(content_hips, style_hips).length() > 80.0, "side by side figures overlap");
    QVERIFY(test::countAround(image, toImage(image, content_hips), 3, test::isGreenish) >= 5);
    QVERIFY(test::countAround(image, toImage(image, style_hips), 3, test::isReddish) >= 5);

    viewport.setLayout(SkeletonViewport::Layout::Overlay);
    image = viewport.grabFrame();
    test::saveScreenshot(image, QStringLiteral("viewport_overlay"));
    const QPointF content_overlaid = *viewport.projectToWidget(0, 0, 0);
    const QPointF style_overlaid = *viewport.projectToWidget(1, 0, 0);
    // Both start on the origin of the floor; their hips differ only in height, which the camera
    // (no roll, Y up) shows as a vertical offset.
    QVERIFY2(std::abs(content_overlaid.x() - style_overlaid.x()) < 25.0,
             qPrintable(QStringLiteral("overlaid hips %1 px apart sideways").arg(content_overlaid.x() - style_overlaid.x())));
  }

  void sideBySideFiguresWalkInLanesAndTheFollowCameraKeepsThemAll() {
    // Issue 14: side by side, clips that walk in different directions at different speeds drifted
    // apart and the follow camera lost them. Each figure now walks in its own lane along the content's
    // direction, and the follow camera backs off when the group outgrows the view.
    SkeletonViewport viewport;
    viewport.resize(900, 500);
    // At one rate, as the app shows them (the timeline's).
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content, cmu_.fps()),
                         figureFromClip(zombie_, FigureRole::Style, cmu_.fps())});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    QCOMPARE(viewport.layout(), SkeletonViewport::Layout::SideBySide);
    QCOMPARE(viewport.cameraMode(), SkeletonViewport::CameraMode::Follow);
    const int frames = viewport.frameCount();
    const double margin = 0.03 * viewport.width();
    int outside = 0;
    QString first_miss;
    double widest_gap = 0.0;
    for (int frame = 0; frame < frames; frame += 12) {
      viewport.setFrame(frame);
      for (int figure = 0; figure < 2; ++figure)
        for (int joint = 0; joint < viewport.figure(figure).jointCount(); ++joint) {
          const QPointF p = *viewport.projectToWidget(figure, joint, frame);
          if (p.x() < margin || p.x() > viewport.width() - margin || p.y() < 0 || p.y() > viewport.height()) {
            if (outside++ == 0)
              first_miss = QStringLiteral("figure %1 joint %2 at frame %3: (%4, %5)")
                               .arg(figure).arg(joint).arg(frame).arg(p.x()).arg(p.y());
          }
        }
      widest_gap = std::max(widest_gap, QLineF(*viewport.projectToWidget(0, 0, frame), *viewport.projectToWidget(1, 0, frame)).length());
    }
    QVERIFY2(outside == 0, qPrintable(QStringLiteral("%1 joints outside the view, first %2").arg(outside).arg(first_miss)));
    // In lanes, the two stay about a lane apart on screen (they drifted across the whole view).
    QVERIFY2(widest_gap < 0.5 * viewport.width(), qPrintable(QStringLiteral("hips up to %1 px apart").arg(widest_gap)));
    viewport.setFrame(frames - 1);
    test::saveScreenshot(viewport.grabFrame(), QStringLiteral("viewport_side_by_side_end"));
  }

  void cameraInteractionMovesTheView() {
    SkeletonViewport viewport;
    viewport.resize(800, 500);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    const auto head = [&] { return *viewport.projectToWidget(0, jointNamed(cmu_, {"Head"}), 0); };
    const QPointF start = head();
    // Orbit: left drag.
    QTest::mousePress(&viewport, Qt::LeftButton, Qt::NoModifier, QPoint(400, 250));
    QTest::mouseMove(&viewport, QPoint(500, 250));
    QTest::mouseRelease(&viewport, Qt::LeftButton, Qt::NoModifier, QPoint(500, 250));
    QVERIFY(QLineF(start, head()).length() > 2.0);
    // Reset returns to the framing.
    viewport.resetCamera();
    QVERIFY(QLineF(start, head()).length() < 1.0);
    // Pan: shift + left drag moves the head by about the drag.
    QTest::mousePress(&viewport, Qt::LeftButton, Qt::ShiftModifier, QPoint(400, 250));
    QTest::mouseMove(&viewport, QPoint(450, 280), 0);
    QTest::mouseRelease(&viewport, Qt::LeftButton, Qt::ShiftModifier, QPoint(450, 280));
    const QPointF panned = head();
    QVERIFY2(std::abs(panned.x() - start.x() - 50.0) < 15.0 && std::abs(panned.y() - start.y() - 30.0) < 15.0,
             qPrintable(QStringLiteral("pan moved the head by (%1, %2)").arg(panned.x() - start.x()).arg(panned.y() - start.y())));
    // Zoom: the wheel brings the figure closer, so joints spread apart on screen.
    viewport.resetCamera();
    const auto spread = [&] { return QLineF(*viewport.projectToWidget(0, 0, 0), head()).length(); };
    const double before = spread();
    QWheelEvent wheel(QPointF(400, 250), viewport.mapToGlobal(QPointF(400, 250)), QPoint(), QPoint(0, 240),
                      Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(&viewport, &wheel);
    QVERIFY(spread() > before * 1.2);
    for (int notch = 0; notch < 3; ++notch) QApplication::sendEvent(&viewport, &wheel);  // a close-up
    const double zoomed = spread();
    // Playing on in follow mode keeps the user's close-up of a single figure (the camera backs off only
    // to keep several figures in view).
    QCOMPARE(viewport.cameraMode(), SkeletonViewport::CameraMode::Follow);
    viewport.setFrame(10);
    viewport.setFrame(20);
    const int head_joint = jointNamed(cmu_, {"Head"});
    const double later = QLineF(*viewport.projectToWidget(0, 0, 20), *viewport.projectToWidget(0, head_joint, 20)).length();
    QVERIFY2(later > 0.8 * zoomed, qPrintable(QStringLiteral("hips-head %1 px after playing, %2 px zoomed").arg(later).arg(zoomed)));
  }

  // At reduced resolution (a drag: LiveResolution) the frame has half the pixels across and down and
  // is scaled up to the whole widget: joints appear where they project, as at full resolution.
  void aReducedResolutionFrameFillsTheView() {
    SkeletonViewport viewport;
    viewport.resize(900, 600);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content)});
    viewport.setFrame(60);
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    viewport.setReducedResolution(true);
    QCOMPARE(viewport.grabFrame().size(), QSize(450, 300) * viewport.devicePixelRatio());
    const QImage shown = viewport.grab().toImage();  // what the screen shows: the widget's own paint
    QVERIFY(!test::saveScreenshot(shown, QStringLiteral("viewport_reduced")).isEmpty());
    const int head = jointNamed(cmu_, {"Head", "head"});
    const int right_ankle = jointNamed(cmu_, {"RightAnkle", "RightFoot"});
    for (const int joint : {0, head, right_ankle}) {
      const auto point = viewport.projectToWidget(0, joint, 60);
      QVERIFY(point.has_value());
      const int green = test::countAround(shown, toImage(shown, *point), 3, test::isGreenish);
      QVERIFY2(green >= 5, qPrintable(QStringLiteral("joint %1 at (%2, %3): only %4 of 49 pixels are green")
                                          .arg(joint).arg(point->x()).arg(point->y()).arg(green)));
    }
    viewport.setReducedResolution(false);
    QCOMPARE(viewport.grabFrame().size(), QSize(900, 600) * viewport.devicePixelRatio());
  }

  // A new figure with the skeleton of the one it replaces (every live edit's result) reuses its VTK
  // pipeline: it must still be drawn with its own colour, pose and size.
  void aFigureReplacedByOneWithTheSameSkeletonIsDrawnAnew() {
    SkeletonViewport viewport;
    viewport.resize(800, 560);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Output)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    viewport.grabFrame();
    // Green (content) where blue (output) was, the same skeleton 20 % smaller, at another frame.
    FigureData smaller = figureFromClip(cmu_, FigureRole::Content);
    for (double& value : smaller.positions) value *= 0.8;
    viewport.setFigures({smaller});
    viewport.setFrame(90);
    const QImage image = viewport.grabFrame();
    const int head = jointNamed(cmu_, {"Head", "head"});
    for (const int joint : {0, head}) {
      const auto point = viewport.projectToWidget(0, joint, 90);
      QVERIFY(point.has_value());
      const int green = test::countAround(image, toImage(image, *point), 3, test::isGreenish);
      QVERIFY2(green >= 5, qPrintable(QStringLiteral("joint %1: only %2 of 49 pixels are green").arg(joint).arg(green)));
    }
    viewport.setFigures({figureFromClip(zombie_, FigureRole::Content)});  // another skeleton: built anew
    QVERIFY(test::luminanceVariance(viewport.grabFrame()) > 50.0);
  }

  // A figure renamed (the result went out of date): the legend says so at once, nothing is rendered.
  void aRenamedFigureChangesOnlyTheLegend() {
    SkeletonViewport viewport;
    viewport.resize(640, 400);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content), figureFromClip(cmu_, FigureRole::Output)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    viewport.grabFrame();
    const int renders = viewport.renderCount();
    QVERIFY_THROWS_EXCEPTION(std::out_of_range, viewport.renameFigure(2, QStringLiteral("none")));
    viewport.renameFigure(1, QStringLiteral("walk (elderly, out of date)"));
    QCOMPARE(viewport.figure(1).name, QStringLiteral("walk (elderly, out of date)"));
    bool in_legend = false;
    for (const QLabel* label : viewport.findChildren<QLabel*>())
      in_legend = in_legend || (label->isVisible() && label->text().contains(QStringLiteral("walk (elderly, out of date)")));
    QVERIFY(in_legend);
    viewport.repaint();
    QCOMPARE(viewport.renderCount(), renders);
  }

  // The camera's clipping range is set from the scene's own bounds (floor and whole clip) rather than
  // computed by VTK at every render: a figure refilled with the same skeleton and lifted 3 m in its
  // second half is drawn where its joints project at every frame. (Gross errors in those bounds fail
  // most tests here; the floor alone already spans this clip's depth, so this test guards the refill.)
  void aRefilledFigureIsDrawnWhereverItGoes() {
    SkeletonViewport viewport;
    viewport.resize(800, 560);
    viewport.setCameraMode(SkeletonViewport::CameraMode::Fixed);
    FigureData lifted = figureFromClip(cmu_, FigureRole::Content);
    const int half = lifted.frame_count / 2;
    for (int f = half; f < lifted.frame_count; ++f)
      for (int j = 0; j < lifted.jointCount(); ++j)
        lifted.positions[(static_cast<size_t>(f) * lifted.parents.size() + static_cast<size_t>(j)) * 3 + 1] += 300.0;
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    viewport.grabFrame();
    viewport.setFigures({lifted});  // the same skeleton: refilled
    const int head = jointNamed(cmu_, {"Head", "head"});
    for (const int frame : {0, half + 10, lifted.frame_count - 1}) {
      viewport.setFrame(frame);
      const QImage image = viewport.grabFrame();
      for (const int joint : {0, head}) {
        const auto point = viewport.projectToWidget(0, joint, frame);
        QVERIFY(point.has_value());
        const int green = test::countAround(image, toImage(image, *point), 3, test::isGreenish);
        QVERIFY2(green >= 5, qPrintable(QStringLiteral("frame %1, joint %2: only %3 of 49 pixels are green")
                                           .arg(frame).arg(joint).arg(green)));
      }
    }
  }

  void threeFiguresPlayAtInteractiveRates() {
    SkeletonViewport viewport;
    viewport.resize(1280, 720);
    viewport.setFigures({figureFromClip(cmu_, FigureRole::Content), figureFromClip(zombie_, FigureRole::Style),
                         figureFromClip(cmu_, FigureRole::Output)});
    viewport.show();
    QVERIFY(QTest::qWaitForWindowExposed(&viewport));
    viewport.grabFrame();  // compile shaders outside the measurement

    // What the viewport itself does per frame: re-pose three skeletons (no pipeline rebuild).
    constexpr int kPoses = 2000;
    QElapsedTimer posing;
    posing.start();
    for (int f = 0; f < kPoses; ++f) viewport.setFrame(f % cmu_.frameCount());
    const double pose_ms = static_cast<double>(posing.nsecsElapsed()) / 1e6 / kPoses;

    // Full frames, rendered synchronously (plus a read-back that a screen update does not pay).
    constexpr int kFrames = 40;
    double render_ms = 0.0;
    QElapsedTimer wall;
    wall.start();
    for (int f = 0; f < kFrames; ++f) {
      viewport.setFrame(f * 8);
      viewport.grabFrame();
      render_ms += viewport.lastRenderMilliseconds();
    }
    const double frame_ms = static_cast<double>(wall.nsecsElapsed()) / 1e6 / kFrames;
    qInfo("three figures (%d, %d, %d joints), 1280x720, %s GL, antialiasing %s: posing %.3f ms, frame %.1f ms "
          "(%.1f fps incl. read-back), of which VTK Render %.1f ms",
          cmu_.motion.skeleton.jointCount(), zombie_.motion.skeleton.jointCount(), cmu_.motion.skeleton.jointCount(),
          viewport.softwareRenderer() ? "software" : "hardware", viewport.antialiasing() ? "on" : "off", pose_ms,
          frame_ms, 1000.0 / frame_ms, render_ms / kFrames);
    test::saveScreenshot(viewport.grabFrame(), QStringLiteral("viewport_three_figures"));
    // Posing must stay far below a 60 fps frame budget (16.7 ms); rebuilding the pipeline per frame
    // would cost milliseconds. Rasterising is the GL's business: under software GL on shared cores it
    // is slow, so only a pathological rate fails.
    QVERIFY2(pose_ms < 1.0, qPrintable(QStringLiteral("posing took %1 ms").arg(pose_ms)));
    QVERIFY2(frame_ms < 1000.0, qPrintable(QStringLiteral("a frame took %1 ms").arg(frame_ms)));
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(ViewportRenderTest)
#include "test_viewport_render.moc"
