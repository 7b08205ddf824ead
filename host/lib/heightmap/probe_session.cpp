// Probing a blank into a height map (probe_session.h).
#include "host/lib/heightmap/probe_session.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>  // std::abs
#include <ctime>  // std::time, gmtime_r

namespace host::heightmap {

std::string utc_now_iso8601() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

ProbeRun probe_blank(const AreaMm& job, const ProbeOptions& o, const ProbeTouch& touch,
                     const ProbeProgress& progress) {
  const ProbeGrid g = plan_probe_grid(job, o.grid);
  const std::vector<GridPoint> order = probe_order(g);
  const size_t per_point = o.twice ? 2 : 1;
  size_t planned = order.size() * per_point;
  ProbeRun run;
  std::vector<double> heights(static_cast<size_t>(g.rows) * g.cols, 0.0);
  double repeatability = 0;
  // One point: its reading (the mean of two touches when twice); the spread of two touches
  // further apart than the outlier limit is a loose clip or a chip: refused there.
  auto probe_point = [&](const GridPoint& p) {
    const double x = g.x_mm(p.col), y = g.y_mm(p.row);
    const double first = touch(x, y);
    ++run.touches;
    if (progress) progress(run.touches, planned);
    if (!o.twice) return first;
    const double second = touch(x, y);
    ++run.touches;
    if (progress) progress(run.touches, planned);
    const double spread = std::abs(second - first);
    if (spread > o.outlier_limit_um)
      throw ProbeRefused(fmt::format(
          "probe point row {}, col {} at ({:.3f}, {:.3f}) mm read {:.1f} um then {:.1f} um: "
          "more than {:g} um apart (a loose probe clip, or a chip on the bit?)",
          p.row, p.col, x, y, first, second, o.outlier_limit_um));
    repeatability = std::max(repeatability, spread);
    return 0.5 * (first + second);
  };
  for (const GridPoint& p : order)
    heights[static_cast<size_t>(p.row) * g.cols + p.col] = probe_point(p);

  // Points their neighbours disagree with: probed again once; a reading that now agrees
  // replaces the first (a chip that fell off, a clip that slipped back).
  std::vector<Outlier> outliers = find_outliers(g, heights, o.outlier_limit_um);
  if (!outliers.empty()) {
    planned += outliers.size() * per_point;
    for (const Outlier& out : outliers) {
      const double again = probe_point(out.point);
      run.reprobed.push_back(
          fmt::format("{}; probed again: {:.1f} um", describe_outlier(g, out), again));
      heights[static_cast<size_t>(out.point.row) * g.cols + out.point.col] = again;
    }
    outliers = find_outliers(g, heights, o.outlier_limit_um);
  }
  if (!outliers.empty()) {
    std::string places;
    for (const Outlier& out : outliers) places += "\n  " + describe_outlier(g, out);
    throw ProbeRefused(fmt::format(
        "{} probe point{} still disagree{} with {} neighbours by more than {:g} um after "
        "probing again (a chip or dent in the copper, or a loose probe clip): clean the blank "
        "there, or raise --outlier-limit if the blank is that uneven:{}",
        outliers.size(), outliers.size() == 1 ? "" : "s", outliers.size() == 1 ? "s" : "",
        outliers.size() == 1 ? "its" : "their", o.outlier_limit_um, places));
  }
  HeightMap& m = run.map;
  m.origin_x_mm = g.origin_x_mm;
  m.origin_y_mm = g.origin_y_mm;
  m.pitch_x_mm = g.pitch_x_mm;
  m.pitch_y_mm = g.pitch_y_mm;
  m.rows = g.rows;
  m.cols = g.cols;
  m.heights_um = heights;
  if (o.twice) m.repeatability_um = std::round(repeatability * 10) / 10;
  m.probed_at = utc_now_iso8601();
  m.blank = o.blank;
  validate(m, "the probed height map");
  return run;
}

}  // namespace host::heightmap
