#include "optimise_tab.h"

#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include "style/optimization_transfer.h"

namespace motionstyle {

OptimiseTab::OptimiseTab(QWidget* parent) : QWidget(parent) {
  auto* text = new QLabel(tr("The optimisation method (Holden et al. 2016): no trained network; the content clip's "
                             "hidden units are optimised towards the style clip's Gram matrix with the loss "
                             "network chosen on the Train tab, then the foot, bone and trajectory constraints. Slower than a "
                             "trained network, for one style clip."),
                          this);
  text->setWordWrap(true);
  iterations_spin_ = new QSpinBox(this);
  iterations_spin_->setObjectName(QStringLiteral("Iterations"));
  iterations_spin_->setRange(1, 100000);
  iterations_spin_->setValue(style::OptimizationOptions{}.iterations);
  style_weight_ = new QDoubleSpinBox(this);
  style_weight_->setObjectName(QStringLiteral("OptimiseStyleWeight"));
  style_weight_->setRange(0.0, 1e4);
  style_weight_->setDecimals(2);
  style_weight_->setValue(style::OptimizationOptions{}.style_weight);
  style_weight_->setToolTip(tr("How hard the style clip's Gram matrix pulls against the content "
                               "(content weight 1; both are renormalised to sum 1)"));
  optimise_button_ = new QPushButton(tr("&Optimise"), this);
  optimise_button_->setObjectName(QStringLiteral("OptimiseButton"));
  cancel_button_ = new QPushButton(tr("Cancel"), this);
  connect(optimise_button_, &QPushButton::clicked, this, [this] { emit optimiseRequested(iterations_spin_->value()); });
  connect(cancel_button_, &QPushButton::clicked, this, &OptimiseTab::cancelRequested);
  auto* form = new QFormLayout;
  form->addRow(tr("Iterations"), iterations_spin_);
  form->addRow(tr("Style weight"), style_weight_);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(optimise_button_);
  buttons->addWidget(cancel_button_);
  buttons->addStretch(1);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(text);
  layout->addLayout(form);
  layout->addLayout(buttons);
  layout->addStretch(1);
}

int OptimiseTab::iterations() const { return iterations_spin_->value(); }
double OptimiseTab::styleWeight() const { return style_weight_->value(); }

void OptimiseTab::setRunState(bool can_start, bool running) {
  optimise_button_->setEnabled(can_start);
  cancel_button_->setEnabled(running);
}

}  // namespace motionstyle
