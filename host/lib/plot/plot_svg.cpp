// The plan plot as plain SVG text (see plot_svg.h). Each part is drawn as plot.cpp's cairo
// renderer draws it, in the same order and colours.
#include "host/lib/plot/plot_svg.h"

#include <sstream>  // std::ostringstream

#include "host/lib/plot/cairo_plot.h"  // nice_length
#include "host/lib/plot/plot_layers.h"
#include "host/lib/plot/svg_text.h"

namespace host {

namespace {

using namespace plot_layers;  // NOLINT: the layout and colours

// The start of a stroked path's element: colour, width, round ends, dashes.
void stroke_style(SvgText& svg, const Rgb& c, double width, bool dashed) {
  svg << "<path fill=\"none\" stroke=\"";
  svg.colour(c.r, c.g, c.b) << "\" stroke-width=\"" << width
                            << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
  if (dashed) svg << " stroke-dasharray=\"" << kDashPx[0] << " " << kDashPx[1] << "\"";
}

// A layer as one path element, its polylines thinned as cairo's are.
void layer_path(SvgText& svg, const Layer& layer, const PlotFrame& f) {
  SvgText d;
  layer.each([&](const std::vector<Point2>& pts) {
    bool second = false;  // "M x y L x y x y ...", as the board plot writes it
    thin_polyline(f, pts, [&d, &second](const Point2& p, bool first) {
      d << (first ? (d.out.empty() ? "M" : " M") : second ? " L" : " ");
      d.point(p);
      second = first;
    });
  });
  if (d.out.empty()) return;
  stroke_style(svg, layer.colour, layer.width, layer.dashed);
  svg << " d=\"" << d.out << "\"/>\n";
}

void text_at(SvgText& svg, double x, double y, const std::string& s) {
  svg << "<text x=\"" << x << "\" y=\"" << y << "\">";
  svg.text(s) << "</text>\n";
}

void legend_entry(SvgText& svg, double x, double y, const Rgb& c, double width, bool dashed,
                  const std::string& label) {
  stroke_style(svg, c, width, dashed);
  svg << " d=\"M" << x << " " << y << " L" << x + 30 << " " << y << "\"/>\n";
  text_at(svg, x + 36, y + 4, label);
}

// Title, legend and scale bar (as draw_scale_bar draws it, with round ends).
void labels(SvgText& svg, const PlotInput& in, double bar_mm, double px_per_mm) {
  svg << "<g font-family=\"sans-serif\" font-weight=\"bold\" font-size=\"16\">\n";
  text_at(svg, kSideMarginPx, kTitleBaselinePx, in.title);
  svg << "</g>\n<g font-family=\"sans-serif\" font-size=\"12\">\n";
  const double y = in.height_px - kBottomBandPx / 2;
  legend_entry(svg, kSideMarginPx, y, kDrawingColour, kDrawingWidthPx, false, "drawing");
  legend_entry(svg, kSideMarginPx + 120, y, kCutColour, kCutWidthPx, false, "tool path (pen down)");
  legend_entry(svg, kSideMarginPx + 320, y, kRapidColour, kRapidWidthPx, true, "rapid (pen up)");
  const double x1 = in.width_px - kSideMarginPx, x0 = x1 - bar_mm * px_per_mm;
  stroke_style(svg, Rgb{0, 0, 0}, 2.0, false);
  svg << " d=\"M" << x0 << " " << y - 5 << " L" << x0 << " " << y << " " << x1 << " " << y << " "
      << x1 << " " << y - 5 << "\"/>\n";
  std::ostringstream label;
  label << bar_mm << " mm";
  text_at(svg, x0, y + 16, label.str());
  svg << "</g>\n";
}

}  // namespace

bool plot_fits_plain_svg(const PlotInput& in) {
  const PlotFrame f = plot_frame(in);
  for (const Layer& layer : layers(in)) {
    if (layer_vertices(layer, f) > kMaxSvgVertices) return false;
  }
  return true;
}

std::string plot_svg(const PlotInput& in) {
  const PlotFrame f = plot_frame(in);
  const double bar_mm = nice_length(in.width_px / 5.0 / f.scale_px_per_mm);
  SvgText svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << in.width_px << "pt\" height=\""
      << in.height_px << "pt\" viewBox=\"0 0 " << in.width_px << " " << in.height_px << "\">\n";
  std::ostringstream bar;
  bar << bar_mm;
  svg << "<title>";
  svg.text(in.title) << "</title>\n<desc>Legend: drawing (light blue, wide); tool path (pen down) "
                        "(red); rapid (pen up) (grey, dashed). Scale bar: "
                     << bar.str() << " mm.</desc>\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"rgb(255,255,255)\"/>\n";
  for (const Layer& layer : layers(in)) layer_path(svg, layer, f);
  labels(svg, in, bar_mm, f.scale_px_per_mm);
  svg << "</svg>\n";
  return svg.out;
}

}  // namespace host
