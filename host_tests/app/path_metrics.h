// Test-side geometry: reference polylines (circle, square, star, sine...) in micrometres and
// the distance of a recorded tool path from a polyline (the contour error).
#ifndef HOST_TESTS_APP_PATH_METRICS_H
#define HOST_TESTS_APP_PATH_METRICS_H

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace fake_app {

struct P3 {
  double x, y, z;
};

// Distance from p to the segment a-b.
inline double segment_distance(const P3& p, const P3& a, const P3& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
  const double l2 = dx * dx + dy * dy + dz * dz;
  double t = 0;
  if (l2 > 0) t = ((p.x - a.x) * dx + (p.y - a.y) * dy + (p.z - a.z) * dz) / l2;
  t = std::clamp(t, 0.0, 1.0);
  const double ex = a.x + t * dx - p.x, ey = a.y + t * dy - p.y, ez = a.z + t * dz - p.z;
  return std::sqrt(ex * ex + ey * ey + ez * ez);
}

// Largest distance of any path sample from the polyline (brute force with a moving window:
// the tool goes along the polyline in order).
inline double max_contour_error(const std::vector<P3>& path, const std::vector<P3>& line) {
  double worst = 0;
  size_t seg = 0;
  for (const P3& p : path) {
    double best = 1e300;
    size_t best_seg = seg;
    const size_t lo = seg > 4 ? seg - 4 : 0;
    const size_t hi = std::min(line.size() - 1, seg + 40);
    for (size_t s = lo; s < hi; ++s) {
      const double d = segment_distance(p, line[s], line[s + 1]);
      if (d < best) {
        best = d;
        best_seg = s;
      }
    }
    if (line.size() == 1) best = std::hypot(p.x - line[0].x, p.y - line[0].y);
    seg = best_seg;
    worst = std::max(worst, best);
  }
  return worst;
}

inline double polyline_length(const std::vector<P3>& line) {
  double len = 0;
  for (size_t i = 1; i < line.size(); ++i) {
    len +=
        std::sqrt(std::pow(line[i].x - line[i - 1].x, 2) + std::pow(line[i].y - line[i - 1].y, 2) +
                  std::pow(line[i].z - line[i - 1].z, 2));
  }
  return len;
}

// Circle of radius r about c as chords whose sagitta is chord_um (like the adaptive walker).
inline std::vector<P3> circle(double cx, double cy, double r, double chord_um) {
  const double step = 2 * std::acos(1 - chord_um / r);
  const int n = int(std::ceil(2 * M_PI / step));
  std::vector<P3> out;
  for (int i = 0; i <= n; ++i) {
    const double a = 2 * M_PI * i / n;
    out.push_back({std::round(cx + r * std::cos(a)), std::round(cy + r * std::sin(a)), 0});
  }
  return out;
}

// Closed regular star polygon with k points, outer radius r (sharp turns of 144 deg for 5).
inline std::vector<P3> star(double cx, double cy, double r, int k) {
  std::vector<P3> out;
  for (int i = 0; i <= k; ++i) {
    const double a = M_PI / 2 + 2 * M_PI * (2 * i % k) / k;
    out.push_back({std::round(cx + r * std::cos(a)), std::round(cy + r * std::sin(a)), 0});
  }
  return out;
}

inline std::vector<P3> square(double x0, double y0, double side) {
  return {
      {x0, y0, 0}, {x0 + side, y0, 0}, {x0 + side, y0 + side, 0}, {x0, y0 + side, 0}, {x0, y0, 0}};
}

// Sine wave y = amp sin(2 pi x / period) over length, sampled every step_um.
inline std::vector<P3> sine(double x0, double y0, double amp, double period, double length,
                            double step_um) {
  std::vector<P3> out;
  for (double x = 0; x <= length + 1e-9; x += step_um) {
    out.push_back({std::round(x0 + x), std::round(y0 + amp * std::sin(2 * M_PI * x / period)), 0});
  }
  return out;
}

// Zigzag with the given turn angle (degrees) between legs of length leg_um.
inline std::vector<P3> zigzag(double x0, double y0, double leg_um, double turn_deg, int legs) {
  std::vector<P3> out{{x0, y0, 0}};
  const double half = turn_deg / 2 * M_PI / 180;  // leg angle to the x axis
  double x = x0, y = y0;
  for (int i = 0; i < legs; ++i) {
    x += leg_um * std::cos(half);
    y += (i % 2 ? -1 : 1) * leg_um * std::sin(half);
    out.push_back({std::round(x), std::round(y), 0});
  }
  return out;
}

}  // namespace fake_app

#endif  // HOST_TESTS_APP_PATH_METRICS_H
