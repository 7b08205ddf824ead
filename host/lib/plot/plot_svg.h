// The plan plot as SVG written as plain text: the same layers, colours, legend and scale bar
// as the cairo picture, without loading cairo and fontconfig (`run`'s start-up, issue 24).
#ifndef HOST_LIB_PLOT_PLOT_SVG_H
#define HOST_LIB_PLOT_PLOT_SVG_H

#include <string>  // std::string

#include "host/lib/plot/plot.h"

namespace host {

// True when every layer fits as vectors (plot_layers::kMaxSvgVertices after thinning); a
// larger one goes into the SVG as an image, which cairo draws.
bool plot_fits_plain_svg(const PlotInput& in);

// The SVG document of the plot (every layer as vectors).
std::string plot_svg(const PlotInput& in);

}  // namespace host

#endif  // HOST_LIB_PLOT_PLOT_SVG_H
