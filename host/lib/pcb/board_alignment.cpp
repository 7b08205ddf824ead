// Rigid transforms of a double-sided board's alignment (see board_alignment.h).
#include "host/lib/pcb/board_alignment.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>  // std::atan2, std::cos, std::sin

#include "host/lib/plan/job_plan.h"  // PlanError

namespace host::pcb {

namespace {

const double kPi = 3.14159265358979323846;

Point2 rotated(const Point2& p, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Point2(c * p.x() - s * p.y(), s * p.x() + c * p.y());
}

}  // namespace

Point2 RigidTransform::apply(const Point2& p) const {
  return rotated(p, rotation_rad) + shift_mm;
}

RigidTransform RigidTransform::inverse() const {
  RigidTransform t;
  t.rotation_rad = -rotation_rad;
  t.shift_mm = -rotated(shift_mm, -rotation_rad);
  return t;
}

RigidTransform placement_error(const Point2& pivot_mm, double dx_mm, double dy_mm,
                               double rotation_deg) {
  RigidTransform t;
  t.rotation_rad = rotation_deg * kPi / 180.0;
  t.shift_mm = pivot_mm - rotated(pivot_mm, t.rotation_rad) + Point2(dx_mm, dy_mm);
  return t;
}

RigidTransform measured_alignment(const Point2 expected_mm[2], const Point2 measured_mm[2]) {
  const Point2 e = expected_mm[1] - expected_mm[0], m = measured_mm[1] - measured_mm[0];
  if (std::fabs(m.norm() - e.norm()) > 0.2)
    throw PlanError(fmt::format(
        "the measured alignment holes are {:.3f} mm apart, the job's {:.3f} mm: not the job's "
        "holes 1 and 2 (measure hole 1 first)",
        m.norm(), e.norm()));
  RigidTransform t;
  t.rotation_rad = std::atan2(e.x() * m.y() - e.y() * m.x(), e.dot(m));
  if (std::fabs(t.rotation_rad) > 5 * kPi / 180)
    throw PlanError(fmt::format(
        "the measured alignment holes are turned {:.1f} degrees from the job's (more than 5): "
        "the holes swapped, or the blank on the pins the wrong way round",
        t.rotation_rad * 180 / kPi));
  // The middles of the two pairs coincide: the rounding of each measurement shared out.
  const Point2 me = (expected_mm[0] + expected_mm[1]) / 2,
               mm = (measured_mm[0] + measured_mm[1]) / 2;
  t.shift_mm = mm - rotated(me, t.rotation_rad);
  return t;
}

}  // namespace host::pcb
