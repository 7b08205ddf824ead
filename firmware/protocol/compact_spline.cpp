// #K compact spline data: writer, checker and unpacker (see compact_spline.h).
#include "firmware/protocol/compact_spline.h"

#include "firmware/protocol/varint.h"  // zigzag, put_varint, VarintReader

namespace proto {

namespace {

// Largest difference of two coordinates in range (a larger one is malformed, and refusing
// it first keeps the sums inside int32).
const int32_t kMaxDeltaUm = 2 * core::kMaxCoordinateUm;

// One point's numbers as sent.
struct RawPoint {
  int32_t dx;
  int32_t dy;
  int32_t dw;
  bool has_weight;
};

ErrorCode read_point(VarintReader* r, RawPoint* p) {
  uint32_t x = 0, y = 0, w = 0;
  ErrorCode e = r->next(&x);
  if (e == ErrorCode::kOk) e = r->next(&y);
  p->has_weight = (x & 1U) != 0;
  if (e == ErrorCode::kOk && p->has_weight) e = r->next(&w);
  p->dx = unzigzag(x >> 1);
  p->dy = unzigzag(y);
  p->dw = unzigzag(w);
  return e;
}

bool delta_ok(int32_t d) {
  return d >= -kMaxDeltaUm && d <= kMaxDeltaUm;
}

bool coordinate_ok(int32_t v) {
  return v >= -core::kMaxCoordinateUm && v <= core::kMaxCoordinateUm;
}

}  // namespace

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
  VarintReader r(m.data, m.data_n);
  for (uint8_t i = 0; i < m.control_n; ++i) {
    RawPoint p;
    const ErrorCode e = read_point(&r, &p);
    if (e != ErrorCode::kOk) return e;
  }
  for (uint8_t i = 0; i < m.knot_n; ++i) {
    uint32_t k = 0;
    const ErrorCode e = r.next(&k);
    if (e != ErrorCode::kOk) return e;
    const bool first = m.knot_index == 0 && i == 0;
    if (!first && (k & 1U)) {
      if (i + 1 >= m.knot_n) return ErrorCode::kPayloadLength;  // the repeat is one too many
      ++i;
    }
  }
  return r.at_end() ? ErrorCode::kOk : ErrorCode::kPayloadLength;
}

ErrorCode unpack_compact(const SplineCompactCmd& m, core::Spline* s) {
  VarintReader r(m.data, m.data_n);
  core::ControlPoint prev;
  prev.x_um = 0;
  prev.y_um = 0;
  prev.weight_q14 = core::kWeightOneQ14;
  if (m.control_index > 0) prev = s->control[m.control_index - 1];
  for (uint8_t i = 0; i < m.control_n; ++i) {
    RawPoint p;
    const ErrorCode e = read_point(&r, &p);
    if (e != ErrorCode::kOk) return e;
    if (p.has_weight && !s->rational) return ErrorCode::kFieldRange;
    if (!delta_ok(p.dx) || !delta_ok(p.dy) || !delta_ok(p.dw)) return ErrorCode::kFieldRange;
    core::ControlPoint c;
    c.x_um = prev.x_um + p.dx;
    c.y_um = prev.y_um + p.dy;
    const int32_t w = (int32_t)prev.weight_q14 + p.dw;
    if (!coordinate_ok(c.x_um) || !coordinate_ok(c.y_um) || w < 1 || w > 65535L)
      return ErrorCode::kFieldRange;
    c.weight_q14 = (uint16_t)w;
    s->control[m.control_index + i] = c;
    prev = c;
  }
  int32_t knot = m.knot_index > 0 ? s->knot[m.knot_index - 1] : 0;
  for (uint8_t i = 0; i < m.knot_n; ++i) {
    uint32_t v = 0;
    const ErrorCode e = r.next(&v);
    if (e != ErrorCode::kOk) return e;
    if (m.knot_index == 0 && i == 0) {
      knot = unzigzag(v);
    } else {
      // Room above the previous knot in int32, in unsigned arithmetic (no overflow).
      const uint32_t span = v >> 1;
      const uint32_t room = (uint32_t)0x7FFFFFFFUL - (uint32_t)knot;
      if (span > room) return ErrorCode::kFieldRange;
      knot = (int32_t)((uint32_t)knot + span);
      if (v & 1U) {  // the same knot once more
        if (i + 1 >= m.knot_n) return ErrorCode::kPayloadLength;
        s->knot[m.knot_index + i] = knot;
        ++i;
      }
    }
    s->knot[m.knot_index + i] = knot;
  }
  return r.at_end() ? ErrorCode::kOk : ErrorCode::kPayloadLength;
}

}  // namespace proto
