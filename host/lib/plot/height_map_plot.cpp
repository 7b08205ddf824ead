// Height map and depth error pictures (height_map_plot.h).
#include "host/lib/plot/height_map_plot.h"

#include <cairo-svg.h>   // cairo_svg_surface_create
#include <cairo.h>       // cairo_*
#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::min
#include <cmath>      // std::abs
#include <cstdint>    // uint32_t
#include <stdexcept>  // std::runtime_error

namespace host {

namespace {

constexpr double kWidthPt = 800, kHeightPt = 640;
constexpr double kTitlePt = 36, kLegendPt = 60, kSidePt = 20;

struct Rgb {
  double r, g, b;
};

// -1 .. 1 -> blue .. green .. red (t = 0 green): a reader tells the sign at a glance.
Rgb diverging(double t) {
  t = std::clamp(t, -1.0, 1.0);
  if (t < 0) return {0.1 * (1 + t), 0.65 * (1 + t), 0.15 + 0.8 * -t};
  return {0.1 + 0.85 * t, 0.65 * (1 - t), 0.15 * (1 - t)};
}

// 0 .. 1 -> dark blue .. yellow (heights).
Rgb sequential(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return {0.15 + 0.8 * t, 0.2 + 0.7 * t, 0.55 - 0.4 * t};
}

// mm -> points on the page, the area fitted with its aspect kept, y up.
struct Frame {
  double scale = 1, x0_pt = 0, y0_pt = 0, x0_mm = 0, y0_mm = 0;
  double x(double mm) const { return x0_pt + (mm - x0_mm) * scale; }
  double y(double mm) const { return y0_pt - (mm - y0_mm) * scale; }
};

Frame fit(double x0, double y0, double x1, double y1) {
  const double w = std::max(x1 - x0, 1e-6), h = std::max(y1 - y0, 1e-6);
  Frame f;
  f.scale = std::min((kWidthPt - 2 * kSidePt) / w, (kHeightPt - kTitlePt - kLegendPt) / h);
  f.x0_mm = x0;
  f.y0_mm = y0;
  f.x0_pt = (kWidthPt - w * f.scale) / 2;
  f.y0_pt = kTitlePt + h * f.scale + ((kHeightPt - kTitlePt - kLegendPt) - h * f.scale) / 2;
  return f;
}

void text(cairo_t* cr, double x, double y, double size, const std::string& s) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

// A colour bar along the bottom from `lo` to `hi` with its end labels in um.
template <typename Colour>
void colour_bar(cairo_t* cr, Colour colour, double lo, double hi, const std::string& label) {
  const double x0 = kSidePt + 60, w = kWidthPt - 2 * (kSidePt + 60), y = kHeightPt - 40;
  for (int i = 0; i < 100; ++i) {
    const Rgb c = colour(i / 99.0);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    cairo_rectangle(cr, x0 + w * i / 100.0, y, w / 100.0 + 0.5, 12);
    cairo_fill(cr);
  }
  text(cr, x0 - 55, y + 10, 11, fmt::format("{:.0f} um", lo));
  text(cr, x0 + w + 5, y + 10, 11, fmt::format("{:.0f} um", hi));
  text(cr, x0, y + 28, 11, label);
}

// Runs `draw` on an SVG surface at `path`; throws naming the file on failure.
template <typename Draw>
void svg(const std::string& path, Draw draw) {
  cairo_surface_t* s = cairo_svg_surface_create(path.c_str(), kWidthPt, kHeightPt);
  cairo_t* cr = cairo_create(s);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  draw(cr);
  cairo_destroy(cr);
  cairo_surface_finish(s);
  const cairo_status_t status = cairo_surface_status(s);
  cairo_surface_destroy(s);
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(
        fmt::format("{}: cannot write the plot ({})", path, cairo_status_to_string(status)));
}

}  // namespace

void write_height_map_svg(const heightmap::HeightMap& map, const std::string& title,
                          const std::string& svg_path) {
  const Frame f = fit(map.origin_x_mm, map.origin_y_mm, map.max_x_mm(), map.max_y_mm());
  const double lo = map.min_um(), hi = map.max_um(), span = std::max(hi - lo, 1e-6);
  svg(svg_path, [&](cairo_t* cr) {
    // The surface as the controller interpolates it: an image of one pixel per 2 pt,
    // embedded once (small whatever the map), scaled onto the grid's rectangle.
    const double w_pt = (map.max_x_mm() - map.origin_x_mm) * f.scale;
    const double h_pt = (map.max_y_mm() - map.origin_y_mm) * f.scale;
    const int nx = std::max(2, static_cast<int>(w_pt / 2)),
              ny = std::max(2, static_cast<int>(h_pt / 2));
    cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, nx, ny);
    const int stride = cairo_image_surface_get_stride(img);
    unsigned char* px = cairo_image_surface_get_data(img);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double x = map.origin_x_mm + (i + 0.5) / nx * (map.max_x_mm() - map.origin_x_mm);
        const double y = map.max_y_mm() - (j + 0.5) / ny * (map.max_y_mm() - map.origin_y_mm);
        const Rgb c = sequential((map.interpolate_um(x, y) - lo) / span);
        uint32_t* p = reinterpret_cast<uint32_t*>(px + j * stride) + i;
        *p = (static_cast<uint32_t>(c.r * 255) << 16) | (static_cast<uint32_t>(c.g * 255) << 8) |
             static_cast<uint32_t>(c.b * 255);
      }
    cairo_surface_mark_dirty(img);
    cairo_save(cr);
    cairo_translate(cr, f.x(map.origin_x_mm), f.y(map.max_y_mm()));
    cairo_scale(cr, w_pt / nx, h_pt / ny);
    cairo_set_source_surface(cr, img, 0, 0);
    cairo_paint(cr);
    cairo_restore(cr);
    cairo_surface_destroy(img);
    // The probe points, each with its height.
    for (int r = 0; r < map.rows; ++r)
      for (int c = 0; c < map.cols; ++c) {
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_arc(cr, f.x(map.x_mm(c)), f.y(map.y_mm(r)), 2.5, 0, 2 * 3.14159265);
        cairo_fill(cr);
        if (map.rows * map.cols <= 100)
          text(cr, f.x(map.x_mm(c)) + 3, f.y(map.y_mm(r)) - 3, 8,
               fmt::format("{:.0f}", map.height_um(r, c)));
      }
    text(cr, kSidePt, 24, 15,
         fmt::format("{}: height map, {} x {} points, {:.1f} x {:.1f} mm pitch, range {:.0f} um",
                     title, map.rows, map.cols, map.pitch_x_mm, map.pitch_y_mm, hi - lo));
    colour_bar(cr, sequential, lo, hi, "copper height above Z 0 (dots: probe points, um)");
  });
}

void write_depth_error_svg(const std::vector<heightmap::DepthSample>& samples, double range_um,
                           const std::string& title, const std::string& svg_path) {
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1, worst = 0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const heightmap::DepthSample& s = samples[i];
    if (i == 0) x0 = x1 = s.x_mm, y0 = y1 = s.y_mm;
    x0 = std::min(x0, s.x_mm), x1 = std::max(x1, s.x_mm);
    y0 = std::min(y0, s.y_mm), y1 = std::max(y1, s.y_mm);
    if (std::abs(s.error_um) > std::abs(worst)) worst = s.error_um;
  }
  const Frame f = fit(x0, y0, x1, y1);
  svg(svg_path, [&](cairo_t* cr) {
    cairo_set_line_width(cr, 1.6);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    // Runs of one colour step (a twentieth of the scale) as one polyline, thinned to half a
    // point: the file stays small whatever the path's length.
    auto step_of = [range_um](double e) {
      return static_cast<int>(std::lround(std::clamp(e / range_um, -1.0, 1.0) * 10));
    };
    int run_step = 0;
    bool open = false;
    double last_x = 0, last_y = 0;
    auto finish = [&] {
      if (!open) return;
      const Rgb c = diverging(run_step / 10.0);
      cairo_set_source_rgb(cr, c.r, c.g, c.b);
      cairo_stroke(cr);
      open = false;
    };
    for (size_t i = 0; i < samples.size(); ++i) {
      const heightmap::DepthSample& s = samples[i];
      const double x = f.x(s.x_mm), y = f.y(s.y_mm);
      const int step = step_of(s.error_um);
      if (s.starts_path || i == 0) {
        finish();
      } else if (step != run_step) {
        cairo_line_to(cr, x, y);
        finish();
        cairo_move_to(cr, x, y);  // the next run starts where this one ended
        open = true;
      } else if (std::abs(x - last_x) < 0.5 && std::abs(y - last_y) < 0.5) {
        continue;
      }
      if (!open) {
        cairo_move_to(cr, x, y);
        open = true;
      }
      cairo_line_to(cr, x, y);
      run_step = step;
      last_x = x;
      last_y = y;
    }
    finish();
    text(cr, kSidePt, 24, 15,
         fmt::format("{}: depth error along the isolation paths, worst {:+.1f} um", title, worst));
    colour_bar(
        cr, [](double t) { return diverging(2 * t - 1); }, -range_um, range_um,
        "depth of cut minus planned depth (blue: too shallow, red: too deep)");
  });
}

}  // namespace host
