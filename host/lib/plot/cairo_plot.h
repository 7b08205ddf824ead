// What the cairo plots (the drawing's, the board's) share: the scale bar and the check that
// a surface was written.
#ifndef HOST_LIB_PLOT_CAIRO_PLOT_H
#define HOST_LIB_PLOT_CAIRO_PLOT_H

#include <cairo.h>  // cairo_surface_t, cairo_t

#include <string>  // std::string

namespace host {

// 1, 2 or 5 times a power of ten, the largest not above target.
double nice_length(double target);

// A black scale bar of bar_mm ending at x1_px on the line y_px, its length written below.
void draw_scale_bar(cairo_t* cr, double bar_mm, double px_per_mm, double x1_px, double y_px);

// Throws std::runtime_error naming path (and destroys s) when cairo failed writing s.
void check_cairo_surface(cairo_surface_t* s, const std::string& path);

}  // namespace host

#endif  // HOST_LIB_PLOT_CAIRO_PLOT_H
