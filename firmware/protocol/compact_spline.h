// The #K compact spline data (docs/protocol.md): control points as differences from the
// spline's previous point and knots as spans from its previous knot, each a variable-length
// integer (7 bits a byte, low groups first, high bit = more bytes follow; at most 5 bytes).
//   point: varint(zigzag(dx) * 2 + has_weight), varint(zigzag(dy)),
//          then varint(zigzag(dw)) when has_weight (only in a rational spline; a point
//          without it keeps the previous point's weight)
//   knot:  the spline's first knot varint(zigzag(k)); every later one
//          varint((k - previous) * 2 + repeat), repeat = 1 when the knot after it is the
//          same value (that knot then has no bytes of its own); a span over
//          kMaxCompactSpan does not fit (the sender uses #D for it)
// The first point is taken from (0, 0) with weight 16384 (1.0). Both ends use this file: the
// host to write, the controller to check (codec) and to unpack (spline store).
#ifndef FIRMWARE_PROTOCOL_COMPACT_SPLINE_H
#define FIRMWARE_PROTOCOL_COMPACT_SPLINE_H

#include <stdint.h>  // uint8_t, int32_t, uint32_t

#include "firmware/core/spline.h"        // Spline, ControlPoint
#include "firmware/protocol/messages.h"  // SplineCompactCmd
#include "firmware/protocol/varint.h"    // kMaxVarintBytes

namespace proto {

enum { kMaxCompactPointBytes = 3 * kMaxVarintBytes };  // x, y, weight

// Longest knot span a #K frame carries (its varint holds the span times 2).
static const uint32_t kMaxCompactSpan = 0x7FFFFFFFUL;

// Bytes written to out (at most kMaxCompactPointBytes): point p after prev in a spline that
// is rational or not (a polynomial spline's weights are not sent).
uint8_t put_compact_point(const core::ControlPoint& prev, const core::ControlPoint& p,
                          bool rational, uint8_t* out);
// Bytes written to out (at most kMaxVarintBytes): knot k, the spline's first knot when first,
// else after prev with the repeat flag (the next knot equals k and is not written). 0 bytes
// when k < prev or the span is over kMaxCompactSpan: the knot needs a #D frame.
uint8_t put_compact_knot(int32_t prev, int32_t k, bool first, bool repeat, uint8_t* out);

// kOk when m.data holds exactly m.control_n points then m.knot_n knots; kPayloadLength when
// it ends early, has bytes left, or repeats a knot past the last; kFieldRange for a number
// over 32 bits.
ErrorCode scan_compact(const SplineCompactCmd& m);

// Writes the frame's points and knots into s at m.control_index and m.knot_index, taking the
// previous values from s (the caller has checked the indices follow what is stored and fit
// the spline). Entries beyond the indices only: nothing stored before them changes.
// kFieldRange (what was written is then meaningless) for a weight in a polynomial spline,
// a weight outside 1..65535, a coordinate outside +-core::kMaxCoordinateUm or a knot
// beyond int32; kPayloadLength / kFieldRange as scan_compact for malformed data.
// s == 0: scan_compact. Both run varint_spline.h's one reader.
ErrorCode unpack_compact(const SplineCompactCmd& m, core::Spline* s);

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_COMPACT_SPLINE_H
