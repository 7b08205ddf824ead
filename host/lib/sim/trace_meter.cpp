// Streaming measurement and thinning of the simulated tool path (see trace_meter.h).
#include "host/lib/sim/trace_meter.h"

#include <algorithm>  // std::max
#include <cmath>      // std::hypot, std::abs

#include "host/lib/sim/sim_job.h"  // pen_threshold_mm

namespace host::sim {

namespace {

// The planned curves as polylines (lines exactly, curves within 0.2 um), added one by one:
// a copy of a million lines' polylines held 70 MB while the job started.
std::unique_ptr<NearestSegment> reference_of(const JobPlan& plan) {
  auto index = std::make_unique<NearestSegment>();
  size_t segments = 0;  // the lines' exactly; a sampled curve's grow the list
  for (const PlannedCurve& c : plan.curves) {
    const BSpline s = c.spline();
    if (s.degree == 1 && s.weights.empty() && !s.control.empty()) segments += s.control.size() - 1;
  }
  index->reserve(segments);
  for (const PlannedCurve& c : plan.curves) {
    const BSpline s = c.spline();
    if (s.degree == 1 && s.weights.empty())
      index->add(s.control);
    else
      index->add(sample(s, 0.0002));
  }
  index->index();
  return index;
}

}  // namespace

TraceMeter::TraceMeter(const JobPlan& plan, double keep_step_mm, size_t max_kept)
    : pen_mm_(pen_threshold_mm(plan)), step_mm_(keep_step_mm), max_kept_(max_kept) {
  if (!plan.curves.empty()) reference_ = reference_of(plan);
}

TraceMeter::~TraceMeter() = default;

void TraceMeter::take(const ToolSample& s, bool down) {
  path_.add(Point2(s.x_mm, s.y_mm), down);
  if (max_kept_ > 0 && path_.size() >= max_kept_) coarsen();
}

void TraceMeter::coarsen() {
  // Beyond a metre every position but the ends and the pen changes is gone: stop there.
  while (path_.size() > max_kept_ / 2 && step_mm_ < 1000.0) {
    step_mm_ *= 2;
    path_.thin(step_mm_);
  }
  // Pen changes alone may fill the budget: let it grow with them, not re-thin every sample.
  max_kept_ = std::max(max_kept_, 2 * path_.size());
}

void TraceMeter::add(const ToolSample& b) {
  ++samples_;
  if (b.z_mm >= pen_mm_) lifted_ = true;
  const bool down = lifted_ && b.z_mm < pen_mm_;
  if (have_prev_) {
    const ToolSample& a = prev_;
    if (first_move_ms_ == 0) first_move_ms_ = a.t_ms;
    last_move_ms_ = b.t_ms;
    const double d = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
    (down ? cut_mm_ : rapid_mm_) += d;
    if (down && prev_down_ && d > 0) cut_s_ += (b.t_ms - a.t_ms) / 1000.0;
    // Only the largest error is reported: a sample whose distance to the previous nearest
    // segment is within it cannot raise it, and skips the search (most samples do).
    const Point2 at(b.x_mm, b.y_mm);
    if (down && reference_ &&
        reference_->upper_bound(at, max_error_um_ / 1000.0) * 1000.0 > max_error_um_) {
      const double e = reference_->distance(at) * 1000.0;
      if (e > max_error_um_) {
        max_error_um_ = e;
        worst_ = b;
      }
    }
  }
  if (step_mm_ <= 0) {
    kept_.push_back(b);
  } else {
    // The plot path takes the first sample, the first of each pen state, and every sample a
    // step away from the last one taken (a piece ends where the next begins: pen_path.h).
    const size_t n = path_.size();
    bool take_it = n == 0 || down != path_.pen_down(n - 1);
    if (!take_it) {
      const Point2 k = path_.point(n - 1);
      take_it = std::abs(b.x_mm - k.x()) >= step_mm_ || std::abs(b.y_mm - k.y()) >= step_mm_;
    }
    if (take_it) take(b, down);
    prev_taken_ = take_it;
  }
  prev_ = b;
  prev_down_ = down;
  have_prev_ = true;
}

void TraceMeter::finish() {
  if (step_mm_ > 0 && have_prev_ && !prev_taken_) take(prev_, prev_down_);
  prev_taken_ = true;
}

}  // namespace host::sim
