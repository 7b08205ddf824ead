// Board plot: the PNG rendered with cairo, the SVG written as text (see board_plot.h).
#include "host/lib/plot/board_plot.h"

#include <cairo.h>  // cairo_*

#include <algorithm>  // std::max
#include <cmath>      // std::pow, std::floor
#include <stdexcept>  // std::runtime_error

#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/plot/board_plot_style.h"
#include "host/lib/plot/board_plot_svg.h"
#include "host/lib/plot/cairo_plot.h"  // nice_length, draw_scale_bar, check_cairo_surface
#include "host/lib/plot/png_rows.h"

namespace host {

namespace {

using namespace board_plot_style;  // NOLINT: the layout and colours

const int kBandRows = 128;  // PNG rows drawn at a time: 0.7 MB at 1 400 px wide

void set(cairo_t* cr, const Rgba& c) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, c.a);
}

}  // namespace

PlotFrame board_plot_frame(const pcb::BoardJob& job, int width_px, int* height_px) {
  Extents e = job.plan.extents_mm;
  for (const pcb::Hole& h : job.holes_machine)
    e.add(pcb::to_mm(ClipperLib::IntPoint(h.at.x, h.at.y)));
  for (const pcb::Island& island : job.copper_machine)
    for (const auto& q : island.paths[0]) e.add(pcb::to_mm(q));  // the holes are inside
  if (e.empty()) e.add(Point2(0, 0));
  const double pad_mm = std::max(job.tool_radius_mm, job.cutter_radius_mm) + 0.5;
  e.add(Point2(e.min.x() - pad_mm, e.min.y() - pad_mm));
  e.add(Point2(e.max.x() + pad_mm, e.max.y() + pad_mm));
  const double area_w = width_px - 2 * kSideMarginPx;
  PlotFrame f;
  f.scale_px_per_mm = area_w / std::max(e.width(), 1e-3);
  const double area_h = e.height() * f.scale_px_per_mm;
  *height_px =
      static_cast<int>(std::ceil(area_h + kTitleBandPx + kBottomBandPx + 2 * kSideMarginPx));
  f.origin_x_px = kSideMarginPx - e.min.x() * f.scale_px_per_mm;
  f.origin_y_px = kTitleBandPx + kSideMarginPx + e.max.y() * f.scale_px_per_mm;
  return f;
}

namespace {

// The rows of the picture being drawn: the whole height for SVG; for the PNG one band at a
// time (the picture is drawn once per band), where a mask of the band's size replaces
// cairo's full-size group surface.
struct Band {
  double y0_px = -1e30, y1_px = 1e30;  // rows drawn: y0 <= y < y1
  cairo_surface_t* mask = nullptr;     // A8, the band's size; nullptr: draw with groups
  bool misses(double min_y_px, double max_y_px, double margin_px) const {
    return max_y_px + margin_px < y0_px || min_y_px - margin_px > y1_px;
  }
};

void polygon_paths(cairo_t* cr, const PlotFrame& f, const ClipperLib::Paths& paths,
                   const Band& band) {
  for (const auto& p : paths) {
    if (p.empty()) continue;
    double lo = 1e30, hi = -1e30;
    for (const auto& q : p) {
      const double y = f.to_px(pcb::to_mm(q)).y();
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    if (band.misses(lo, hi, 2.0)) continue;  // adds no crossing to the band's rows
    for (size_t i = 0; i < p.size(); ++i) {
      const Point2 q = f.to_px(pcb::to_mm(p[i]));
      if (i == 0)
        cairo_move_to(cr, q.x(), q.y());
      else
        cairo_line_to(cr, q.x(), q.y());
    }
    cairo_close_path(cr);
  }
}

void polyline(cairo_t* cr, const PlotFrame& f, const std::vector<Point2>& pts) {
  for (size_t i = 0; i < pts.size(); ++i) {
    const Point2 q = f.to_px(pts[i]);
    if (i == 0)
      cairo_move_to(cr, q.x(), q.y());
    else
      cairo_line_to(cr, q.x(), q.y());
  }
  if (pts.size() == 1) cairo_rel_line_to(cr, 0.01, 0);
}

// Strokes the paths that reach the band.
void stroke_paths(cairo_t* cr, const PlotFrame& f, const std::vector<std::vector<Point2>>& paths,
                  double width_px, const Band& band) {
  cairo_set_line_width(cr, width_px);
  for (const auto& p : paths) {
    double lo = 1e30, hi = -1e30;
    for (const Point2& q : p) {
      const double y = f.to_px(q).y();
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    if (p.empty() || band.misses(lo, hi, width_px / 2 + 2.0)) continue;
    polyline(cr, f, p);
    cairo_stroke(cr);
  }
}

// A set of paths stroked in one go: where strokes of one colour overlap, the colour stays
// even (the group, or the band's mask, is painted once with its alpha).
void stroke_group(cairo_t* cr, const PlotFrame& f, const std::vector<std::vector<Point2>>& paths,
                  double width_px, const Rgba& c, const Band& band) {
  const double w = std::max(width_px, 0.5);
  if (!band.mask) {
    cairo_push_group(cr);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    stroke_paths(cr, f, paths, w, band);
    cairo_pop_group_to_source(cr);
    cairo_paint_with_alpha(cr, c.a);
    return;
  }
  if (paths.empty()) return;
  cairo_t* m = cairo_create(band.mask);
  cairo_set_operator(m, CAIRO_OPERATOR_CLEAR);
  cairo_paint(m);
  cairo_set_operator(m, CAIRO_OPERATOR_OVER);
  cairo_translate(m, 0, -band.y0_px);
  cairo_set_line_cap(m, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(m, CAIRO_LINE_JOIN_ROUND);
  cairo_set_source_rgb(m, 0, 0, 0);
  stroke_paths(m, f, paths, w, band);
  cairo_destroy(m);
  cairo_surface_mark_dirty(band.mask);
  set(cr, c);
  cairo_mask_surface(cr, band.mask, 0, band.y0_px);
}

void legend_box(cairo_t* cr, double x, double y, const Rgba& c, const std::string& label) {
  set(cr, c);
  cairo_rectangle(cr, x, y - 8, 24, 12);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_move_to(cr, x + 30, y + 3);
  cairo_show_text(cr, label.c_str());
}

// The holes as dots, the slots as strokes of their width.
void draw_holes(cairo_t* cr, const pcb::BoardJob& job, const PlotFrame& f) {
  const double s = f.scale_px_per_mm;
  set(cr, kHole);
  for (const pcb::Hole& h : job.holes_machine) {
    const Point2 c = f.to_px(pcb::to_mm(ClipperLib::IntPoint(h.at.x, h.at.y)));
    cairo_arc(cr, c.x(), c.y(), std::max(0.5, h.diameter_nm / 2e6 * s), 0, 2 * 3.14159265358979);
    cairo_fill(cr);
  }
  for (const pcb::Slot& sl : job.slots_machine) {
    cairo_set_line_width(cr, std::max(1.0, sl.diameter_nm / 1e6 * s));
    polyline(cr, f,
             {pcb::to_mm(ClipperLib::IntPoint(sl.from.x, sl.from.y)),
              pcb::to_mm(ClipperLib::IntPoint(sl.to.x, sl.to.y))});
    cairo_stroke(cr);
  }
}

// A ring around each narrow gap.
void draw_gaps(cairo_t* cr, const pcb::BoardJob& job, const PlotFrame& f) {
  const double s = f.scale_px_per_mm;
  set(cr, kGap);
  cairo_set_line_width(cr, 2.0);
  for (const pcb::NarrowGap& g : job.report.narrow_gaps) {
    const Point2 c =
        f.to_px(job.frame.to_machine(Point2(g.at.x / pcb::kNmPerMm, g.at.y / pcb::kNmPerMm)));
    cairo_new_sub_path(cr);
    cairo_arc(cr, c.x(), c.y(), std::max(8.0, 0.5 * s), 0, 2 * 3.14159265358979);
    cairo_stroke(cr);
  }
}

// Title, legend, scale bar.
void draw_labels(cairo_t* cr, const BoardPlotInput& in, const PlotFrame& f, int height_px) {
  const double s = f.scale_px_per_mm;
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, 16);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_move_to(cr, kSideMarginPx, kTitleBaselinePx);
  cairo_show_text(cr, in.title.c_str());
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12);
  const double y = height_px - kBottomBandPx / 2;
  LegendEntry shown[kLegendSize];
  const int n = legend_shown(!in.simulated.empty(), !in.job->cutout_paths_mm.empty(), shown);
  for (int i = 0; i < n; ++i)
    legend_box(cr, kSideMarginPx + shown[i].x_px, y, shown[i].colour, shown[i].label);
  draw_scale_bar(cr, nice_length(in.width_px / 6.0 / s), s, in.width_px - kSideMarginPx, y);
}

void render(cairo_t* cr, const BoardPlotInput& in, const PlotFrame& f, int height_px,
            const Band& band) {
  const pcb::BoardJob& job = *in.job;
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
  if (!job.board_machine_nm.empty()) {
    set(cr, kBoard);
    polygon_paths(cr, f, job.board_machine_nm, band);
    cairo_fill(cr);
  }
  set(cr, kCopper);
  polygon_paths(cr, f, pcb::copper_paths(job.copper_machine), band);
  cairo_fill(cr);
  const double s = f.scale_px_per_mm;
  stroke_group(cr, f, job.clearing_paths_mm, 2 * job.clearing_tool_radius_mm * s, kIsolation, band);
  stroke_group(cr, f, job.clearing_paths_mm, 0.6, kIsolationCentre, band);
  stroke_group(cr, f, job.isolation_paths_mm, 2 * job.tool_radius_mm * s, kIsolation, band);
  stroke_group(cr, f, job.isolation_paths_mm, 0.6, kIsolationCentre, band);
  stroke_group(cr, f, job.cutout_paths_mm, 2 * job.cutter_radius_mm * s, kCutout, band);
  stroke_group(cr, f, job.cutout_paths_mm, 0.6, kCutoutCentre, band);
  stroke_group(cr, f, job.tab_paths_mm, 2 * job.cutter_radius_mm * s, kTab, band);
  draw_holes(cr, job, f);
  if (!in.simulated.empty()) {
    const std::vector<std::vector<Point2>> down = pen_down_pieces(in.simulated);
    stroke_group(cr, f, down, 0.5, kSimulated, band);
  }
  draw_gaps(cr, job, f);
  draw_labels(cr, in, f, height_px);
}

}  // namespace

void write_board_plot(const BoardPlotInput& in, const std::string& svg_path,
                      const std::string& png_path) {
  if (!in.job) throw std::runtime_error("board plot: no job");
  if (in.width_px < 200 || in.width_px > 20000)
    throw std::runtime_error("plot width must be 200..20000 pixels");
  int height_px = 0;
  const PlotFrame f = board_plot_frame(*in.job, in.width_px, &height_px);
  if (height_px > 20000) throw std::runtime_error("the board plot would be over 20000 pixels high");
  if (!svg_path.empty()) {
    write_board_plot_svg(in, f, height_px, svg_path);
  }
  if (!png_path.empty()) {
    // Drawn band by band into one band-sized surface, each band handed to the PNG writer.
    const int band_rows = std::min(height_px, kBandRows);
    cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, in.width_px, band_rows);
    check_cairo_surface(s, png_path);
    Band band;
    band.mask = cairo_image_surface_create(CAIRO_FORMAT_A8, in.width_px, band_rows);
    check_cairo_surface(band.mask, png_path);
    try {
      PngRows png(png_path, in.width_px, height_px);
      for (int y0 = 0; y0 < height_px; y0 += band_rows) {
        band.y0_px = y0;
        band.y1_px = y0 + band_rows;
        cairo_t* cr = cairo_create(s);
        cairo_translate(cr, 0, -y0);
        render(cr, in, f, height_px, band);
        cairo_destroy(cr);
        cairo_surface_flush(s);
        png.add_rows(cairo_image_surface_get_data(s), cairo_image_surface_get_stride(s),
                     std::min(band_rows, height_px - y0));
      }
      png.finish();
    } catch (...) {
      cairo_surface_destroy(band.mask);
      cairo_surface_destroy(s);
      throw;
    }
    cairo_surface_destroy(band.mask);
    cairo_surface_destroy(s);
  }
}

}  // namespace host
