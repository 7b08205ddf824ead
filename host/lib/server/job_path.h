// The running job's tool path for the page's live preview: the plan's XY moves as pieces (a
// rapid, a feed, a drill's travel, or the splines of one curve), each a polyline in mm that
// starts at a known length along the path, and how far along it the machine has got.
#ifndef HOST_LIB_SERVER_JOB_PATH_H
#define HOST_LIB_SERVER_JOB_PATH_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <cstddef>  // size_t
#include <cstdint>  // uint32_t
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
  // Bytes held (the path and its index by step), for tests.
  size_t heap_bytes() const;

 private:
  // The whole path is one polyline from the zero; piece k runs from point ends_[k - 1]
  // (point 0 for the first) to point ends_[k]. A line's three moves take three points and
  // three pieces (the old vectors per piece took ~450 bytes a line).
  struct Piece {
    uint32_t end = 0;  // its last point
    bool pen_down = false;
    double start_mm = 0;
  };
  size_t begin_of(size_t piece) const { return piece == 0 ? 0 : pieces_[piece - 1].end; }
  double end_mm_of(size_t piece) const {
    return piece + 1 < pieces_.size() ? pieces_[piece + 1].start_mm : length_mm_;
  }
  // The preview thinned to step_mm; false (out unfinished) when it takes over max_points.
  bool thinned(double step_mm, size_t max_points, nlohmann::json* pieces) const;

  std::vector<Point2> points_;
  std::vector<Piece> pieces_;
  std::vector<uint32_t> piece_of_step_;  // the first piece at or after each plan step
  double length_mm_ = 0;
  size_t cursor_piece_ = 0;  // where the last advance() found the tool
  size_t cursor_point_ = 0;  // the segment (points i, i + 1) there
  double cursor_mm_ = 0;     // the length along the path to that segment's start
  double done_mm_ = 0;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_PATH_H
