// Host B-spline -> firmware core::Spline conversion (see firmware_spline.h).
#include "host/lib/plan/firmware_spline.h"

#include <algorithm>  // std::max, std::sort, std::unique
#include <cmath>      // std::llround, std::fabs
#include <cstdint>    // int64_t
#include <cstring>    // memset
#include <map>        // std::map
#include <sstream>    // std::ostringstream

#include "host/lib/plan/contour_form.h"  // snap_to_contour_form

namespace host {

namespace {

// Splits a clamped spline at interior knots until every piece has at most max_control
// control points. A knot of multiplicity = degree makes the curve pass through one control
// point, where it is cut into two clamped curves. Each cut works on a window of the next
// few dozen control points (knot insertion only changes points near the knot), so a curve
// of a million points is split in linear time.
std::vector<BSpline> split_to_fit(const BSpline& c, size_t max_control) {
  const size_t p = static_cast<size_t>(c.degree);
  // Enough for the cut knot (index <= max_control), its run (< p more) and the spans that
  // inserting it reads (p more).
  const size_t window = max_control + 2 * p + 2;
  std::vector<BSpline> out;
  // The part not yet cut off: `head` (taken from c and perhaps changed by knot insertion),
  // then c's control points from next_control and knots from next_knot; head always holds
  // control count + degree + 1 knots.
  BSpline head;
  head.degree = c.degree;
  size_t next_control = 0, next_knot = 0;
  for (;;) {
    while (head.control.size() < window && next_control < c.control.size()) {
      head.control.push_back(c.control[next_control]);
      if (c.rational()) head.weights.push_back(c.weights[next_control]);
      ++next_control;
    }
    while (head.knots.size() < head.control.size() + p + 1)
      head.knots.push_back(c.knots[next_knot++]);
    if (head.control.size() <= max_control) break;
    // The last run start (first index) of an interior knot value within the first max_control.
    size_t best = 0;
    for (size_t i = p + 1; i <= max_control; ++i) {
      if (head.knots[i] != head.knots[i - 1]) best = i;
    }
    if (best == 0) throw ConversionError("no interior knot to split the curve at");
    const double u = head.knots[best];
    size_t mult = 0;
    while (best + mult < head.knots.size() && head.knots[best + mult] == u) ++mult;
    for (; mult < p; ++mult) head = insert_knot(head, u);
    // Joint control point: index best - 1 (the run of u starts at knot index best).
    BSpline left;
    left.degree = c.degree;
    left.control.assign(head.control.begin(), head.control.begin() + best);
    if (c.rational()) left.weights.assign(head.weights.begin(), head.weights.begin() + best);
    left.knots.assign(head.knots.begin(), head.knots.begin() + best + p);
    left.knots.push_back(u);
    out.push_back(std::move(left));
    head.control.erase(head.control.begin(), head.control.begin() + best - 1);
    if (c.rational()) head.weights.erase(head.weights.begin(), head.weights.begin() + best - 1);
    head.knots.erase(head.knots.begin(), head.knots.begin() + best - 1);
    head.knots.front() = u;
  }
  out.push_back(std::move(head));
  return out;
}

// Worst relative rounding error of the weights w scaled so the largest is m; once it reaches
// `enough` the rest are not looked at (a search that only takes an error below it).
double weight_error(const std::vector<double>& w, double w_max, long m, double enough = 1e300) {
  const double f = static_cast<double>(m) / w_max;
  double err = 0;
  for (double x : w) {
    const double q = std::floor(x * f + 0.5);
    if (q < 1) return 1e300;
    err = std::max(err, std::fabs(q - x * f) / q);
    if (err >= enough) return err;
  }
  return err;
}

// Integer Q14 weights for a rational spline: the common factor that puts the largest
// weight at m / 16384. The smallest m under 32768 that the rounding bound guarantees keeps
// every weight's relative error below 0.25 um over the longest control leg (1e-4 at most;
// the curve moves by about a tenth of a micrometre, and its points are whole micrometres
// anyway): small weights differ by little, which the compact #K frames send in few bytes.
// Failing that, m in [32768, 65535] with the smallest worst relative error.
std::vector<uint16_t> quantise_weights(const std::vector<double>& w, double max_leg_um) {
  double w_max = 0;
  for (double x : w) w_max = std::max(w_max, x);
  const double tolerance = std::min(1e-4, 0.25 / std::max(max_leg_um, 1.0));
  // Rounding moves a weight x scaled by m / w_max by half a unit at most: a relative error
  // within tolerance for every weight once the smallest is 0.5 / tolerance + 0.5 units.
  // The errors depend on the distinct weights alone: a spline of arcs has a few among many
  // control points (1 and each arc's cos(sweep / 2)), smallest first, which err most.
  std::vector<double> distinct = w;
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  const double w_min = distinct.front();
  const double m_sure = std::ceil((0.5 / tolerance + 0.5) * w_max / w_min);
  long best_m = 0, best_fallback = 65535;
  if (m_sure < 32768 && weight_error(distinct, w_max, static_cast<long>(m_sure)) <= tolerance)
    best_m = static_cast<long>(m_sure);
  // The fallback's m depends on the weights alone, and a board's arcs repeat a few angles:
  // each search tries up to 32 768 scales, so its answers are kept (a bounded number).
  thread_local std::map<std::vector<double>, long> searched;
  if (best_m == 0) {
    const auto known = searched.find(distinct);
    if (known != searched.end()) best_m = known->second;
  }
  double best_err = 1e300;
  for (long m = 65535; best_m == 0 && m >= 32768; --m) {
    const double err = weight_error(distinct, w_max, m, best_err);
    if (err < best_err) best_err = err, best_fallback = m;
    if (err < 1e-9) break;
  }
  if (best_m == 0) {
    best_m = best_fallback;
    if (searched.size() >= 4096) searched.clear();  // a job of many angles
    searched.emplace(distinct, best_m);
  }
  std::vector<uint16_t> q;
  const double f = static_cast<double>(best_m) / w_max;
  for (double x : w) {
    const double v = std::floor(x * f + 0.5);
    if (v < 1) {
      std::ostringstream o;
      o << "weights range from " << x << " to " << w_max
        << ": too wide for the firmware's Q2.14 weights";
      throw ConversionError(o.str());
    }
    q.push_back(static_cast<uint16_t>(v));
  }
  return q;
}

// Integer knots, chain by chain. A knot of multiplicity >= degree cuts the spline into two
// curves that do not depend on each other's knots, and a curve keeps its shape under an
// affine map of its own knots: so each such chain gets its own scale. A chain of one span
// (a Bezier piece between corners, every span of a degree-1 spline) is 1 unit long; a longer
// chain gets units so that each span is at least 4x the longest control leg (um) around it
// (moving a knot by half a unit then moves the curve by about 1/8 um), 16 units at least,
// but never a finer scale than the whole vector over kKnotRangeTarget units. Small spans
// are what the compact #K frames carry in few bytes.
std::vector<int32_t> chain_knots(const BSpline& s) {
  const size_t p = static_cast<size_t>(s.degree);
  const size_t nk = s.knots.size();
  const double whole = static_cast<double>(kKnotRangeTarget) / (s.knots.back() - s.knots.front());
  std::vector<int32_t> out(nk, 0);
  // Multiplicity of the value at each knot index (the knots never decrease: runs).
  std::vector<size_t> multiplicity(nk, 0);
  for (size_t i = 0; i < nk;) {
    size_t e = i;
    while (e < nk && s.knots[e] == s.knots[i]) ++e;
    for (size_t k = i; k < e; ++k) multiplicity[k] = e - i;
    i = e;
  }
  auto leg_um = [&](size_t span) {  // span i uses control points i-p .. i
    double leg = 0;
    for (size_t c = span >= p ? span - p + 1 : 1; c <= span && c < s.control.size(); ++c)
      leg = std::max(leg, (s.control[c] - s.control[c - 1]).norm() * 1000.0);
    return leg;
  };
  int64_t at = 0;  // integer value of the chain's first knot
  size_t first = 0;
  while (first + 1 < nk) {
    // The chain: knots first..last, cut at an interior knot of multiplicity >= degree.
    size_t last = first + 1;
    while (last + 1 < nk && !(s.knots[last] > s.knots[first] && s.knots[last + 1] > s.knots[last] &&
                              multiplicity[last] >= p))
      ++last;
    int spans = 0;
    double scale = 16.0 / (s.knots[last] - s.knots[first]);
    for (size_t i = first; i < last; ++i) {
      const double span = s.knots[i + 1] - s.knots[i];
      if (span <= 0) continue;
      ++spans;
      scale = std::max(scale, std::max(16.0, 4.0 * leg_um(i)) / span);
    }
    if (spans == 1) scale = 1.0 / (s.knots[last] - s.knots[first]);
    scale = std::min(scale, whole);
    for (size_t i = first; i <= last; ++i)
      out[i] = static_cast<int32_t>(at + std::llround((s.knots[i] - s.knots[first]) * scale));
    at = out[last];
    first = last;
  }
  return out;
}

// One piece (at most kMaxControlPoints control points) in firmware form.
core::Spline to_firmware(const BSpline& s) {
  core::Spline f;
  memset(&f, 0, sizeof f);
  f.degree = static_cast<uint8_t>(s.degree);
  f.rational = s.rational();
  f.control_count = static_cast<uint16_t>(s.control.size());
  f.knot_count = static_cast<uint16_t>(s.knots.size());
  std::vector<uint16_t> w;
  if (s.rational()) {
    double leg_um = 0;
    for (size_t i = 1; i < s.control.size(); ++i)
      leg_um = std::max(leg_um, (s.control[i] - s.control[i - 1]).norm() * 1000.0);
    w = quantise_weights(s.weights, leg_um);
  }
  for (size_t i = 0; i < s.control.size(); ++i) {
    const double x_um = s.control[i].x() * 1000.0;
    const double y_um = s.control[i].y() * 1000.0;
    if (!(std::fabs(x_um) <= core::kMaxCoordinateUm) ||
        !(std::fabs(y_um) <= core::kMaxCoordinateUm)) {
      std::ostringstream o;
      o << "control point " << i << " (" << s.control[i].x() << ", " << s.control[i].y()
        << ") mm is beyond the firmware's +-" << core::kMaxCoordinateUm / 1000 << " mm";
      throw ConversionError(o.str());
    }
    f.control[i].x_um = static_cast<int32_t>(std::llround(x_um));
    f.control[i].y_um = static_cast<int32_t>(std::llround(y_um));
    f.control[i].weight_q14 = s.rational() ? w[i] : core::kWeightOneQ14;
  }
  const std::vector<int32_t> knots = chain_knots(s);
  for (size_t i = 0; i < s.knots.size(); ++i) f.knot[i] = knots[i];
  for (size_t i = 0; i + 1 < s.knots.size(); ++i) {
    if (s.knots[i + 1] > s.knots[i] && f.knot[i + 1] == f.knot[i]) {
      throw ConversionError(
          "a knot span is shorter than the firmware's knot resolution "
          "(1 / 2^28 of the knot vector)");
    }
  }
  // Lines and arcs between corners go out as #Q frames: the plan holds what those rebuild.
  snap_to_contour_form(&f);
  const core::GeometryError e = core::validate_spline(f);
  if (e != core::GeometryError::kOk) {
    std::ostringstream o;
    o << "the converted spline fails the firmware's check (geometry error " << static_cast<int>(e)
      << ")";
    throw ConversionError(o.str());
  }
  return f;
}

}  // namespace

std::vector<core::Spline> to_firmware_splines(const BSpline& mm_spline) {
  const std::string problem = check_bspline(mm_spline);
  if (!problem.empty()) throw ConversionError(problem);
  if (mm_spline.degree > core::kMaxDegree) {
    throw ConversionError("degree " + std::to_string(mm_spline.degree) +
                          " is above the firmware's " + std::to_string(core::kMaxDegree));
  }
  std::vector<BSpline> pieces;
  if (mm_spline.control.size() <= core::kMaxControlPoints) {
    pieces.push_back(mm_spline);
  } else {
    pieces = split_to_fit(clamped(mm_spline), core::kMaxControlPoints);
  }
  std::vector<core::Spline> out;
  out.reserve(pieces.size());
  for (const BSpline& p : pieces) out.push_back(to_firmware(p));
  return out;
}

BSpline from_firmware_spline(const core::Spline& f) {
  BSpline s;
  s.degree = f.degree;
  for (uint16_t i = 0; i < f.control_count; ++i) {
    s.control.emplace_back(f.control[i].x_um / 1000.0, f.control[i].y_um / 1000.0);
    if (f.rational) s.weights.push_back(f.control[i].weight_q14 / 16384.0);
  }
  for (uint16_t i = 0; i < f.knot_count; ++i) s.knots.push_back(f.knot[i]);
  return s;
}

}  // namespace host
