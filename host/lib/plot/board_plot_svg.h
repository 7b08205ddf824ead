// The board plot as SVG written as plain text: the same picture as the PNG (cairo), without
// loading cairo and fontconfig for a vector file (a board command's start-up, issue 24).
#ifndef HOST_LIB_PLOT_BOARD_PLOT_SVG_H
#define HOST_LIB_PLOT_BOARD_PLOT_SVG_H

#include <string>  // std::string

#include "host/lib/plot/board_plot.h"  // BoardPlotInput, PlotFrame

namespace host {

// The SVG document of the plot, height_px high, drawn through frame f.
std::string board_plot_svg(const BoardPlotInput& in, const PlotFrame& f, int height_px);

// Writes board_plot_svg to path; throws std::runtime_error naming path when it cannot.
void write_board_plot_svg(const BoardPlotInput& in, const PlotFrame& f, int height_px,
                          const std::string& path);

}  // namespace host

#endif  // HOST_LIB_PLOT_BOARD_PLOT_SVG_H
