// #Q contour data: writer, checker and unpacker (see contour_spline.h).
#include "firmware/protocol/contour_spline.h"

#include "firmware/core/isqrt.h"       // isqrt32
#include "firmware/protocol/varint.h"  // zigzag, put_varint, VarintReader

namespace proto {

namespace {

// Largest difference of two coordinates in range (refusing a larger one keeps sums in int32).
const int32_t kMaxDeltaUm = 2 * core::kMaxCoordinateUm;

bool coordinate_ok(int32_t v) {
  return v >= -core::kMaxCoordinateUm && v <= core::kMaxCoordinateUm;
}

// n / d rounded to nearest (halves away from zero), d > 0.
int32_t divide_rounded(int32_t n, int32_t d) {
  return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

// floor(n * 2^26 / d) for n < 4 d and d < 2^31: long division, a quotient bit a step, so
// no 64-bit arithmetic.
uint32_t ratio_q26(uint32_t n, uint32_t d) {
  uint32_t q = n / d;
  uint32_t rem = n - q * d;
  for (uint8_t i = 0; i < 26; ++i) {
    rem <<= 1;  // rem < d < 2^31
    q <<= 1;
    if (rem >= d) {
      rem -= d;
      q |= 1U;
    }
  }
  return q;
}

// sqrt(n) rounded to nearest.
uint32_t isqrt_rounded(uint32_t n) {
  const uint32_t r = core::isqrt32(n);
  return n - r * r > r ? r + 1U : r;  // (r + 1/2)^2 = r^2 + r + 1/4
}

// |v| <= limit, for any v (negating INT32_MIN would overflow).
bool within(int32_t v, int32_t limit) {
  return v >= -limit && v <= limit;
}

// Reads the numbers of one element.
ErrorCode read_element(VarintReader* r, ContourElement* e) {
  uint32_t x = 0, y = 0, h = 0;
  ErrorCode err = r->next(&x);
  if (err == ErrorCode::kOk) err = r->next(&y);
  e->arc = (x & 1U) != 0;
  if (err == ErrorCode::kOk && e->arc) err = r->next(&h);
  e->dx_um = unzigzag(x >> 1);
  e->dy_um = unzigzag(y);
  e->height_um = unzigzag(h);
  return err;
}

// Elements in a frame whose counts scan_contour accepted.
uint8_t element_count(const SplineContourCmd& m) {
  return (uint8_t)((m.control_index == 0 ? m.control_n - 1U : m.control_n) / 2U);
}

}  // namespace

ErrorCode contour_middle(const core::ControlPoint& p0, const ContourElement& e,
                         core::ControlPoint* middle) {
  middle->x_um = p0.x_um + e.dx_um / 2;
  middle->y_um = p0.y_um + e.dy_um / 2;
  middle->weight_q14 = core::kWeightOneQ14;
  if (!e.arc) return ErrorCode::kOk;
  if (!within(e.dx_um, kMaxContourArcAxisUm) || !within(e.dy_um, kMaxContourArcAxisUm))
    return ErrorCode::kFieldRange;
  const uint32_t chord2 = (uint32_t)(e.dx_um * e.dx_um) + (uint32_t)(e.dy_um * e.dy_um);
  const int32_t chord = (int32_t)core::isqrt32(chord2);
  if (chord == 0 || !within(e.height_um, chord)) return ErrorCode::kFieldRange;
  // The unit normal (-dy, dx) / chord times the height; |height * d| < 2^29.
  middle->x_um += divide_rounded(-e.height_um * e.dy_um, chord);
  middle->y_um += divide_rounded(e.height_um * e.dx_um, chord);
  // weight^2 = cos^2(half angle) = chord^2 / (4 leg^2), from the rounded middle point.
  const int32_t lx = middle->x_um - p0.x_um;
  const int32_t ly = middle->y_um - p0.y_um;
  const uint32_t leg2 = (uint32_t)(lx * lx) + (uint32_t)(ly * ly);  // < 2^31: |l| < 2^15
  // A leg no longer than half the chord (rounding, at a height of about 0): weight 1.0.
  if (leg2 <= chord2 / 4U) return ErrorCode::kOk;
  middle->weight_q14 = (uint16_t)isqrt_rounded(ratio_q26(chord2, leg2));
  return ErrorCode::kOk;
}

uint8_t put_contour_start(int32_t x_um, int32_t y_um, uint8_t* out) {
  const uint8_t n = put_varint(zigzag(x_um), out);
  return (uint8_t)(n + put_varint(zigzag(y_um), out + n));
}

uint8_t put_contour_element(const ContourElement& e, uint8_t* out) {
  uint8_t n = put_varint((zigzag(e.dx_um) << 1) | (e.arc ? 1U : 0U), out);
  n = (uint8_t)(n + put_varint(zigzag(e.dy_um), out + n));
  if (e.arc) n = (uint8_t)(n + put_varint(zigzag(e.height_um), out + n));
  return n;
}

ErrorCode scan_contour(const SplineContourCmd& m) {
  // Index 0 starts with the first point; every other frame starts at a corner (odd index).
  const bool first = m.control_index == 0;
  if (first ? (m.control_n & 1U) == 0 : ((m.control_index & 1U) == 0 || (m.control_n & 1U) != 0))
    return ErrorCode::kFieldRange;
  VarintReader r(m.data, m.data_n);
  uint32_t v = 0;
  ErrorCode e = ErrorCode::kOk;
  if (first) {
    e = r.next(&v);
    if (e == ErrorCode::kOk) e = r.next(&v);
  }
  const uint8_t n = element_count(m);
  for (uint8_t i = 0; i < n && e == ErrorCode::kOk; ++i) {
    ContourElement el;
    e = read_element(&r, &el);
  }
  if (e != ErrorCode::kOk) return e;
  return r.at_end() ? ErrorCode::kOk : ErrorCode::kPayloadLength;
}

ErrorCode unpack_contour(const SplineContourCmd& m, core::Spline* s) {
  VarintReader r(m.data, m.data_n);
  core::ControlPoint p0;
  uint8_t at = m.control_index;
  if (at == 0) {
    uint32_t x = 0, y = 0;
    ErrorCode e = r.next(&x);
    if (e == ErrorCode::kOk) e = r.next(&y);
    if (e != ErrorCode::kOk) return e;
    p0.x_um = unzigzag(x);
    p0.y_um = unzigzag(y);
    p0.weight_q14 = core::kWeightOneQ14;
    if (!coordinate_ok(p0.x_um) || !coordinate_ok(p0.y_um)) return ErrorCode::kFieldRange;
    s->control[at++] = p0;
  } else {
    p0 = s->control[at - 1];
  }
  const uint8_t n = element_count(m);
  for (uint8_t i = 0; i < n; ++i) {
    ContourElement el;
    ErrorCode e = read_element(&r, &el);
    if (e != ErrorCode::kOk) return e;
    if (!within(el.dx_um, kMaxDeltaUm) || !within(el.dy_um, kMaxDeltaUm))
      return ErrorCode::kFieldRange;
    core::ControlPoint p1;
    p1.x_um = p0.x_um + el.dx_um;
    p1.y_um = p0.y_um + el.dy_um;
    p1.weight_q14 = core::kWeightOneQ14;
    if (!coordinate_ok(p1.x_um) || !coordinate_ok(p1.y_um)) return ErrorCode::kFieldRange;
    e = contour_middle(p0, el, &s->control[at]);
    if (e != ErrorCode::kOk) return e;
    if (!coordinate_ok(s->control[at].x_um) || !coordinate_ok(s->control[at].y_um))
      return ErrorCode::kFieldRange;
    s->control[at + 1] = p1;
    at = (uint8_t)(at + 2U);
    p0 = p1;
  }
  if (!r.at_end()) return ErrorCode::kPayloadLength;
  if (at == s->control_count) {
    // Knots 0 0 0, each corner's index twice, the last three times.
    const uint8_t elements = (uint8_t)((s->control_count - 1U) / 2U);
    uint8_t k = 0;
    s->knot[k++] = 0;
    for (uint8_t i = 0; i <= elements; ++i) {
      s->knot[k++] = i;
      s->knot[k++] = i;
    }
    s->knot[k++] = elements;
  }
  return ErrorCode::kOk;
}

bool is_contour_shape(const core::Spline& s) {
  return s.degree == 2 && s.rational && (s.control_count & 1U) == 1U &&
         s.knot_count == s.control_count + 3U;
}

}  // namespace proto
