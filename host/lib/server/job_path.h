// The running job's tool path for the page's live preview: the plan's XY moves as pieces (a
// rapid, a feed, a drill's travel, or the splines of one curve), each a polyline in mm that
// starts at a known length along the path, and how far along it the machine has got.
#ifndef HOST_LIB_SERVER_JOB_PATH_H
#define HOST_LIB_SERVER_JOB_PATH_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <cstddef>  // size_t
#include <cstdint>  // uint32_t, uint64_t
#include <vector>   // std::vector

#include "host/lib/plan/job_plan.h"

namespace host::server {

class JobPath {
 public:
  // Splines sampled within tol_mm of the curve (the page draws a line per sample).
  explicit JobPath(const JobPlan& plan, double tol_mm = 0.02);

  // The length along the path (mm) to the machine's position while plan step `step` runs
  // (-1: the job's commands have all run): the nearest point of that step's piece or the
  // one before, never behind the last answer, the earliest of equally near points (a
  // closed curve at its start is 0 mm into it, not done).
  double advance(int step, const Point2& position_mm);
  double length_mm() const { return length_mm_; }
  // {"length_mm", "thinned_to_mm", "pieces": [{"pen_down", "start_mm", "length_mm",
  // "points_mm": [[x, y]..]}]}: every piece and point while they are at most max_points
  // (thinned_to_mm 0); beyond that (a job of a million lines: a page cannot draw three
  // million pieces), points closer than thinned_to_mm to the last one drawn are left out
  // and pieces shorter than it join the piece before, the step doubled until it fits.
  // start_mm and length_mm stay exact either way.
  nlohmann::json to_json(size_t max_points = kPreviewPoints) const;
  static constexpr size_t kPreviewPoints = 200000;
  // The piece plan step `step` moves along (a step that does not move: the next piece). It
  // grows by 0 or 1 from one step to the next, so it is kept as one bit a step and a count
  // every 64 steps.
  size_t piece_of_step(size_t step) const;
  // Bytes held (the path and its index by step), for tests.
  size_t heap_bytes() const;

 private:
  // The whole path is one polyline from the zero; piece k runs from point end(k - 1) (point 0
  // for the first) to point end(k). A line's travel and cut take two points and two pieces,
  // about 40 bytes (80 with double points and a piece index per step; 450 with vectors per
  // piece): a million-line job's path is what the server holds longest.
  struct PointMm {
    float x, y;  // 60 nm steps at 1 m: finer than the page's micrometres
  };
  static constexpr uint32_t kPenDownBit = 0x80000000u;
  Point2 point(size_t i) const { return Point2(points_[i].x, points_[i].y); }
  size_t end_of(size_t piece) const { return ends_[piece] & ~kPenDownBit; }
  bool pen_down(size_t piece) const { return (ends_[piece] & kPenDownBit) != 0; }
  size_t begin_of(size_t piece) const { return piece == 0 ? 0 : end_of(piece - 1); }
  double end_mm_of(size_t piece) const {
    return piece + 1 < starts_mm_.size() ? starts_mm_[piece + 1] : length_mm_;
  }
  // The preview thinned to step_mm; false (out unfinished) when it takes over max_points.
  bool thinned(double step_mm, size_t max_points, nlohmann::json* pieces) const;

  std::vector<PointMm> points_;
  std::vector<uint32_t> ends_;       // each piece's last point, its pen state in the top bit
  std::vector<double> starts_mm_;    // each piece's length along the path at its start
  std::vector<uint64_t> step_bits_;  // bit s: step s's piece is one more than step s - 1's
  std::vector<uint32_t> step_base_;  // word w: the piece of the step before step 64 w
  size_t steps_ = 0;
  double length_mm_ = 0;
  size_t cursor_piece_ = 0;  // where the last advance() found the tool
  size_t cursor_point_ = 0;  // the segment (points i, i + 1) there
  double cursor_mm_ = 0;     // the length along the path to that segment's start
  double done_mm_ = 0;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_PATH_H
