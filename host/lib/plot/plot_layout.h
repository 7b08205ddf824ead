// The bands every plot leaves around its drawing area (the plan plot and the board plot,
// in SVG and PNG alike), so that the pictures share one layout.
#ifndef HOST_LIB_PLOT_PLOT_LAYOUT_H
#define HOST_LIB_PLOT_PLOT_LAYOUT_H

namespace host {
namespace plot_layout {

const double kTitleBandPx = 40.0;      // the title, above the drawing area
const double kTitleBaselinePx = 26.0;  // the title's baseline, inside that band
const double kBottomBandPx = 60.0;     // the legend and the scale bar, below it
const double kSideMarginPx = 20.0;     // around the drawing area and the bands' text

}  // namespace plot_layout
}  // namespace host

#endif  // HOST_LIB_PLOT_PLOT_LAYOUT_H
