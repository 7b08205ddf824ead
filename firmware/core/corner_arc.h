// The tool's arc round a convex corner of an offset path: the unit normals it steps
// through, and the unit left normal of a curve direction they are made of.
#ifndef FIRMWARE_CORE_CORNER_ARC_H
#define FIRMWARE_CORE_CORNER_ARC_H

#include <stdint.h>  // int32_t, uint16_t, uint8_t

#include "firmware/core/span_evaluator.h"  // Direction, PointQ6

namespace core {

// A unit vector in Q15 (components widened to 32 bits for the arithmetic; |c| <= 2^15).
struct UnitQ15 {
  int32_t x_q15;
  int32_t y_q15;
};

// v / 4 truncated toward zero (as C's v / 4) for |v| <= 2^16.
int16_t quarter_toward_zero(int32_t v);

// Unit left normal (-dy, dx) / |d| in Q15 ((0, 32767) for a zero d): one root and two
// 32/16 divisions.
UnitQ15 left_unit_normal(const Direction& d);

// The normals of the arc round a convex corner of an offset path, from n1 (the incoming
// span's) to n2 (the outgoing one's), split at the bisector when the turn is over 90
// degrees; each point the normalised linear blend of its half's two ends, the last of a
// half its end exactly, as many per half as keep the arc's chord error within tol_um.
class CornerArc {
 public:
  // left_offset: the tool runs left of travel (R > 0); r_abs_um: |R|.
  void begin(const PointQ6& center, const UnitQ15& n1, const UnitQ15& n2, bool over_90,
             bool left_offset, uint32_t r_abs_um, uint16_t tol_um);
  bool active() const { return halves_left_ > 0; }
  void stop() { halves_left_ = 0; }
  const PointQ6& center() const { return center_; }
  // The next normal; the arc ends after the last half's last one.
  UnitQ15 next_normal();

 private:
  PointQ6 center_;
  UnitQ15 a_;
  UnitQ15 b_;
  UnitQ15 c_;
  uint16_t steps_;  // points per half
  uint16_t index_;  // next point index within the half, 1..steps_
  uint8_t halves_left_;
};

}  // namespace core

#endif  // FIRMWARE_CORE_CORNER_ARC_H
