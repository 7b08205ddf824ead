// The plan's steps, held compactly. A million-line job has four million steps (lift,
// travel, plunge, feed per line) that differ from one another only in their target and
// curve: each step is kept as 16 bytes (target, curve, and which "shape" it has), and each
// distinct rest of a step (kind, heights, feeds, offset, spline, text) once.
#ifndef HOST_LIB_PLAN_STEP_LIST_H
#define HOST_LIB_PLAN_STEP_LIST_H

#include <stdint.h>  // uint32_t, int32_t

#include <cstddef>           // size_t, ptrdiff_t
#include <initializer_list>  // std::initializer_list
#include <iterator>          // std::input_iterator_tag
#include <vector>            // std::vector

#include "host/lib/plan/plan_step.h"

namespace host {

class StepList {
 public:
  // Steps are handed out by value (made from their shape): read them, change a copy and
  // put it back with set().
  class const_iterator {
   public:
    typedef std::input_iterator_tag iterator_category;
    typedef PlanStep value_type;
    typedef std::ptrdiff_t difference_type;
    typedef const PlanStep* pointer;
    typedef const PlanStep reference;

    const_iterator() = default;
    const_iterator(const StepList* list, size_t i) : list_(list), i_(i) {}
    const PlanStep operator*() const { return (*list_)[i_]; }
    const_iterator& operator++() {
      ++i_;
      return *this;
    }
    const_iterator operator++(int) {
      const_iterator before = *this;
      ++i_;
      return before;
    }
    bool operator==(const const_iterator& o) const { return i_ == o.i_; }
    bool operator!=(const const_iterator& o) const { return i_ != o.i_; }
    size_t index() const { return i_; }

   private:
    const StepList* list_ = nullptr;
    size_t i_ = 0;
  };

  StepList() = default;
  StepList(std::initializer_list<PlanStep> steps) { assign(steps.begin(), steps.end()); }
  StepList& operator=(std::initializer_list<PlanStep> steps) {
    assign(steps.begin(), steps.end());
    return *this;
  }
  StepList& operator=(const std::vector<PlanStep>& steps) {
    assign(steps.data(), steps.data() + steps.size());
    return *this;
  }

  size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  const PlanStep operator[](size_t i) const;
  const PlanStep front() const { return (*this)[0]; }
  const PlanStep back() const { return (*this)[size() - 1]; }
  const_iterator begin() const { return const_iterator(this, 0); }
  const_iterator end() const { return const_iterator(this, size()); }

  void reserve(size_t n) { entries_.reserve(n); }
  size_t capacity() const { return entries_.capacity(); }
  void push_back(const PlanStep& s);
  void set(size_t i, const PlanStep& s);  // replaces step i
  // Changes step i: change(PlanStep&) is given a copy, which then replaces it.
  template <class Change>
  void edit(size_t i, Change change) {
    PlanStep s = (*this)[i];
    change(s);
    set(i, s);
  }
  void insert(const_iterator at, const PlanStep& s);
  void erase(const_iterator at);

  // Heap bytes held (the entries' reservation and the shapes), for the memory tests.
  size_t heap_bytes() const;

 private:
  struct Entry {  // 16 bytes: a million-line job holds four million
    uint32_t shape;
    int32_t curve;
    core::PointUm to;
  };
  Entry entry_of(const PlanStep& s);
  void assign(const PlanStep* first, const PlanStep* last);

  std::vector<PlanStep> shapes_;  // each with `to` and `curve` cleared
  std::vector<Entry> entries_;
  // Shapes used last, looked through before a new one is made: a job switches between a
  // handful (lift, travel, plunge, feed) and would otherwise add one per step.
  static const int kRecent = 8;
  uint32_t recent_[kRecent] = {0, 0, 0, 0, 0, 0, 0, 0};
  int recent_count_ = 0;
  int recent_next_ = 0;
};

}  // namespace host

#endif  // HOST_LIB_PLAN_STEP_LIST_H
