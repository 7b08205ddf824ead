// The running job's tool path for the page's live preview: the plan's XY moves as pieces (a
// rapid, a feed, a drill's travel, or the splines of one curve), each a polyline in mm that
// starts at a known length along the path, and how far along it the machine has got.
#ifndef HOST_LIB_SERVER_JOB_PATH_H
#define HOST_LIB_SERVER_JOB_PATH_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <cstddef>  // size_t
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
  // {"length_mm", "pieces": [{"pen_down", "start_mm", "length_mm", "points_mm": [[x, y]..]}]}
  nlohmann::json to_json() const;

 private:
  struct Piece {
    bool pen_down = false;
    double start_mm = 0;
    std::vector<Point2> points_mm;
    std::vector<double> at_mm;  // length along the path at each point
  };
  std::vector<Piece> pieces_;
  std::vector<size_t> piece_of_step_;  // the first piece at or after each plan step
  double length_mm_ = 0;
  size_t cursor_piece_ = 0;    // where the last advance() found the tool
  size_t cursor_segment_ = 0;  // segment (points i, i+1) of that piece
  double done_mm_ = 0;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_PATH_H
