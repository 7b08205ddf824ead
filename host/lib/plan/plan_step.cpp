// A plan step's spline and text, kept out of line and shared by copies.
#include "host/lib/plan/plan_step.h"

#include <atomic>   // std::atomic
#include <utility>  // std::move

namespace host {

struct PlanStep::Extra {
  StepSpline spline;
  std::string text;
  mutable std::atomic<int> refs{1};
};

PlanStep::ExtraRef::ExtraRef(const ExtraRef& other) : p_(other.p_) {
  if (p_) p_->refs.fetch_add(1, std::memory_order_relaxed);
}

PlanStep::ExtraRef::~ExtraRef() {
  if (p_ && p_->refs.fetch_sub(1, std::memory_order_acq_rel) == 1) delete p_;
}

const StepSpline& PlanStep::spline() const {
  static const StepSpline kNone;
  return extra_.get() ? extra_.get()->spline : kNone;
}

void PlanStep::set_spline(StepSpline spline) {
  Extra* e = new Extra;
  e->spline = std::move(spline);
  if (extra_.get()) e->text = extra_.get()->text;
  extra_ = ExtraRef(e);
}

const std::string& PlanStep::text() const {
  static const std::string kNone;
  return extra_.get() ? extra_.get()->text : kNone;
}

void PlanStep::set_text(std::string text) {
  Extra* e = new Extra;
  e->text = std::move(text);
  if (extra_.get()) e->spline = extra_.get()->spline;
  extra_ = ExtraRef(e);
}

bool PlanStep::same_shape(const PlanStep& o) const {
  // dwell_ms shares its bytes with z_start_um: comparing it compares either.
  return kind == o.kind && spindle_on == o.spindle_on && z_um == o.z_um &&
         feed_um_per_s == o.feed_um_per_s && tool_offset_um == o.tool_offset_um &&
         dwell_ms == o.dwell_ms && extra_.get() == o.extra_.get();
}

}  // namespace host
