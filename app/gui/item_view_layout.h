#pragma once
// Lays out an item view's rows now rather than at the event loop's next pass, after its items were
// cleared and filled again.
//
// Why: MainWindow paints the viewport at once after a change (QWidget::repaint), and Qt then paints
// every dirty widget of the window with it. A list with a dirty corner (the focus it just got back from a
// file dialog) was painted in that pass with its layout still pending: the layout ran inside the paint
// and its request to paint the whole list was lost, so a clip opened while the Clips list had the
// keyboard focus stayed off screen until the list was clicked (test newClipRowsAreOnTheScreenWithoutAClick).

#include <QAbstractItemView>

namespace motionstyle {

inline void layOutItemsNow(QAbstractItemView& view) { view.doItemsLayout(); }

}  // namespace motionstyle
