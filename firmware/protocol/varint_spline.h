// The one reader of the varint spline frames, #K (compact) and #Q (contour): both are
// points as differences from the previous one, flagged x, then y, then a third number when
// flagged (#K: the weight's difference; #Q: the arc's height). Checks a frame's structure
// (codec) or unpacks it into a spline (spline store); compact_spline.h and contour_spline.h
// give each frame's layout.
#ifndef FIRMWARE_PROTOCOL_VARINT_SPLINE_H
#define FIRMWARE_PROTOCOL_VARINT_SPLINE_H

#include <stdint.h>  // uint8_t

#include "firmware/core/spline.h"          // Spline
#include "firmware/protocol/wire_codes.h"  // ErrorCode

namespace proto {

// A #K or #Q frame's fields (a #Q frame has no knot fields: knot_index = knot_n = 0).
struct VarintSplineFrame {
  const uint8_t* data;
  uint8_t data_n;
  uint8_t control_index;
  uint8_t control_n;
  uint8_t knot_index;
  uint8_t knot_n;
  bool contour;  // #Q
};

// s == 0: only the structure (scan_compact, scan_contour). Else the values written into s
// as unpack_compact / unpack_contour describe.
ErrorCode read_varint_spline(const VarintSplineFrame& f, core::Spline* s);

// read_varint_spline of the frame with those fields (#K and #Q hand theirs in).
inline ErrorCode read_varint_fields(const uint8_t* data, uint8_t data_n, uint8_t control_index,
                                    uint8_t control_n, uint8_t knot_index, uint8_t knot_n,
                                    bool contour, core::Spline* s) {
  const VarintSplineFrame f = {data, data_n, control_index, control_n, knot_index, knot_n, contour};
  return read_varint_spline(f, s);
}

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_VARINT_SPLINE_H
