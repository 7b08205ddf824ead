// Probe grid planning, order and outliers (probe_grid.h).
#include "host/lib/heightmap/probe_grid.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::sort
#include <cmath>      // std::ceil

namespace host::heightmap {

namespace {

// Points along one side so that the pitch is at most `spacing` (at least 2).
int points_for(double length_mm, double spacing_mm) {
  const double gaps = std::ceil(length_mm / spacing_mm - 1e-9);
  return std::max(2, static_cast<int>(gaps) + 1);
}

// The serpentine that runs along rows (X) when `along_x`, else along columns (Y).
std::vector<GridPoint> serpentine(const ProbeGrid& g, bool along_x) {
  std::vector<GridPoint> order;
  const int lines = along_x ? g.rows : g.cols, per = along_x ? g.cols : g.rows;
  for (int line = 0; line < lines; ++line)
    for (int k = 0; k < per; ++k) {
      const int i = line % 2 == 0 ? k : per - 1 - k;
      order.push_back(along_x ? GridPoint{line, i} : GridPoint{i, line});
    }
  return order;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

ProbeGrid plan_probe_grid(const AreaMm& job, const GridOptions& o) {
  if (!(o.margin_mm >= 0)) throw GridError("the probe margin must be 0 mm or above");
  // The margin stops at the zero corner (X 0, Y 0: where the blank begins, perhaps at the
  // travel's end) unless the job itself goes beyond it.
  auto low = [&](double v) { return v < 0 ? v - o.margin_mm : std::max(0.0, v - o.margin_mm); };
  const double x0 = low(job.x0), y0 = low(job.y0);
  const double w = job.x1 + o.margin_mm - x0, h = job.y1 + o.margin_mm - y0;
  if (!(w > 0) || !(h > 0))
    throw GridError("the job has no extent to probe (no cutting moves, and no margin)");
  ProbeGrid g;
  if (!(o.spacing_mm <= kMaxPitchMm) && o.rows == 0 && o.cols == 0)
    throw GridError(
        fmt::format("a probe spacing of {:g} mm is more than the controller's largest "
                    "pitch, {:g} mm",
                    o.spacing_mm, kMaxPitchMm));
  if (o.rows > 0 || o.cols > 0) {
    if (o.rows < 2 || o.cols < 2 || o.rows > kMaxGridSide || o.cols > kMaxGridSide)
      throw GridError(fmt::format("a probe grid of {} x {}: rows and cols must each be 2 to {}",
                                  o.rows, o.cols, kMaxGridSide));
    g.rows = o.rows;
    g.cols = o.cols;
  } else {
    if (!(o.spacing_mm > 0)) throw GridError("the probe spacing must be above 0 mm");
    g.cols = points_for(w, o.spacing_mm);
    g.rows = points_for(h, o.spacing_mm);
    if (g.rows > kMaxGridSide || g.cols > kMaxGridSide)
      throw GridError(fmt::format(
          "probing {:.1f} x {:.1f} mm every {:g} mm takes {} x {} points; the controller keeps "
          "at most {} a side: use a spacing of {:.1f} mm or more",
          w, h, o.spacing_mm, g.cols, g.rows, kMaxGridSide, std::max(w, h) / (kMaxGridSide - 1)));
  }
  g.origin_x_mm = x0;
  g.origin_y_mm = y0;
  g.pitch_x_mm = w / (g.cols - 1);
  g.pitch_y_mm = h / (g.rows - 1);
  if (std::max(g.pitch_x_mm, g.pitch_y_mm) > kMaxPitchMm ||
      std::min(g.pitch_x_mm, g.pitch_y_mm) < kMinPitchMm)
    throw GridError(fmt::format(
        "a probe grid of {} x {} over {:.1f} x {:.1f} mm has a pitch of ({:.3f}, {:.3f}) mm; the "
        "controller takes {:g} to {:g} mm",
        g.rows, g.cols, w, h, g.pitch_x_mm, g.pitch_y_mm, kMinPitchMm, kMaxPitchMm));
  return g;
}

double travel_mm(const ProbeGrid& g, const std::vector<GridPoint>& order) {
  double sum = 0;
  for (size_t i = 1; i < order.size(); ++i)
    sum += std::hypot(g.x_mm(order[i].col) - g.x_mm(order[i - 1].col),
                      g.y_mm(order[i].row) - g.y_mm(order[i - 1].row));
  return sum;
}

std::vector<GridPoint> probe_order(const ProbeGrid& g) {
  std::vector<GridPoint> by_rows = serpentine(g, true), by_cols = serpentine(g, false);
  return travel_mm(g, by_cols) < travel_mm(g, by_rows) ? by_cols : by_rows;
}

std::vector<Outlier> find_outliers(const ProbeGrid& g, const std::vector<double>& h,
                                   double limit_um) {
  const size_t n = static_cast<size_t>(g.rows) * g.cols;
  std::vector<bool> out(n, false);
  auto index = [&](int r, int c) { return static_cast<size_t>(r) * g.cols + c; };
  auto usable = [&](int r, int c) {
    return r >= 0 && r < g.rows && c >= 0 && c < g.cols && !out[index(r, c)];
  };
  const int dirs[4][2] = {{0, 1}, {1, 0}, {0, -1}, {-1, 0}};
  // What the points not yet found predict for (r, c), along each axis: quadratics through
  // three or four of them where there are (exact for a tilt and a bow, however strong),
  // else straight lines.
  auto predictions = [&](int r, int c) {
    std::vector<double> p;
    for (int d = 0; d < 2; ++d) {
      const int dr = dirs[d][0], dc = dirs[d][1];
      auto ok = [&](int k) { return usable(r + k * dr, c + k * dc); };
      auto h_at = [&](int k) { return h[index(r + k * dr, c + k * dc)]; };
      const size_t before = p.size();
      if (ok(-2) && ok(-1) && ok(1) && ok(2))
        p.push_back((-h_at(-2) + 4 * h_at(-1) + 4 * h_at(1) - h_at(2)) / 6);
      for (int s = -1; s <= 1; s += 2) {
        if (ok(-s) && ok(s) && ok(2 * s)) p.push_back(h_at(-s) / 3 + h_at(s) - h_at(2 * s) / 3);
        if (ok(s) && ok(2 * s) && ok(3 * s))
          p.push_back(3 * h_at(s) - 3 * h_at(2 * s) + h_at(3 * s));
      }
      if (p.size() > before) continue;
      if (ok(-1) && ok(1)) p.push_back(0.5 * (h_at(-1) + h_at(1)));
      for (int s = -1; s <= 1; s += 2)
        if (ok(s) && ok(2 * s)) p.push_back(2 * h_at(s) - h_at(2 * s));
    }
    return p;
  };
  // The most condemned point first: a bad point disagrees with every prediction of it, its
  // neighbours only with those it takes part in. Then again without it, so its predictions
  // of its neighbours are not believed.
  std::vector<Outlier> found;
  for (;;) {
    std::optional<Outlier> worst;
    double worst_share = 0;
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.cols; ++c) {
        if (out[index(r, c)]) continue;
        const std::vector<double> p = predictions(r, c);
        if (p.empty()) continue;
        const double mid = median(p), hc = h[index(r, c)];
        if (std::abs(hc - mid) <= limit_um) continue;
        size_t disagree = 0;
        for (double v : p) disagree += std::abs(hc - v) > limit_um ? 1 : 0;
        const double share = static_cast<double>(disagree) / p.size();
        if (!worst || share > worst_share ||
            (share == worst_share &&
             std::abs(hc - mid) > std::abs(worst->height_um - worst->predicted_um))) {
          worst = Outlier{{r, c}, hc, mid};
          worst_share = share;
        }
      }
    if (!worst) return found;
    out[index(worst->point.row, worst->point.col)] = true;
    found.push_back(*worst);
  }
}

std::string describe_outlier(const ProbeGrid& g, const Outlier& o) {
  return fmt::format(
      "row {}, col {} at ({:.3f}, {:.3f}) mm reads {:.1f} um, its neighbours {:.1f} um",
      o.point.row, o.point.col, g.x_mm(o.point.col), g.y_mm(o.point.row), o.height_um,
      o.predicted_um);
}

}  // namespace host::heightmap
