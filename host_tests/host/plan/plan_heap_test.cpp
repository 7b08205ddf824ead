// The heap a plan takes at its peak, counted by replacing the global operator new: planning
// a drawing of separate lines must not hold the drawing's curves, the ordering's index and
// the planned curves all at once (a million-line job peaked near 600 MB in `run`). Its own
// executable: the counting operator new is global.
#include <gtest/gtest.h>
#include <malloc.h>  // malloc_usable_size

#include <atomic>   // std::atomic
#include <cstdlib>  // std::malloc, std::free
#include <new>      // std::bad_alloc
#include <random>   // std::mt19937

#include "host/lib/drawing/conics.h"
#include "host/lib/plan/job_plan.h"

namespace {

std::atomic<size_t> g_heap_bytes{0};
std::atomic<size_t> g_heap_peak{0};

void* counted_alloc(size_t n) {
  void* p = std::malloc(n == 0 ? 1 : n);
  if (p == nullptr) throw std::bad_alloc();
  const size_t now = g_heap_bytes += malloc_usable_size(p);
  size_t peak = g_heap_peak.load();
  while (now > peak && !g_heap_peak.compare_exchange_weak(peak, now)) {
  }
  return p;
}

void counted_free(void* p) {
  if (p == nullptr) return;
  g_heap_bytes -= malloc_usable_size(p);
  std::free(p);
}

}  // namespace

void* operator new(size_t n) {
  return counted_alloc(n);
}
void* operator new[](size_t n) {
  return counted_alloc(n);
}
void operator delete(void* p) noexcept {
  counted_free(p);
}
void operator delete[](void* p) noexcept {
  counted_free(p);
}
void operator delete(void* p, size_t) noexcept {
  counted_free(p);
}
void operator delete[](void* p, size_t) noexcept {
  counted_free(p);
}

namespace host {
namespace {

// n separate lines scattered over 280 x 190 mm, named as the DXF import names them.
Drawing scattered_lines(int n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(0, 280), y(0, 190), d(-2, 2);
  Drawing dr;
  dr.path = "lines.dxf";
  dr.curves.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    Curve c;
    const Point2 a(x(rng), y(rng));
    c.set_spline(line_spline(a, a + Point2(d(rng), d(rng))));
    c.kind = "LINE";
    c.source = "LINE #" + std::to_string(i + 1) + " (line " + std::to_string(7 * i + 8) + ")";
    dr.curves.push_back(std::move(c));
  }
  return dr;
}

// A drawing of separate lines holds a line's two ends inline, not a BSpline with its control
// point and knot vectors, and its kind as a literal: the Curve (96 bytes) and its name, ~136
// bytes a line (~265 with a BSpline and a kind string in every Curve; the import of a million
// lines peaked there).
TEST(PlanHeap, ADrawingOfSeparateLinesHoldsTheEndsNotABSplineALine) {
  const int n = 100000;
  const size_t empty = g_heap_bytes.load();
  const Drawing d = scattered_lines(n);
  const size_t held = g_heap_bytes.load() - empty;
  RecordProperty("drawing_bytes_per_line", static_cast<int>(held / n));
  EXPECT_LE(held, 150u * n) << held / n << " bytes a line held by the drawing";
  EXPECT_TRUE(d.curves[0].held.inline_line());
}

TEST(PlanHeap, PlanningSeparateLinesHoldsTheDrawingOrThePlanNotBothWithTheIndex) {
  const int n = 100000;
  Drawing d = scattered_lines(n);
  const size_t with_drawing = g_heap_bytes.load();
  g_heap_peak = with_drawing;
  PlanOptions o;
  o.work_width_mm = 297;
  o.work_height_mm = 210;
  const JobPlan plan = plan_job(std::move(d), o);
  const size_t peak = g_heap_peak.load() - with_drawing;
  ASSERT_EQ(plan.curves.size(), static_cast<size_t>(n));
  // Lift, travel, plunge and feed a line (a few end within the chaining tolerance of the
  // previous one: a feed across the gap instead).
  ASSERT_GT(plan.steps.size(), 39u * n / 10);
  // Counted above the drawing (~136 bytes a line: a Curve holding the line's ends, and its
  // name), which planning takes over in place: 96 bytes a line at the peak (112 when each
  // curve was scaled into a second vector of BSplines and names beside it). The ordering's
  // grid (a vector per cell, a copy of the ends) held beside the planned curves made the
  // peak 203; a BSpline in every planned curve 135.
  RecordProperty("peak_bytes_per_line", static_cast<int>(peak / n));
  EXPECT_LE(peak, 105u * n) << peak / n << " bytes a line above the drawing";
}

// A straight line holds nothing on the heap once planned: its two ends are inline.
TEST(PlanHeap, AStraightPlannedCurveHoldsNoHeap) {
  const size_t before = g_heap_bytes.load();
  PlannedCurve c;
  c.set_spline(line_spline(Point2(1, 2), Point2(3, 4)));
  EXPECT_EQ(g_heap_bytes.load() - before, 0u);
  EXPECT_EQ(end_point(c.spline()), Point2(3, 4));
}

// What a finished plan of separate lines holds, a line: four steps of 16 bytes (their shapes
// shared), the planned curve (88 bytes) and its name (~40 on the heap): 191. Four 40-byte
// PlanSteps made it 287; a BSpline with its two vectors in every planned curve ~400.
TEST(PlanHeap, APlanOfSeparateLinesHoldsAboutTwoHundredBytesALine) {
  const int n = 100000;
  const size_t empty = g_heap_bytes.load();
  JobPlan plan;
  {
    PlanOptions o;
    o.work_width_mm = 297;
    o.work_height_mm = 210;
    plan = plan_job(scattered_lines(n), o);
  }
  const size_t held = g_heap_bytes.load() - empty;
  ASSERT_EQ(plan.curves.size(), static_cast<size_t>(n));
  RecordProperty("plan_bytes_per_line", static_cast<int>(held / n));
  EXPECT_LE(held, 210u * n) << held / n << " bytes a line held by the plan";
}

}  // namespace
}  // namespace host
