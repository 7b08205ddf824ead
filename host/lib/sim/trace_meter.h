// Measures a simulated tool path as it is produced, sample by sample, so a job of any
// length needs no stored trace: path lengths (pen down / up), cutting and motion time, and
// the contour error of every pen-down sample against the planned curves. Keeps every sample,
// or a plot's path (PenPath) thinned to a given step, always keeping pen changes, within a
// budget of positions: a job of any length keeps a bounded plot path.
#ifndef HOST_LIB_SIM_TRACE_METER_H
#define HOST_LIB_SIM_TRACE_METER_H

#include <cstddef>  // size_t
#include <memory>   // std::unique_ptr
#include <vector>   // std::vector

#include "host/lib/plan/job_plan.h"
#include "host/lib/plan/pen_path.h"
#include "host/lib/sim/contour_error.h"
#include "host/lib/sim/sim_machine.h"

namespace host::sim {

class TraceMeter {
 public:
  // keep_step_mm 0 keeps every sample (kept()); otherwise the plot path (path()) takes a
  // sample when it lies this far (in X or Y: the plot's plane) from the previous one taken,
  // or the pen went up or down. With a step, max_kept (0: no limit) bounds the path: when
  // it reaches it, the step is doubled and the path thinned again, until it holds at most
  // half of that. Pen changes are never dropped, so their count is the floor.
  TraceMeter(const JobPlan& plan, double keep_step_mm, size_t max_kept = 0);
  ~TraceMeter();
  void add(const ToolSample& sample);
  // Keeps the last sample (call once, after the job).
  void finish();

  double cut_mm() const { return cut_mm_; }
  double rapid_mm() const { return rapid_mm_; }
  double cut_s() const { return cut_s_; }
  double motion_s() const { return (last_move_ms_ - first_move_ms_) / 1000.0; }
  double max_contour_error_um() const { return max_error_um_; }
  // The pen-down sample with the largest contour error (where to look first).
  const ToolSample& worst_sample() const { return worst_; }
  size_t samples() const { return samples_; }
  // Segment distances the contour error has cost so far (for tests).
  size_t segments_examined() const { return reference_ ? reference_->segments_examined() : 0; }
  // The step the kept path has now (keep_step_mm, doubled each time it hit max_kept).
  double keep_step_mm() const { return step_mm_; }
  // Every sample (keep_step_mm 0); take it when done.
  std::vector<ToolSample>& kept() { return kept_; }
  // The plot path (keep_step_mm > 0); take it when done.
  PenPath& path() { return path_; }

 private:
  void take(const ToolSample& s, bool down);  // onto the plot path
  void coarsen();

  double pen_mm_;
  double step_mm_;
  size_t max_kept_;
  std::unique_ptr<NearestSegment> reference_;
  bool have_prev_ = false, prev_down_ = false, lifted_ = false;
  ToolSample prev_{};
  bool prev_taken_ = false;
  uint64_t first_move_ms_ = 0, last_move_ms_ = 0;
  double cut_mm_ = 0, rapid_mm_ = 0, cut_s_ = 0, max_error_um_ = 0;
  ToolSample worst_{};
  size_t samples_ = 0;
  std::vector<ToolSample> kept_;
  PenPath path_;
};

}  // namespace host::sim

#endif  // HOST_LIB_SIM_TRACE_METER_H
