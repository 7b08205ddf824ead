// The plan's steps as 16-byte entries over a few shared shapes.
#include "host/lib/plan/step_list.h"

#include <stdexcept>  // std::out_of_range

namespace host {

const PlanStep StepList::operator[](size_t i) const {
  const Entry& e = entries_.at(i);
  PlanStep s = shapes_[e.shape];
  s.to = e.to;
  s.curve = e.curve;
  return s;
}

StepList::Entry StepList::entry_of(const PlanStep& s) {
  Entry e;
  e.curve = s.curve;
  e.to = s.to;
  for (int k = 0; k < recent_count_; ++k) {
    if (shapes_[recent_[k]].same_shape(s)) {
      e.shape = recent_[k];
      return e;
    }
  }
  PlanStep shape = s;
  shape.to = core::PointUm{0, 0};
  shape.curve = -1;
  e.shape = static_cast<uint32_t>(shapes_.size());
  shapes_.push_back(shape);
  // A step with its own spline or text is not met again: keep the recent ones for the rest.
  if (s.spline().empty() && s.text().empty()) {
    recent_[recent_next_] = e.shape;
    recent_next_ = (recent_next_ + 1) % kRecent;
    if (recent_count_ < kRecent) ++recent_count_;
  }
  return e;
}

void StepList::push_back(const PlanStep& s) {
  entries_.push_back(entry_of(s));
}

void StepList::set(size_t i, const PlanStep& s) {
  if (i >= entries_.size()) throw std::out_of_range("StepList::set");
  entries_[i] = entry_of(s);
}

void StepList::insert(const_iterator at, const PlanStep& s) {
  const Entry e = entry_of(s);
  entries_.insert(entries_.begin() + static_cast<std::ptrdiff_t>(at.index()), e);
}

void StepList::erase(const_iterator at) {
  entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(at.index()));
}

void StepList::assign(const PlanStep* first, const PlanStep* last) {
  *this = StepList();
  entries_.reserve(static_cast<size_t>(last - first));
  for (; first != last; ++first) push_back(*first);
}

size_t StepList::heap_bytes() const {
  return entries_.capacity() * sizeof(Entry) + shapes_.capacity() * sizeof(PlanStep);
}

}  // namespace host
