// SVG and PNG plots of a drawing's curves against a tool path: pen-down segments solid,
// pen-up moves dashed, with a legend, a scale bar and a title. The SVG is plain text (cairo
// only draws a layer too large for vectors into it as an image); the PNG is cairo's.
#ifndef HOST_LIB_PLOT_PLOT_H
#define HOST_LIB_PLOT_PLOT_H

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

#include "host/lib/drawing/bspline.h"
#include "host/lib/plan/pen_path.h"
#include "host/lib/plot/polylines.h"

namespace host {

struct PlotInput {
  std::string title;
  Polylines drawing_curves_mm;  // each curve sampled as a polyline
  PenPath tool_path;            // pen down solid, pen up dashed
  int width_px = 1000;          // PNG size in pixels (SVG: the same numbers in points)
  int height_px = 750;
};

// How mm map to image pixels (x right, y up in mm; y down in pixels).
struct PlotFrame {
  double scale_px_per_mm = 1.0;
  double origin_x_px = 0.0;  // pixel of x = 0 mm
  double origin_y_px = 0.0;  // pixel of y = 0 mm
  Point2 to_px(const Point2& mm) const {
    return Point2(origin_x_px + mm.x() * scale_px_per_mm, origin_y_px - mm.y() * scale_px_per_mm);
  }
};

// The frame write_plot uses: all curves and the tool path fitted, aspect kept, inside the
// area left by the title (top) and the legend and scale bar (bottom).
PlotFrame plot_frame(const PlotInput& in);

// Writes the plot; an empty path skips that file. Throws std::runtime_error naming the
// file when it cannot be written.
void write_plot(const PlotInput& in, const std::string& svg_path, const std::string& png_path);

}  // namespace host

#endif  // HOST_LIB_PLOT_PLOT_H
