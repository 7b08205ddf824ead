// The #Q contour data (docs/protocol.md): a rational quadratic spline made of straight lines
// and circular arcs joined at corners, as PCB isolation and most drawings are. Each element
// is its end point (a difference from its start) and, for an arc, the signed height of its
// middle control point above the chord; the middle point, its weight and every knot follow
// from those, so a line costs two numbers and an arc three instead of two points, weights
// and knots.
//   first point (only in the frame at control index 0): varint(zigzag(x)), varint(zigzag(y))
//   element:  varint(zigzag(dx) * 2 + arc), varint(zigzag(dy)), then varint(zigzag(h)) if arc
// Element i adds control points 2i+1 (middle) and 2i+2 (its end, weight 1.0). Knots: 0 0 0,
// then each corner's index twice, the last three times (spans of 1). Both ends use this file:
// the host to write and to know what the controller will hold, the controller to check
// (codec) and to unpack (spline store).
#ifndef FIRMWARE_PROTOCOL_CONTOUR_SPLINE_H
#define FIRMWARE_PROTOCOL_CONTOUR_SPLINE_H

#include <stdint.h>  // uint8_t, int32_t

#include "firmware/core/spline.h"        // Spline, ControlPoint
#include "firmware/protocol/messages.h"  // SplineContourCmd
#include "firmware/protocol/varint.h"    // kMaxVarintBytes

namespace proto {

enum {
  // Largest |dx|, |dy| of an arc element: the squares of chord and legs stay in 32 bits.
  kMaxContourArcAxisUm = 16383,
  kMaxContourElementBytes = 3 * kMaxVarintBytes
};

struct ContourElement {
  int32_t dx_um;  // end point minus start point
  int32_t dy_um;
  bool arc;
  int32_t height_um;  // arc: middle control point's distance from the chord, > 0 to the left
};

// The element's middle control point after start p0: a line's halves the chord (rounded
// toward p0); an arc's stands height_um off the chord's middle, square to it, with weight
// cos(half the arc's angle) = chord / (2 leg) in Q14, rounded. kFieldRange for an arc with
// |dx| or |dy| over kMaxContourArcAxisUm, a zero chord or |height| above the chord.
ErrorCode contour_middle(const core::ControlPoint& p0, const ContourElement& e,
                         core::ControlPoint* middle);

// Bytes written to out: the spline's first point (at most 2 * kMaxVarintBytes), or one
// element (at most kMaxContourElementBytes).
uint8_t put_contour_start(int32_t x_um, int32_t y_um, uint8_t* out);
uint8_t put_contour_element(const ContourElement& e, uint8_t* out);

// kOk when m.data holds exactly what m's indices say (the first point at index 0, then
// whole elements); kFieldRange for a count that is not whole elements or a number over 32
// bits; kPayloadLength when the data ends early or has bytes left.
ErrorCode scan_contour(const SplineContourCmd& m);

// Writes the frame's points into s from m.control_index, after s's point control_index - 1
// (the caller has checked the indices follow what is stored and fit the spline); when
// last, also every knot. Entries beyond the stored ones only. kFieldRange for a point
// outside +-core::kMaxCoordinateUm or an element contour_middle refuses; kPayloadLength /
// kFieldRange as scan_contour for malformed data.
// s == 0: scan_contour. Both run varint_spline.h's one reader.
ErrorCode unpack_contour(const SplineContourCmd& m, core::Spline* s);

// True if s (degree, rational, counts) is the shape #Q frames fill: degree 2, rational, an
// odd number of control points, knot count = control count + 3.
bool is_contour_shape(const core::Spline& s);

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_CONTOUR_SPLINE_H
