// Plot rendering with cairo: the PNG, and the SVG of a plot with a layer too large for
// vectors (an image inside it); other SVGs are plain text (plot_svg.cpp).
#include "host/lib/plot/plot.h"

#include <cairo-svg.h>  // cairo_svg_surface_create
#include <cairo.h>      // cairo_*

#include <algorithm>  // std::min
#include <cmath>      // std::pow, std::floor
#include <fstream>    // std::ifstream, std::ofstream
#include <sstream>    // std::ostringstream

#include "host/lib/plot/cairo_plot.h"  // nice_length, draw_scale_bar, check_cairo_surface
#include "host/lib/plot/plot_layers.h"
#include "host/lib/plot/plot_svg.h"
#include "host/lib/plot/svg_text.h"

namespace host {

namespace {

using namespace plot_layers;  // NOLINT: the layout, colours and layers

void set_colour(cairo_t* cr, const Rgb& c) {
  cairo_set_source_rgb(cr, c.r, c.g, c.b);
}

// Adds a polyline to the current path, thinned (thin_polyline). Returns the vertices added.
size_t add_polyline(cairo_t* cr, const PlotFrame& f, const std::vector<Point2>& pts) {
  return thin_polyline(f, pts, [cr](const Point2& p, bool first) {
    if (first)
      cairo_move_to(cr, p.x(), p.y());
    else
      cairo_line_to(cr, p.x(), p.y());
  });
}

void stroke_layer(cairo_t* cr, const Layer& layer, const PlotFrame& f) {
  set_colour(cr, layer.colour);
  cairo_set_line_width(cr, layer.width);
  cairo_set_dash(cr, kDashPx, layer.dashed ? 2 : 0, 0);
  size_t in_path = 0;
  layer.each([&](const std::vector<Point2>& pts) {
    in_path += add_polyline(cr, f, pts);
    if (in_path > 100000) {  // keeps cairo's path buffer bounded
      cairo_stroke(cr);
      in_path = 0;
    }
  });
  cairo_stroke(cr);
  cairo_set_dash(cr, kDashPx, 0, 0);
}

// A layer too big for vectors, as pixels: round pen stamps every half pixel along each
// polyline into a coverage mask, painted in the layer's colour (dashes are not drawn: at
// this density they would not show). cairo's stroker takes minutes for a million wide strokes;
// this takes well under a second.
void raster_layer(cairo_t* cr, const Layer& layer, const PlotFrame& f, const PlotInput& in) {
  const int w = in.width_px, h = in.height_px;
  cairo_surface_t* mask = cairo_image_surface_create(CAIRO_FORMAT_A8, w, h);
  cairo_surface_flush(mask);
  unsigned char* data = cairo_image_surface_get_data(mask);
  const int stride = cairo_image_surface_get_stride(mask);
  const double r = std::max(0.5, layer.width / 2);
  const int ri = static_cast<int>(std::ceil(r));
  auto stamp = [&](double x, double y) {
    const long cx = std::lround(x), cy = std::lround(y);
    for (int dy = -ri; dy <= ri; ++dy) {
      const long yy = cy + dy;
      if (yy < 0 || yy >= h) continue;
      for (int dx = -ri; dx <= ri; ++dx) {
        const long xx = cx + dx;
        if (xx >= 0 && xx < w && dx * dx + dy * dy <= r * r + 0.25) data[yy * stride + xx] = 255;
      }
    }
  };
  layer.each([&](const std::vector<Point2>& pts) {
    for (size_t i = 0; i < pts.size(); ++i) {
      const Point2 b = f.to_px(pts[i]);
      if (i == 0) {
        stamp(b.x(), b.y());
        continue;
      }
      const Point2 a = f.to_px(pts[i - 1]);
      const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.5)));
      for (int k = 1; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        stamp(a.x() + (b.x() - a.x()) * t, a.y() + (b.y() - a.y()) * t);
      }
    }
  });
  cairo_surface_mark_dirty(mask);
  set_colour(cr, layer.colour);
  cairo_mask_surface(cr, mask, 0, 0);
  cairo_surface_destroy(mask);
}

// Draws a layer: as vectors, or, past kMaxSvgVertices, as an image of the plot's size (the
// SVG stays a few MB and the drawing fast whatever the job's size).
void draw_layer(cairo_t* cr, const Layer& layer, const PlotFrame& f, const PlotInput& in) {
  if (layer_vertices(layer, f) <= kMaxSvgVertices)
    stroke_layer(cr, layer, f);
  else
    raster_layer(cr, layer, f, in);
}

void text(cairo_t* cr, double x, double y, const std::string& s) {
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

void legend_entry(cairo_t* cr, double x, double y, const Rgb& c, double width, bool dashed,
                  const std::string& label) {
  set_colour(cr, c);
  cairo_set_line_width(cr, width);
  cairo_set_dash(cr, kDashPx, dashed ? 2 : 0, 0);
  cairo_move_to(cr, x, y);
  cairo_line_to(cr, x + 30, y);
  cairo_stroke(cr);
  cairo_set_dash(cr, kDashPx, 0, 0);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, x + 36, y + 4, label);
}

void render(cairo_t* cr, const PlotInput& in) {
  const PlotFrame f = plot_frame(in);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const Layer& layer : layers(in)) draw_layer(cr, layer, f, in);
  // Title.
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, 16);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, kSideMarginPx, kTitleBaselinePx, in.title);
  // Legend and scale bar in the bottom band.
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12);
  const double y = in.height_px - kBottomBandPx / 2;
  legend_entry(cr, kSideMarginPx, y, kDrawingColour, kDrawingWidthPx, false, "drawing");
  legend_entry(cr, kSideMarginPx + 120, y, kCutColour, kCutWidthPx, false, "tool path (pen down)");
  legend_entry(cr, kSideMarginPx + 320, y, kRapidColour, kRapidWidthPx, true, "rapid (pen up)");
  draw_scale_bar(cr, nice_length(in.width_px / 5.0 / f.scale_px_per_mm), f.scale_px_per_mm,
                 in.width_px - kSideMarginPx, y);
}

// Text with &, <, > and " escaped for XML.
std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// cairo writes text as glyph outlines; this adds the title and the legend as searchable,
// accessible SVG <title> and <desc> elements right after the <svg> start tag.
void add_svg_text(const std::string& path, const PlotInput& in) {
  std::string svg;
  {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    svg = s.str();
  }
  const size_t tag = svg.find("<svg");
  const size_t end = tag == std::string::npos ? tag : svg.find('>', tag);
  if (end == std::string::npos) throw std::runtime_error(path + ": cairo wrote no <svg> element");
  std::ostringstream add;
  add << "\n<title>" << xml_escape(in.title) << "</title>\n<desc>Legend: drawing (light blue, "
      << "wide); tool path (pen down) (red); rapid (pen up) (grey, dashed). Scale bar: "
      << nice_length(in.width_px / 5.0 / plot_frame(in).scale_px_per_mm) << " mm.</desc>";
  svg.insert(end + 1, add.str());
  std::ofstream o(path, std::ios::binary | std::ios::trunc);
  o << svg;
  if (!o) throw std::runtime_error(path + ": cannot write the plot");
}

}  // namespace

PlotFrame plot_frame(const PlotInput& in) {
  Extents e;
  in.drawing_curves_mm.each([&e](const std::vector<Point2>& c) {
    for (const Point2& p : c) e.add(p);
  });
  for (size_t i = 0; i < in.tool_path.size(); ++i) e.add(in.tool_path.point(i));
  if (e.empty()) e.add(Point2(0, 0));
  const double w = std::max(e.width(), 1e-3), h = std::max(e.height(), 1e-3);
  const double area_w = in.width_px - 2 * kSideMarginPx;
  const double area_h = in.height_px - kTitleBandPx - kBottomBandPx - 2 * kSideMarginPx;
  PlotFrame f;
  f.scale_px_per_mm = std::min(area_w / w, area_h / h);
  // Centre the bounds in the area.
  const double cx = kSideMarginPx + area_w / 2, cy = kTitleBandPx + kSideMarginPx + area_h / 2;
  const Point2 mid = 0.5 * (e.min + e.max);
  f.origin_x_px = cx - mid.x() * f.scale_px_per_mm;
  f.origin_y_px = cy + mid.y() * f.scale_px_per_mm;
  return f;
}

void write_plot(const PlotInput& in, const std::string& svg_path, const std::string& png_path) {
  if (in.width_px < 200 || in.height_px < 200 || in.width_px > 20000 || in.height_px > 20000) {
    throw std::runtime_error("plot size must be 200..20000 pixels each way");
  }
  if (!svg_path.empty() && plot_fits_plain_svg(in)) {
    write_svg_file(plot_svg(in), svg_path);
  } else if (!svg_path.empty()) {
    cairo_surface_t* s = cairo_svg_surface_create(svg_path.c_str(), in.width_px, in.height_px);
    check_cairo_surface(s, svg_path);
    cairo_t* cr = cairo_create(s);
    render(cr, in);
    cairo_destroy(cr);
    cairo_surface_finish(s);
    check_cairo_surface(s, svg_path);
    cairo_surface_destroy(s);
    add_svg_text(svg_path, in);
  }
  if (!png_path.empty()) {
    cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, in.width_px, in.height_px);
    check_cairo_surface(s, png_path);
    cairo_t* cr = cairo_create(s);
    render(cr, in);
    cairo_destroy(cr);
    const cairo_status_t st = cairo_surface_write_to_png(s, png_path.c_str());
    cairo_surface_destroy(s);
    if (st != CAIRO_STATUS_SUCCESS) {
      throw std::runtime_error(png_path + ": cannot write the plot: " + cairo_status_to_string(st));
    }
  }
}

}  // namespace host
