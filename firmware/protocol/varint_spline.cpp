// The one reader of #K and #Q spline data (see varint_spline.h).
#include "firmware/protocol/varint_spline.h"

#include "firmware/protocol/contour_spline.h"  // contour_middle, ContourElement
#include "firmware/protocol/varint.h"          // VarintReader, unzigzag

namespace proto {

namespace {

// Largest difference of two coordinates in range (refusing a larger one keeps sums in int32).
const int32_t kMaxDeltaUm = 2 * core::kMaxCoordinateUm;

// |v| <= limit, for any v (negating INT32_MIN would overflow).
bool within(int32_t v, int32_t limit) {
  return v >= -limit && v <= limit;
}

bool point_ok(const core::ControlPoint& p) {
  return within(p.x_um, core::kMaxCoordinateUm) && within(p.y_um, core::kMaxCoordinateUm);
}

// #K knots after the points: the first knot of the spline as itself, every later one as
// its span from the previous knot with the repeat flag.
ErrorCode read_knots(const VarintSplineFrame& f, VarintReader* r, core::Spline* s) {
  int32_t knot = (s != 0 && f.knot_index > 0) ? s->knot[f.knot_index - 1] : 0;
  for (uint8_t i = 0; i < f.knot_n; ++i) {
    uint32_t v = 0;
    const ErrorCode e = r->next(&v);
    if (e != ErrorCode::kOk) return e;
    if (f.knot_index == 0 && i == 0) {
      knot = unzigzag(v);
    } else {
      // Room above the previous knot in int32, in unsigned arithmetic (no overflow).
      const uint32_t span = v >> 1;
      if (s != 0 && span > (uint32_t)0x7FFFFFFFUL - (uint32_t)knot) return ErrorCode::kFieldRange;
      knot = (int32_t)((uint32_t)knot + span);
      if (v & 1U) {  // the same knot once more
        if (i + 1 >= f.knot_n) return ErrorCode::kPayloadLength;
        if (s != 0) s->knot[f.knot_index + i] = knot;
        ++i;
      }
    }
    if (s != 0) s->knot[f.knot_index + i] = knot;
  }
  return ErrorCode::kOk;
}

// #Q's knots once its last point is stored: 0 0 0, each corner's index twice, the last
// three times.
void write_contour_knots(core::Spline* s) {
  const uint8_t elements = (uint8_t)((s->control_count - 1U) / 2U);
  uint8_t k = 0;
  s->knot[k++] = 0;
  for (uint8_t i = 0; i <= elements; ++i) {
    s->knot[k++] = i;
    s->knot[k++] = i;
  }
  s->knot[k++] = elements;
}

}  // namespace

ErrorCode read_varint_spline(const VarintSplineFrame& f, core::Spline* s) {
  uint8_t at = f.control_index;
  // #Q at index 0 starts with the spline's first point (two plain numbers, no middle);
  // every other #Q frame starts at a corner (odd index) and holds whole elements.
  bool start = f.contour && at == 0;
  uint8_t items = f.control_n;
  if (f.contour) {
    if (start ? (f.control_n & 1U) == 0 : ((at & 1U) == 0 || (f.control_n & 1U) != 0))
      return ErrorCode::kFieldRange;
    // The first point and (n - 1) / 2 elements, or n / 2 elements.
    items = (uint8_t)((f.control_n + 1U) / 2U);
  }
  VarintReader r(f.data, f.data_n);
  core::ControlPoint prev;
  prev.x_um = 0;
  prev.y_um = 0;
  prev.weight_q14 = core::kWeightOneQ14;
  if (s != 0 && at > 0) prev = s->control[at - 1];
  for (uint8_t i = 0; i < items; ++i, start = false) {
    // x (flagged but at a #Q start), y, and the third number when flagged.
    uint32_t v[3] = {0, 0, 0};
    for (uint8_t k = 0; k < 3; ++k) {
      if (k == 2 && (start || (v[0] & 1U) == 0)) break;
      const ErrorCode e = r.next(&v[k]);
      if (e != ErrorCode::kOk) return e;
    }
    if (s == 0) continue;
    const bool flagged = !start && (v[0] & 1U) != 0;
    if (!start) v[0] >>= 1;
    // Every difference within kMaxDeltaUm (a #Q height beyond it is refused by
    // contour_middle all the same: kFieldRange either way), in place.
    int32_t* const dv = reinterpret_cast<int32_t*>(v);  // signed view of v (may alias)
    for (uint8_t k = 0; k < 3; ++k) {
      dv[k] = unzigzag(v[k]);
      if (!within(dv[k], kMaxDeltaUm)) return ErrorCode::kFieldRange;
    }
    ContourElement d;
    d.dx_um = dv[0];
    d.dy_um = dv[1];
    d.arc = flagged;
    d.height_um = dv[2];  // #K: the weight's difference
    core::ControlPoint p;
    p.x_um = prev.x_um + d.dx_um;
    p.y_um = prev.y_um + d.dy_um;
    p.weight_q14 = core::kWeightOneQ14;
    if (!f.contour) {
      if (flagged && !s->rational) return ErrorCode::kFieldRange;
      const int32_t w = (int32_t)prev.weight_q14 + d.height_um;
      if (w < 1 || w > 65535L) return ErrorCode::kFieldRange;
      p.weight_q14 = (uint16_t)w;
    }
    if (!point_ok(p)) return ErrorCode::kFieldRange;
    if (f.contour && !start) {
      core::ControlPoint* middle = &s->control[at++];
      const ErrorCode e = contour_middle(prev, d, middle);
      if (e != ErrorCode::kOk) return e;
      if (!point_ok(*middle)) return ErrorCode::kFieldRange;
    }
    s->control[at++] = p;
    prev = p;
  }
  const ErrorCode e = read_knots(f, &r, s);
  if (e != ErrorCode::kOk) return e;
  if (!r.at_end()) return ErrorCode::kPayloadLength;
  if (f.contour && s != 0 && at == s->control_count) write_contour_knots(s);
  return ErrorCode::kOk;
}

}  // namespace proto
