#pragma once
// OptimiseTab: the Style networks panel's form for the optimisation method (Holden et al. 2016,
// style/optimization_transfer.h): its iterations and style weight, and the Optimise / Cancel buttons.
// It owns the form only: the owner runs the job (optimiseRequested, cancelRequested) and says whether
// one may start or is running (setRunState).

#include <QWidget>

class QDoubleSpinBox;
class QPushButton;
class QSpinBox;

namespace motionstyle {

class OptimiseTab : public QWidget {
  Q_OBJECT

 public:
  explicit OptimiseTab(QWidget* parent = nullptr);

  int iterations() const;     // stage 1 (the constraint stage gets 100 / 250 of them)
  double styleWeight() const; // s, before renormalisation with the content weight 1
  void setRunState(bool can_start, bool running);

 signals:
  void optimiseRequested(int iterations);
  void cancelRequested();

 private:
  QSpinBox* iterations_spin_ = nullptr;
  QDoubleSpinBox* style_weight_ = nullptr;
  QPushButton* optimise_button_ = nullptr;
  QPushButton* cancel_button_ = nullptr;
};

}  // namespace motionstyle
