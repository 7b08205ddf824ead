// Point generator engine: walks a spline span by span and emits points (optionally offset
// by the tool radius) with chord-tolerance-adaptive parameter steps.
#ifndef FIRMWARE_CORE_CURVE_WALKER_H
#define FIRMWARE_CORE_CURVE_WALKER_H

#include <stdint.h>  // uint16_t, int32_t

#include "firmware/core/corner_arc.h"      // CornerArc, UnitQ15
#include "firmware/core/geometry_error.h"  // GeometryError
#include "firmware/core/span_evaluator.h"  // SpanEvaluator
#include "firmware/core/spline.h"          // Spline, PointUm

namespace core {

// The one step mode (a uniform mode, N points per span, had no user: no wire message
// selects it; gone with the flash budget). Any other value is refused by begin().
enum class StepMode : uint8_t { kAdaptive = 1 };

// Default chord tolerance of the adaptive mode, micrometres.
static const uint16_t kDefaultChordToleranceUm = 5;
// Largest tool offset accepted, micrometres (|tool_offset_um|).
static const int32_t kMaxToolOffsetUm = 100000L;

struct StepSettings {
  StepMode mode;
  uint16_t chord_tolerance_um;  // max chord error (default 5), 1..10000, of the steps and
                                // of corner arcs
  int32_t tool_offset_um;       // > 0 left of travel, < 0 right, 0 none
};

// Settings with the defaults: adaptive, 5 um, no offset.
StepSettings default_step_settings();

// Usage: begin(); then next() until it returns false; then error() says whether the curve
// finished (kOk) or stopped (e.g. kOffsetTooLarge). Each next() call does bounded work:
// one point (adaptive: at most 24 trials of 1 evaluation on polynomial spans without
// offset (4 if a sample falls beyond the chord's end), 8 for rational spans or with an
// offset; a corner arc: one arc point), or at a knot the next span's setup plus the joint
// point. Adaptive steps keep the real chord error <= tolerance (docs/core-math.md).
//
// Tool offset: each point moves by |R| along the unit normal of dP/du (left of travel for
// R > 0). Corners (a tangent discontinuity at a knot, e.g. multiplicity = degree):
//   - turning away from the offset side (convex for the tool): the tool goes round the
//     corner on an arc of radius |R| about the corner point, points spaced so that the
//     arc's chord error stays within chord_tolerance_um; an exact reversal goes round the end on a
//     half circle;
//   - turning toward the offset side (concave): one point at the intersection of the two
//     offset tangent lines (the miter point) replaces the two offset ends; if the turn is
//     sharper than about 150 degrees the miter would run away and the curve walker stops with
//     kOffsetTooLarge.
// Offset larger than the radius of curvature on the offset side: detected when the
// offset path runs backward relative to the curve between two consecutive points; the
// walker stops with kOffsetTooLarge (points already emitted stay valid).
// A trial step's chord, prepared for distances (curve_walker.cpp).
struct Chord;

class CurveWalker {
 public:
  CurveWalker();
  // Validates spline and settings; keeps the pointer (the spline must outlive stepping).
  GeometryError begin(const Spline* spline, const StepSettings& settings);
  // Next point; false when finished or stopped. First point is the curve start (offset),
  // last is the curve end exactly (offset).
  bool next(PointUm* out);
  bool done() const { return phase_ == kDone; }
  // kOk while running or after a normal finish; the reason when stepping stopped early.
  GeometryError error() const { return error_; }
  // Span index and parameter (uq16, 65536 = span end) of the last curve point used
  // (tests measure the real chord error between consecutive points with it).
  uint16_t span() const { return span_; }
  uint32_t t_q16() const { return t_q16_; }

 private:
  enum Phase { kIdle, kStart, kInSpan, kDone };
  bool enter_span(uint16_t span);
  bool step_in_span(PointUm* out);
  bool joint(PointUm* out);
  bool corner(const PointQ6& at, const Direction& in_dir, const Direction& out_dir, PointUm* out);
  bool arc_point(PointUm* out);
  uint32_t adaptive_next();
  uint32_t trial_error(uint32_t step, uint8_t parts_log2);
  uint32_t sampled_error(const Chord& chord, uint32_t step, uint8_t parts_log2);
  PointQ6 path_point(uint32_t t_q16, Direction* dir);
  PointQ6 offset_point(const PointQ6& base, const UnitQ15& normal) const;
  Direction usable_direction(uint32_t t_q16);
  bool emit_checked(const PointQ6& base, const PointQ6& p, PointUm* out);
  bool emit_plain(const PointQ6& p, PointUm* out);
  bool fail(GeometryError e);

  const Spline* spline_;
  StepSettings settings_;
  SpanEvaluator eval_;
  Phase phase_;
  GeometryError error_;
  uint16_t span_;
  uint32_t t_q16_;      // current parameter in the span, 0..65536
  uint32_t h_q16_;      // adaptive: step that worked last
  uint32_t accept_q6_;  // adaptive: a trial step is accepted at chord error <= 0.9 tol
  uint32_t target_q6_;  // adaptive: the next step aims at 0.7 tol
  PointQ6 step_point_;  // adaptive: path point at the accepted step (no second evaluation)
  PointQ6 step_base_;   // adaptive: the curve point it was offset from
  PointQ6 path_base_;   // curve point of the last path_point() call
  Direction last_dir_;  // last non-zero direction (fallback at cusps)
  PointQ6 last_out_;    // last emitted point, before rounding
  PointQ6 last_base_;   // curve point it was offset from
  // Pending second point of a discontinuous joint.
  bool pending_;
  PointQ6 pending_point_;
  CornerArc arc_;  // a convex corner's arc in progress
};

}  // namespace core

#endif  // FIRMWARE_CORE_CURVE_WALKER_H
