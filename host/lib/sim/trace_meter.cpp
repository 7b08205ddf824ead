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

void TraceMeter::keep(const ToolSample& s, bool down) {
  kept_.push_back(s);
  kept_down_ = down;
  if (max_kept_ > 0 && step_mm_ > 0 && kept_.size() >= max_kept_) coarsen();
}

void TraceMeter::coarsen() {
  // Pen state of each kept sample, found as add() found it (pen changes are all kept).
  std::vector<bool> down(kept_.size());
  bool lifted = false;
  for (size_t i = 0; i < kept_.size(); ++i) {
    if (kept_[i].z_mm >= pen_mm_) lifted = true;
    down[i] = lifted && kept_[i].z_mm < pen_mm_;
  }
  // Beyond a metre every sample but the ends and the pen changes is gone: stop there.
  while (kept_.size() > max_kept_ / 2 && step_mm_ < 1000.0) {
    step_mm_ *= 2;
    size_t out = 0;
    const size_t n = kept_.size();
    for (size_t i = 0; i < n; ++i) {
      // Keep the ends (the last is prev_ when prev_kept_), both sides of every pen change,
      // and a sample a step away from the last kept one.
      bool keep_it = i == 0 || i + 1 == n || down[i] != down[i - 1] || down[i] != down[i + 1];
      if (!keep_it) {
        const ToolSample& k = kept_[out - 1];
        keep_it = std::abs(kept_[i].x_mm - k.x_mm) >= step_mm_ ||
                  std::abs(kept_[i].y_mm - k.y_mm) >= step_mm_;
      }
      if (keep_it) {
        kept_[out] = kept_[i];
        down[out] = down[i];
        ++out;
      }
    }
    kept_.resize(out);
    down.resize(out);
  }
  // Pen changes alone may fill the budget: let it grow with them, not re-thin every sample.
  max_kept_ = std::max(max_kept_, 2 * kept_.size());
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
  // Thinning: keep the first sample, both sides of every pen change, and every sample a step
  // away from the previous kept one.
  bool keep_it = kept_.empty() || step_mm_ <= 0;
  if (!keep_it && down != kept_down_) {
    if (!prev_kept_ && have_prev_) keep(prev_, prev_down_);
    keep_it = true;
  }
  if (!keep_it) {
    const ToolSample& k = kept_.back();
    keep_it = std::abs(b.x_mm - k.x_mm) >= step_mm_ || std::abs(b.y_mm - k.y_mm) >= step_mm_;
  }
  if (keep_it) keep(b, down);
  prev_kept_ = keep_it;
  prev_ = b;
  prev_down_ = down;
  have_prev_ = true;
}

void TraceMeter::finish() {
  if (have_prev_ && !prev_kept_) keep(prev_, prev_down_);
  prev_kept_ = true;
}

}  // namespace host::sim
