// Double-sided boards: the rigid transforms of the flip's alignment. A flipped blank sits on
// the pins a little turned and shifted; the operator measures two alignment holes in the
// machine frame and the job is turned and shifted to them before it is encoded (B-splines
// are affine invariant: the transformed control points give the transformed curve).
#ifndef HOST_LIB_PCB_BOARD_ALIGNMENT_H
#define HOST_LIB_PCB_BOARD_ALIGNMENT_H

#include "host/lib/drawing/bspline.h"  // Point2

namespace host::pcb {

// p -> R(rotation) p + shift (machine frame, mm).
struct RigidTransform {
  double rotation_rad = 0;
  Point2 shift_mm{0, 0};
  Point2 apply(const Point2& p) const;
  RigidTransform inverse() const;
  bool identity() const { return rotation_rad == 0 && shift_mm.x() == 0 && shift_mm.y() == 0; }
};

// A blank placed turned by rotation_deg about `pivot_mm` and shifted by (dx, dy) mm.
RigidTransform placement_error(const Point2& pivot_mm, double dx_mm, double dy_mm,
                               double rotation_deg);

// The transform taking the job's two alignment holes (where they should be) onto where the
// operator measured them. Throws PlanError when the measured holes are not 0.2 mm as far
// apart as the job's, or the turn is over 5 degrees (the wrong holes, or a blank put on the
// pins the wrong way round).
RigidTransform measured_alignment(const Point2 expected_mm[2], const Point2 measured_mm[2]);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_BOARD_ALIGNMENT_H
