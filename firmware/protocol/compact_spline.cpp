// #K compact spline data: writer, checker and unpacker (see compact_spline.h).
#include "firmware/protocol/compact_spline.h"

#include "firmware/protocol/varint.h"         // zigzag, put_varint
#include "firmware/protocol/varint_spline.h"  // read_varint_fields

namespace proto {

uint8_t put_compact_point(const core::ControlPoint& prev, const core::ControlPoint& p,
                          bool rational, uint8_t* out) {
  const bool has_weight = rational && p.weight_q14 != prev.weight_q14;
  uint8_t n = put_varint((zigzag(p.x_um - prev.x_um) << 1) | (has_weight ? 1U : 0U), out);
  n = (uint8_t)(n + put_varint(zigzag(p.y_um - prev.y_um), out + n));
  if (has_weight) {
    const int32_t dw = (int32_t)p.weight_q14 - (int32_t)prev.weight_q14;
    n = (uint8_t)(n + put_varint(zigzag(dw), out + n));
  }
  return n;
}

uint8_t put_compact_knot(int32_t prev, int32_t k, bool first, bool repeat, uint8_t* out) {
  if (first) return put_varint(zigzag(k), out);
  if (k < prev) return 0;
  const uint32_t span = (uint32_t)k - (uint32_t)prev;
  if (span > kMaxCompactSpan) return 0;
  return put_varint((span << 1) | (repeat ? 1U : 0U), out);
}

ErrorCode scan_compact(const SplineCompactCmd& m) {
  return unpack_compact(m, 0);  // no spline: the structure only
}

ErrorCode unpack_compact(const SplineCompactCmd& m, core::Spline* s) {
  return read_varint_fields(m.data, m.data_n, m.control_index, m.control_n, m.knot_index, m.knot_n,
                            false, s);
}

}  // namespace proto
