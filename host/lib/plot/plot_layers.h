// The plan plot's layout, colours and layers, shared by its SVG writer (plain text) and its
// cairo renderer (the PNG) so the two pictures stay the same.
#ifndef HOST_LIB_PLOT_PLOT_LAYERS_H
#define HOST_LIB_PLOT_PLOT_LAYERS_H

#include <cmath>       // std::abs
#include <functional>  // std::function
#include <vector>      // std::vector

#include "host/lib/plot/plot.h"
#include "host/lib/plot/plot_layout.h"

namespace host {
namespace plot_layers {

using namespace plot_layout;  // NOLINT: the bands, the same as the board plot's

struct Rgb {
  double r, g, b;
};
const Rgb kDrawingColour = {0.55, 0.75, 0.95};  // light blue, wide: the drawing
const Rgb kCutColour = {0.75, 0.05, 0.05};      // dark red, thin: the pen-down path
const Rgb kRapidColour = {0.45, 0.45, 0.45};    // grey dashed: pen-up moves
const double kDrawingWidthPx = 5.0;
const double kCutWidthPx = 1.2;
const double kRapidWidthPx = 0.8;
const double kDashPx[] = {6.0, 4.0};

const double kMinStepPx = 0.5;          // thinner detail than this is not visible
const size_t kMaxSvgVertices = 150000;  // a layer with more is an image in the SVG (~2.5 MB)

// One layer: a style and its polylines (each handed to the callback), stroked as one path.
struct Layer {
  Rgb colour;
  double width;
  bool dashed;
  std::function<void(const std::function<void(const std::vector<Point2>&)>&)> each;
};

// The drawing underneath, wide; the tool path on top: pen up dashed, pen down solid.
inline std::vector<Layer> layers(const PlotInput& in) {
  auto tool = [&in](bool down) {
    return [&in, down](const std::function<void(const std::vector<Point2>&)>& fn) {
      in.tool_path.each_piece([&fn, down](const std::vector<Point2>& piece, bool d) {
        if (d == down) fn(piece);
      });
    };
  };
  return {Layer{kDrawingColour, kDrawingWidthPx, false,
                [&in](const std::function<void(const std::vector<Point2>&)>& fn) {
                  in.drawing_curves_mm.each(fn);
                }},
          Layer{kRapidColour, kRapidWidthPx, true, tool(false)},
          Layer{kCutColour, kCutWidthPx, false, tool(true)}};
}

// The polyline in pixels, thinned to the plot's resolution: a vertex closer than half a
// pixel to the previous one adds nothing a person could see (the last one is kept). Calls
// to(px, first) for each vertex kept, and once more 0.01 px to the right of a lone vertex
// (a dot, stroked as a round cap). Returns the vertices kept, the dot's second not counted.
template <typename To>
size_t thin_polyline(const PlotFrame& f, const std::vector<Point2>& pts, To to) {
  if (pts.empty()) return 0;
  Point2 last = f.to_px(pts[0]);
  to(last, true);
  size_t n = 1;
  for (size_t i = 1; i < pts.size(); ++i) {
    const Point2 p = f.to_px(pts[i]);
    const bool end = i + 1 == pts.size();
    if (!end && std::abs(p.x() - last.x()) < kMinStepPx && std::abs(p.y() - last.y()) < kMinStepPx)
      continue;
    to(p, false);
    last = p;
    ++n;
  }
  if (n == 1) to(Point2(last.x() + 0.01, last.y()), false);
  return n;
}

// Vertices the layer takes after thinning (what its SVG path would hold).
inline size_t layer_vertices(const Layer& layer, const PlotFrame& f) {
  size_t n = 0;
  layer.each([&](const std::vector<Point2>& pts) {
    n += thin_polyline(f, pts, [](const Point2&, bool) {});
  });
  return n;
}

}  // namespace plot_layers
}  // namespace host

#endif  // HOST_LIB_PLOT_PLOT_LAYERS_H
