// The job plan: a drawing turned into the ordered machine actions the encoder sends —
// pen (Z) up/down, rapids, splines in firmware form, straight feeds — in the machine frame
// (micrometres from the zero corner), checked against the work area.
#ifndef HOST_LIB_PLAN_JOB_PLAN_H
#define HOST_LIB_PLAN_JOB_PLAN_H

#include <stdint.h>  // int32_t

#include <functional>  // std::function
#include <memory>      // std::shared_ptr
#include <stdexcept>   // std::runtime_error
#include <string>      // std::string
#include <utility>     // std::swap
#include <vector>      // std::vector

#include "firmware/config/machine_config.h"
#include "firmware/core/spline.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/drawing/held_spline.h"  // LineKnots
#include "host/lib/plan/job_defaults.h"    // every default below
#include "host/lib/plan/plan_step.h"
#include "host/lib/plan/step_list.h"

namespace host {

// Which side of each curve the tool centre runs on, seen along the curve's direction as
// drawn in the file (kept when the planner reverses a curve: the offset sign flips).
enum class ToolSide { kCentre, kLeft, kRight };

// How holes of a drilling cycle (G81/G82/G83) are sent: as one drill step each (the
// controller's drill command), or as Z moves (plunge, dwell, retract) that any controller
// version runs. Holes with a dwell at the bottom (G82) or pecks (G83) always use Z moves.
enum class DrillMode { kDrillCommand, kZMoves };

struct PlanOptions {
  double scale = defaults::kScale;  // applied to the drawing (mm) before anything else
  // The drawing's lower-left corner goes to (margin, margin)
  double margin_mm = defaults::kMarginMm;
  // Instead: machine = drawing * scale + offset_mm, the same for every file of one board
  // (the back, drill and outline programs of a PCB then line up).
  bool fixed_offset = false;
  Point2 offset_mm{0, 0};
  double work_width_mm = defaults::work_width_mm();  // work area: x in [0, width], y in [0, height]
  double work_height_mm = defaults::work_height_mm();
  bool reorder = true;  // greedy nearest-neighbour ordering, with reversal
  // Ends closer than this: no pen lift between curves
  double chain_tolerance_mm = defaults::kChainToleranceMm;
  ToolSide tool_side = ToolSide::kCentre;
  double tool_radius_mm = 0.0;                       // used when tool_side != kCentre
  double z_up_mm = defaults::kZUpMm;                 // pen-up (travel) height above the work zero
  double z_down_mm = defaults::kZDownMm;             // pen-down (cutting) height
  double feed_mm_per_s = defaults::feed_mm_per_s();  // cutting feed for splines and straight feeds
  double plunge_mm_per_s = defaults::kPlungeMmPerS;  // Z feed for pen down
  bool lines_as_feeds = true;  // a single straight segment becomes a kFeed, not a spline
  // The controller's travel: the work area may not be larger, Z moves stay within +-Z.
  double travel_width_mm = defaults::travel_mm(config::kAxisX);
  double travel_height_mm = defaults::travel_mm(config::kAxisY);
  double travel_z_mm = defaults::travel_mm(config::kAxisZ);
  // Programs with an order (G-code, Drawing::program non-empty):
  bool file_depths = true;  // cut at the program's own Z where it gives one (else z_down_mm)
  DrillMode drill_mode = DrillMode::kDrillCommand;
  // The file's plunge feed is capped here (Z axis)
  double drill_feed_max_mm_per_s = defaults::kDrillFeedMaxMmPerS;
  // Highest the tool goes for a pause (the program's tool-change height is capped here):
  // Z is zeroed at the work, about mid-travel, so half the Z travel is above it.
  double pause_z_max_mm = defaults::travel_mm(config::kAxisZ) / 2;
  // Runs of short G1 moves are sent as cubic B-splines within this distance of the
  // program's path (0: every move as a straight feed).
  double fit_tolerance_mm = defaults::kFitToleranceMm;
  // Called now and then in each stage of planning a drawing ("curves measured", "curves
  // moved to the margin", "curve ends indexed", "curves ordered", "curves checked against
  // the work area", "curves made into steps"), for a progress bar.
  WorkProgress progress;
};

// A planned curve: the drawing curve in the machine frame (mm), in the direction drawn.
// A straight line as the DXF import and the reversal make it (degree 1, two points, knots
// 0 0 1 1 or their reversal) keeps its two ends inline: a million-line drawing held a
// BSpline with two heap vectors a line (~140 bytes more). Any other curve is kept whole,
// shared by copies of the plan (never changed once set).
struct PlannedCurve {
  // The curve, made from the two ends for a straight line: take it once per use, not per
  // point.
  BSpline spline() const;
  void set_spline(BSpline spline);
  // Kept as its two ends (no curve on the heap).
  bool inline_line() const { return line_knots_ != LineKnots::kNotALine; }

  int drawing_index = 0;  // index in Drawing::curves
  bool reversed = false;  // traced end to start
  bool chained = false;   // starts where the previous one ended: no pen lift before it

 private:
  // Here, in the padding after the flags (88 bytes a curve, not 96 with a HeldSpline).
  LineKnots line_knots_ = LineKnots::kNotALine;

 public:
  std::string source;  // entity it came from (for messages)

 private:
  // x0 y0 x1 y1: doubles, not two Point2s, whose 16-byte alignment pads the struct to 96.
  double ends_[4] = {0, 0, 0, 0};
  std::shared_ptr<const BSpline> curve_;  // kNotALine: the curve
};

struct JobPlan {
  StepList steps;                    // starts and ends with the pen up at the zero (0, 0)
  std::vector<PlannedCurve> curves;  // in the order drawn
  Point2 offset_mm{0, 0};            // machine = drawing * scale + offset_mm
  Extents extents_mm;                // of the curves in the machine frame (tool centre)
  double cut_length_mm = 0.0;        // pen-down path length (approximate, from sampling)
  double rapid_length_mm = 0.0;      // pen-up X/Y travel
  int pen_lifts = 0;                 // kPenUp steps between curves
  int holes = 0;                     // drilled holes (kDrill steps or their Z moves)
};

// A job that must not be sent (out of the work area, a curve the firmware cannot hold,
// an empty drawing). what() names the curve and the coordinate or problem.
class PlanError : public std::runtime_error {
 public:
  explicit PlanError(const std::string& msg) : std::runtime_error(msg) {}
};

// The one check of a work area against the controller's travel, for drawings and boards:
// throws PlanError ("--work W H mm is beyond the controller's travel ...") when it is larger
// or not positive.
void check_work_area(double work_width_mm, double work_height_mm, double travel_width_mm,
                     double travel_height_mm);

// Plans the whole job; every check is done before anything is returned. A drawing without
// a program (DXF) is reordered for short rapids; a program (G-code) keeps the file's order
// and its pauses, dwells, spindle switching and drilling (see program_plan.cpp).
JobPlan plan_job(const Drawing& drawing, const PlanOptions& options);
// The same, taking the drawing's curves (left empty) so that a large drawing is not held
// twice while it is planned. A program (G-code) is planned as above and kept.
JobPlan plan_job(Drawing&& drawing, const PlanOptions& options);

}  // namespace host

#endif  // HOST_LIB_PLAN_JOB_PLAN_H
