#include "host_tests/host/pcb/raster_compare.h"

#include <cairo.h>
#include <unistd.h>  // getpid

#include <algorithm>  // std::sort, std::min, std::max
#include <cmath>      // std::ceil, std::floor
#include <cstdio>     // std::remove, std::snprintf
#include <cstdlib>    // std::system
#include <fstream>    // std::ofstream
#include <stdexcept>  // std::runtime_error

#include "host/lib/pcb/gerber_shapes.h"

namespace host::pcb::test {

size_t Raster::count() const {
  size_t n = 0;
  for (unsigned char d : dark) n += d;
  return n;
}

Window window_around(const PcbLayer& layer, double margin_mm, double dpi) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  auto add = [&](double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  };
  for (const auto& p : layer.polygons_nm) {
    for (const auto& q : p) add(q.X * 1e-6, q.Y * 1e-6);
  }
  for (const auto& h : layer.holes) {
    const double r = h.diameter_nm * 0.5e-6;
    add(h.at.x * 1e-6 - r, h.at.y * 1e-6 - r);
    add(h.at.x * 1e-6 + r, h.at.y * 1e-6 + r);
  }
  for (const auto& s : layer.slots) {
    const double r = s.diameter_nm * 0.5e-6;
    add(std::min(s.from.x, s.to.x) * 1e-6 - r, std::min(s.from.y, s.to.y) * 1e-6 - r);
    add(std::max(s.from.x, s.to.x) * 1e-6 + r, std::max(s.from.y, s.to.y) * 1e-6 + r);
  }
  Window w;
  w.pixel_mm = 25.4 / dpi;
  // Start on a whole pixel so that the window's corner is exact in inches too.
  w.x0_mm = std::floor((x0 - margin_mm) / w.pixel_mm) * w.pixel_mm;
  w.y0_mm = std::floor((y0 - margin_mm) / w.pixel_mm) * w.pixel_mm;
  w.w = static_cast<int>(std::ceil((x1 + margin_mm - w.x0_mm) / w.pixel_mm));
  w.h = static_cast<int>(std::ceil((y1 + margin_mm - w.y0_mm) / w.pixel_mm));
  return w;
}

Raster rasterise(const ClipperLib::Paths& paths, const Window& win) {
  struct Edge {
    double y_lo, y_hi, x_at_lo, slope;  // pixel units, y up
    int dir;
  };
  std::vector<Edge> edges;
  const double inv = 1.0 / (win.pixel_mm * 1e6);
  for (const auto& p : paths) {
    for (size_t k = 0; k < p.size(); ++k) {
      const auto& a = p[k];
      const auto& b = p[(k + 1) % p.size()];
      const double ax = (a.X * 1e-6 - win.x0_mm) * 1e6 * inv,
                   ay = (a.Y * 1e-6 - win.y0_mm) * 1e6 * inv;
      const double bx = (b.X * 1e-6 - win.x0_mm) * 1e6 * inv,
                   by = (b.Y * 1e-6 - win.y0_mm) * 1e6 * inv;
      if (ay == by) continue;
      Edge e;
      e.dir = by > ay ? 1 : -1;
      e.y_lo = std::min(ay, by);
      e.y_hi = std::max(ay, by);
      e.x_at_lo = ay < by ? ax : bx;
      e.slope = (bx - ax) / (by - ay);
      edges.push_back(e);
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const Edge& l, const Edge& r) { return l.y_lo < r.y_lo; });
  Raster r;
  r.w = win.w;
  r.h = win.h;
  r.dark.assign(static_cast<size_t>(win.w) * win.h, 0);
  std::vector<const Edge*> active;
  std::vector<std::pair<double, int>> xs;
  size_t next = 0;
  for (int row_from_bottom = 0; row_from_bottom < win.h; ++row_from_bottom) {
    const double y = row_from_bottom + 0.5;
    while (next < edges.size() && edges[next].y_lo <= y) active.push_back(&edges[next++]);
    xs.clear();
    size_t keep = 0;
    for (const Edge* e : active) {
      if (e->y_hi <= y) continue;  // finished
      active[keep++] = e;
      if (e->y_lo <= y) xs.push_back({e->x_at_lo + (y - e->y_lo) * e->slope, e->dir});
    }
    active.resize(keep);
    std::sort(xs.begin(), xs.end());
    int winding = 0;
    unsigned char* row = &r.dark[static_cast<size_t>(win.h - 1 - row_from_bottom) * win.w];
    for (size_t k = 0; k + 1 < xs.size(); ++k) {
      winding += xs[k].second;
      if (winding == 0) continue;
      // Pixels whose centre c + 0.5 lies in [xs[k], xs[k+1]).
      const int c0 = std::max(0, static_cast<int>(std::ceil(xs[k].first - 0.5)));
      const int c1 = std::min(win.w, static_cast<int>(std::ceil(xs[k + 1].first - 0.5)));
      for (int c = c0; c < c1; ++c) row[c] = 1;
    }
  }
  return r;
}

ClipperLib::Paths drill_shapes(const PcbLayer& layer) {
  ClipperLib::Paths out;
  for (const Hole& h : layer.holes) {
    out.push_back(circle_path({static_cast<double>(h.at.x), static_cast<double>(h.at.y)},
                              static_cast<double>(h.diameter_nm), 100));
  }
  for (const Slot& s : layer.slots) {
    out.push_back(capsule_path({static_cast<double>(s.from.x), static_cast<double>(s.from.y)},
                               {static_cast<double>(s.to.x), static_cast<double>(s.to.y)},
                               static_cast<double>(s.diameter_nm), 100));
  }
  return out;
}

ClipperLib::Paths hairlines(const PcbLayer& strokes, double pixel_mm) {
  const double pixel_nm = pixel_mm * 1e6;
  ClipperLib::ClipperOffset off;
  for (size_t k = 0; k < strokes.polygons_nm.size(); ++k)
    if (k < strokes.outline_widths_nm.size() && strokes.outline_widths_nm[k] < pixel_nm)
      off.AddPath(strokes.polygons_nm[k], ClipperLib::jtRound, ClipperLib::etOpenRound);
  ClipperLib::Paths out;
  off.Execute(out, pixel_nm / 2);
  return out;
}

bool gerbv_available() {
  return std::system("gerbv --version > /dev/null 2>&1") == 0;
}

Raster gerbv_render(const std::string& file, const Window& win) {
  static int serial = 0;
  const std::string png = "/tmp/engraver_pcb_gerbv_" + std::to_string(getpid()) + "_" +
                          std::to_string(serial++) + ".png";
  char geometry[256];
  // gerbv multiplies the window in inches by the dpi in float and truncates: a quarter pixel
  // more keeps 4.042 in at 500 dpi 2021 px (it was 2020.9999, 2020 px).
  std::snprintf(geometry, sizeof geometry,
                "--border=0 --dpi=%.3f '--origin=%.6f;%.6f' --window_inch=%.6fx%.6f", win.dpi(),
                win.x0_mm / 25.4, win.y0_mm / 25.4, (win.w + 0.25) * win.pixel_mm / 25.4,
                (win.h + 0.25) * win.pixel_mm / 25.4);
  const std::string cmd = "gerbv -x png -o '" + png + "' " + geometry +
                          " --foreground=#000000ff --background=#ffffff '" + file +
                          "' > /dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("gerbv failed: " + cmd);
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.c_str());
  std::remove(png.c_str());
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(s);
    throw std::runtime_error("gerbv wrote no readable PNG: " + cmd);
  }
  Raster r;
  r.w = cairo_image_surface_get_width(s);
  r.h = cairo_image_surface_get_height(s);
  if (r.w != win.w || r.h != win.h) {
    cairo_surface_destroy(s);
    throw std::runtime_error("gerbv image is " + std::to_string(r.w) + " x " + std::to_string(r.h) +
                             ", expected " + std::to_string(win.w) + " x " + std::to_string(win.h) +
                             ": " + cmd);
  }
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  r.dark.resize(static_cast<size_t>(r.w) * r.h);
  for (int y = 0; y < r.h; ++y) {
    for (int x = 0; x < r.w; ++x) {
      const unsigned char* px = data + static_cast<size_t>(y) * stride + 4 * x;
      r.dark[static_cast<size_t>(y) * r.w + x] = px[1] < 128;  // green byte (ARGB32)
    }
  }
  cairo_surface_destroy(s);
  return r;
}

std::string gerbv_drill_export(const std::string& file) {
  static int serial = 0;
  const std::string out = "/tmp/engraver_pcb_gerbv_" + std::to_string(getpid()) + "_" +
                          std::to_string(serial++) + ".drl";
  const std::string cmd = "gerbv -x drill -o '" + out + "' '" + file + "' > /dev/null 2>&1";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("gerbv failed: " + cmd);
  return out;
}

Agreement compare(const Raster& a, const Raster& b) {
  Agreement g;
  g.pixels = a.dark.size();
  if (a.w != b.w || a.h != b.h) throw std::runtime_error("rasters of different sizes");
  for (int y = 0; y < a.h; ++y) {
    for (int x = 0; x < a.w; ++x) {
      const size_t k = static_cast<size_t>(y) * a.w + x;
      g.dark_either += a.dark[k] | b.dark[k];
      if (a.dark[k] == b.dark[k]) continue;
      ++g.mismatched;
      // Does each image have the other's value next to this pixel?
      bool a_near = false, b_near = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= a.w || yy >= a.h) continue;
          const size_t n = static_cast<size_t>(yy) * a.w + xx;
          b_near |= b.dark[n] == a.dark[k];
          a_near |= a.dark[n] == b.dark[k];
        }
      }
      g.beyond_edge += !(a_near && b_near);
    }
  }
  return g;
}

void write_difference(const Raster& ours, const Raster& gerbv, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << ours.w << " " << ours.h << "\n255\n";
  for (size_t k = 0; k < ours.dark.size(); ++k) {
    const bool o = ours.dark[k], g = gerbv.dark[k];
    const unsigned char rgb[3] = {static_cast<unsigned char>(o && g ? 0
                                                             : o    ? 255
                                                             : g    ? 0
                                                                    : 255),
                                  static_cast<unsigned char>(o || g ? 0 : 255),
                                  static_cast<unsigned char>(o && g ? 0
                                                             : g    ? 255
                                                             : o    ? 0
                                                                    : 255)};
    out.write(reinterpret_cast<const char*>(rgb), 3);
  }
}

}  // namespace host::pcb::test
