// What the cairo plots share (see cairo_plot.h).
#include "host/lib/plot/cairo_plot.h"

#include <cmath>      // std::pow, std::floor, std::log10
#include <sstream>    // std::ostringstream
#include <stdexcept>  // std::runtime_error

namespace host {

double nice_length(double target) {
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  if (target >= 5 * p) return 5 * p;
  if (target >= 2 * p) return 2 * p;
  return p;
}

void draw_scale_bar(cairo_t* cr, double bar_mm, double px_per_mm, double x1_px, double y_px) {
  const double x0 = x1_px - bar_mm * px_per_mm;
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 2.0);
  cairo_move_to(cr, x0, y_px - 5);
  cairo_line_to(cr, x0, y_px);
  cairo_line_to(cr, x1_px, y_px);
  cairo_line_to(cr, x1_px, y_px - 5);
  cairo_stroke(cr);
  std::ostringstream label;
  label << bar_mm << " mm";
  cairo_move_to(cr, x0, y_px + 16);
  cairo_show_text(cr, label.str().c_str());
}

void check_cairo_surface(cairo_surface_t* s, const std::string& path) {
  const cairo_status_t st = cairo_surface_status(s);
  if (st != CAIRO_STATUS_SUCCESS) {
    const std::string msg = cairo_status_to_string(st);
    cairo_surface_destroy(s);
    throw std::runtime_error(path + ": cannot write the plot: " + msg);
  }
}

}  // namespace host
