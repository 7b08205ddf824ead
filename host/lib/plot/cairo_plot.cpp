// What the cairo plots share (see cairo_plot.h).
#include "host/lib/plot/cairo_plot.h"

#include <cmath>      // std::pow, std::floor, std::log10
#include <stdexcept>  // std::runtime_error

namespace host {

double nice_length(double target) {
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  if (target >= 5 * p) return 5 * p;
  if (target >= 2 * p) return 2 * p;
  return p;
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
