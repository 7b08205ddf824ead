// #Q contour data: writer, checker and unpacker (see contour_spline.h).
#include "firmware/protocol/contour_spline.h"

#include "firmware/core/divide.h"             // div_u32_u16
#include "firmware/core/isqrt.h"              // isqrt32
#include "firmware/protocol/varint.h"         // zigzag, put_varint
#include "firmware/protocol/varint_spline.h"  // read_varint_fields

namespace proto {

namespace {

// n / d rounded to nearest (halves away from zero), d > 0 and |n| <= d * d (the quotient
// fits 16 bits): one 32/16 division.
__attribute__((noinline)) int32_t divide_rounded(int32_t n, uint16_t d) {
  const uint32_t magnitude = (uint32_t)(n >= 0 ? n : -n) + d / 2U;
  const int32_t q = (int32_t)core::div_u32_u16(magnitude, d, 0);
  return n >= 0 ? q : -q;
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

// |v| <= limit, for any v (negating INT32_MIN would overflow). Out of line: contour_middle
// checks three values (-34 B on the AVR proxy).
__attribute__((noinline)) bool within(int32_t v, int32_t limit) {
  return v >= -limit && v <= limit;
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
  // Every factor below fits 16 bits: |dx|, |dy| <= 16383, |height| <= chord < 2^15.
  const int16_t dx = (int16_t)e.dx_um;
  const int16_t dy = (int16_t)e.dy_um;
  const uint32_t chord2 = (uint32_t)((int32_t)dx * dx) + (uint32_t)((int32_t)dy * dy);
  const uint16_t chord = core::isqrt32(chord2);
  if (chord == 0 || !within(e.height_um, chord)) return ErrorCode::kFieldRange;
  const int16_t h = (int16_t)e.height_um;
  // The unit normal (-dy, dx) / chord times the height; |height * d| <= chord^2 < 2^29.
  middle->x_um += divide_rounded(-((int32_t)h * dy), chord);
  middle->y_um += divide_rounded((int32_t)h * dx, chord);
  // weight^2 = cos^2(half angle) = chord^2 / (4 leg^2), from the rounded middle point.
  const int16_t lx = (int16_t)(middle->x_um - p0.x_um);  // |l| < 2^15
  const int16_t ly = (int16_t)(middle->y_um - p0.y_um);
  const uint32_t leg2 = (uint32_t)((int32_t)lx * lx) + (uint32_t)((int32_t)ly * ly);  // < 2^31
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
  return unpack_contour(m, 0);  // no spline: the structure only
}

ErrorCode unpack_contour(const SplineContourCmd& m, core::Spline* s) {
  return read_varint_fields(m.data, m.data_n, m.control_index, m.control_n, 0, 0, true, s);
}

bool is_contour_shape(const core::Spline& s) {
  return s.degree == 2 && s.rational && (s.control_count & 1U) == 1U &&
         s.knot_count == s.control_count + 3U;
}

}  // namespace proto
