// Test support: the reader's copper rasterised at pixel centres, gerbv's PNG of the same
// file (the independent reference), and how well they agree.
#ifndef HOST_TESTS_HOST_PCB_RASTER_COMPARE_H
#define HOST_TESTS_HOST_PCB_RASTER_COMPARE_H

#include <clipper.hpp>  // ClipperLib::Paths

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/pcb/pcb_layer.h"

namespace host::pcb::test {

// A window on the board: lower-left corner in mm, pixels of `pixel_mm`, w x h pixels. Row 0
// is the top (as in a PNG).
struct Window {
  double x0_mm = 0, y0_mm = 0, pixel_mm = 0.0254;
  int w = 0, h = 0;
  double dpi() const { return 25.4 / pixel_mm; }
};

struct Raster {
  int w = 0, h = 0;
  std::vector<unsigned char> dark;  // row-major, 1 = copper
  size_t count() const;
};

// A window around the layer's copper and holes with `margin_mm` on every side, pixel size
// from dpi (use one that divides a power of ten, so the corner prints exactly in inches),
// whole pixels.
Window window_around(const PcbLayer& layer, double margin_mm, double dpi);

// Non-zero fill of the polygons, sampled at pixel centres.
Raster rasterise(const ClipperLib::Paths& paths, const Window& win);

// The layer's holes and slots as filled discs and stadiums.
ClipperLib::Paths drill_shapes(const PcbLayer& layer);

// The strokes of `strokes` (a Gerber read as an outline: centre lines and their widths)
// narrower than a pixel, as gerbv draws them in a picture: one pixel wide, round ends. A
// zero-width line is no copper, but gerbv shows it (its limitLineWidth).
ClipperLib::Paths hairlines(const PcbLayer& strokes, double pixel_mm);

// True if `gerbv --version` runs.
bool gerbv_available();

// gerbv -x png of `file` over the window (no antialiasing, black on white); throws
// std::runtime_error if gerbv fails or the image size differs from the window.
Raster gerbv_render(const std::string& file, const Window& win);

// gerbv -x drill of `file` (gerbv's reading written back as INCH,TZ with 4 decimals) to a
// temporary file, whose path is returned; throws std::runtime_error if gerbv fails.
std::string gerbv_drill_export(const std::string& file);

struct Agreement {
  size_t pixels = 0;       // all pixels in the window
  size_t dark_either = 0;  // copper in either image
  size_t mismatched = 0;   // copper in one image only
  // Mismatches with no pixel of the same value within one pixel in the other image: real
  // differences, not gerbv snapping its strokes to the pixel grid.
  size_t beyond_edge = 0;
  double of_all() const { return 1.0 - static_cast<double>(mismatched) / pixels; }
  double of_copper() const {
    return dark_either ? 1.0 - static_cast<double>(mismatched) / dark_either : 1.0;
  }
};

// `a` is ours, `b` gerbv's (same size).
Agreement compare(const Raster& a, const Raster& b);

// Writes a PPM showing both (for looking at a failure): black both, red ours only, blue
// gerbv only.
void write_difference(const Raster& ours, const Raster& gerbv, const std::string& path);

}  // namespace host::pcb::test

#endif  // HOST_TESTS_HOST_PCB_RASTER_COMPARE_H
