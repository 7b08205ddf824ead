// Pieces shared by the two planners (job_plan.cpp for drawings, program_plan.cpp for
// G-code programs): unit conversion, the work-area check with its advice, and the steps
// that trace one curve.
#ifndef HOST_LIB_PLAN_PLAN_STEPS_H
#define HOST_LIB_PLAN_PLAN_STEPS_H

#include <stdint.h>  // int32_t

#include <string>  // std::string

#include "host/lib/plan/job_plan.h"

namespace host::plan_detail {

int32_t to_um(double mm);
core::PointUm to_um(const Point2& p);

// True when the curve is exactly a chain of straight segments through its control points.
bool is_polyline(const BSpline& s);

// Length of a polyline approximation of the curve.
double curve_length(const BSpline& s);

// "curve N (entity)" with N the drawing's curve number (as `engraver info` shows it).
std::string describe(const PlannedCurve& c);

// Refuses a job whose tool centre (extents_mm, machine frame, grown by the tool radius)
// leaves the work area: says how big the job is, how big the work area is and what would
// fit (--scale, --margin, --work up to the controller's travel). `culprit` names the first
// curve or hole that leaves it and where; "" when not known.
void check_job_fits(const Extents& extents_mm, double radius_mm, const PlanOptions& o,
                    const std::string& culprit);

// The first point of curve c (machine frame) outside the work area, as "curve N (...)
// reaches (x, y) mm"; "" when it stays inside.
std::string first_exit(const PlannedCurve& c, double radius_mm, const PlanOptions& o);

// Refuses options the controller cannot run: a work area beyond its travel, bad feeds.
void check_options(const PlanOptions& o);

// Where the tool centre is at the start (or end) of curve s when the controller offsets it
// by offset_um (> 0 left of travel) along the normal: the pen goes down there, not on the
// drawn line.
Point2 offset_point(const BSpline& s, bool at_start, int32_t offset_um);

// Appends the steps that trace c (already at its start with the pen down; spline is
// c.spline(), made once by the caller): straight feeds for a polyline without offset,
// firmware splines otherwise.
void append_curve_steps(const PlannedCurve& c, const BSpline& spline, int index, int32_t offset_um,
                        const PlanOptions& o, JobPlan* plan);

// Appends a curve's spline steps (curve `index`): its firmware pieces, each ending where it
// ends, the last exactly at the curve's end. Throws ConversionError (nothing appended) when
// the curve has no firmware form; the caller names the curve.
void append_spline_steps(const BSpline& spline, int index, int32_t feed_um_per_s, int32_t offset_um,
                         JobPlan* plan);

}  // namespace host::plan_detail

#endif  // HOST_LIB_PLAN_PLAN_STEPS_H
