#pragma once
// ViewportScene: the VTK pipeline behind SkeletonViewport (INTERNAL header: only .cpp files of this
// library include it; public headers stay free of VTK types).
//
// Built by setFigures() (a figure whose skeleton is unchanged keeps its pipeline): per figure a joints actor (instanced spheres), a bones actor (instanced
// cylinders oriented parent -> joint), a contact-marker actor (flat discs on the floor) and a root
// trajectory polyline; plus one floor (a checker that fades out with distance), a light kit and a
// gradient background. setFrame() only rewrites point coordinates and glyph arrays of existing data
// sets, so playback never rebuilds the pipeline.
//
// Space: figure data are world cm, Y-up. Each figure is drawn placed: its first-frame root on the floor
// plane moves to its lane's start (the origin when overlaid), and side by side it is turned about the
// vertical so that it travels along the content's direction (placeFigures); the placement is applied
// through the actors' origin, orientation and position.

#include <vtkSmartPointer.h>

#include <array>
#include <memory>
#include <vector>

#include "figure_data.h"

class vtkRenderer;

namespace motionstyle::detail {

using Vec3 = std::array<double, 3>;

enum class SceneLayout { SideBySide, Overlay };

class ViewportScene {
 public:
  ViewportScene();
  ~ViewportScene();
  ViewportScene(const ViewportScene&) = delete;
  ViewportScene& operator=(const ViewportScene&) = delete;

  vtkRenderer* renderer() const;

  // Replaces the figures (each already validated) and shows frame 0.
  void setFigures(std::vector<FigureData> figures);
  const std::vector<FigureData>& figures() const { return figures_; }
  void renameFigure(int index, const QString& name) { figures_.at(static_cast<size_t>(index)).name = name; }
  int frameCount() const;  // the longest figure's frames; 0 without figures

  void setLayout(SceneLayout layout);
  SceneLayout layout() const { return layout_; }
  void setTrajectoriesVisible(bool visible);
  bool trajectoriesVisible() const { return trajectories_visible_; }
  // Coarser tessellation of the joint spheres, bone cylinders and contact discs (kept across
  // setFigures until turned off).
  void setCoarseGlyphs(bool coarse);
  // FXAA edge smoothing (one full-screen pass per frame).
  void setAntialiasing(bool on);
  bool antialiasing() const;

  // Poses every figure at `frame`; a figure shorter than that holds its last frame.
  void setFrame(int frame);
  int frame() const { return frame_; }

  // A joint's drawn position (cm, world, placement included) at `frame` (clamped per figure).
  Vec3 drawnJoint(int figure, int joint, int frame) const;
  // The mean drawn root position over all figures at `frame`: what the follow camera tracks.
  Vec3 anchor(int frame) const;
  // Axis-aligned bounds {xmin, xmax, ymin, ymax, zmin, zmax} of the drawn joints at `frame`, or over
  // the whole clip when frame < 0. Without figures: a 2 m box around the origin.
  std::array<double, 6> bounds(int frame) const;
  // A box {xmin, xmax, ymin, ymax, zmin, zmax} that holds everything drawn at any frame (floor,
  // figures, paths): the camera's clipping range is set from it, which VTK would otherwise compute
  // at every render from every actor's bounds (a sixth of a render's cost under software GL).
  const std::array<double, 6>& drawnBounds() const { return drawn_bounds_; }
  // The tallest figure's height in cm (vertical extent of its joints), 170 without figures.
  double characterHeight() const;

 private:
  struct FigureVisual;

  void buildFloor();
  void placeFigures();
  void poseFigure(size_t index);

  vtkSmartPointer<vtkRenderer> renderer_;
  std::vector<FigureData> figures_;
  std::vector<std::unique_ptr<FigureVisual>> visuals_;
  struct Floor;
  std::unique_ptr<Floor> floor_;
  SceneLayout layout_ = SceneLayout::SideBySide;
  int frame_ = 0;
  double floor_height_ = 0.0;
  std::array<double, 6> drawn_bounds_{};
  bool trajectories_visible_ = true;
  bool coarse_glyphs_ = false;
};

}  // namespace motionstyle::detail
