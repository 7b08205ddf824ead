// What the cairo plots (the drawing's, the board's) share: the scale bar's length and the
// check that a surface was written.
#ifndef HOST_LIB_PLOT_CAIRO_PLOT_H
#define HOST_LIB_PLOT_CAIRO_PLOT_H

#include <cairo.h>  // cairo_surface_t

#include <string>  // std::string

namespace host {

// 1, 2 or 5 times a power of ten, the largest not above target.
double nice_length(double target);

// Throws std::runtime_error naming path (and destroys s) when cairo failed writing s.
void check_cairo_surface(cairo_surface_t* s, const std::string& path);

}  // namespace host

#endif  // HOST_LIB_PLOT_CAIRO_PLOT_H
