// How far a simulated tool path strays from the curves it should follow.
#ifndef HOST_LIB_SIM_CONTOUR_ERROR_H
#define HOST_LIB_SIM_CONTOUR_ERROR_H

#include <cstddef>        // size_t
#include <cstdint>        // uint32_t, uint64_t
#include <unordered_map>  // std::unordered_map
#include <vector>         // std::vector

#include "host/lib/drawing/bspline.h"  // host::Point2

namespace host::sim {

// Distance from each point to the nearest segment of any polyline, indexed on a grid so a
// whole job (1e6 points, 1e6 segments) takes a second or so. Exact: the grid only chooses
// which segments are looked at.
//
// A coarse grid (cell_mm) holds every segment. When the segments are much shorter than its
// cells (a contour of a million 0.3 um segments puts ~1 700 in each 0.5 mm cell, and every
// query looked at all of them), a sparse fine grid sized to the segments holds the short
// ones, and the coarse grid's long ones are searched beside it; the whole coarse search runs
// only when neither finds a segment within the fine rings searched.
class NearestSegment {
 public:
  NearestSegment(const std::vector<std::vector<Point2>>& polylines, double cell_mm = 0.5);
  // Built polyline by polyline (no copy of a large job's curves): add(), then index().
  explicit NearestSegment(double cell_mm = 0.5) : cell_(cell_mm) {}
  void add(const std::vector<Point2>& polyline);
  // Room for this many segments (a million lines' index grew by doubling to twice its size).
  void reserve(size_t segments) { segments_.reserve(segments); }
  void index();

  // Distance in mm; searches outward ring by ring until no closer segment can exist.
  double distance(const Point2& p) const;
  // An upper bound on distance(p) for a segment or a few: p's distance to the previous
  // query's nearest segment, and when that is beyond enough_mm, to the segments after it
  // too (the tool moves on along its path; the nearest of them is the next query's start).
  double upper_bound(const Point2& p, double enough_mm) const;
  // Segment distances computed so far (how much a query costs, for tests).
  size_t segments_examined() const { return examined_; }
  // The fine grid's cell (0: none; every query uses the coarse grid).
  double fine_cell_mm() const { return fine_cell_; }
  // Bytes the index holds (its segments, grids and cell lists), for tests.
  size_t held_bytes() const;

 private:
  struct Segment {
    Point2 a, b;
  };
  // A dense grid in compressed rows: cell c holds entries[start[c] .. start[c + 1]).
  struct Grid {
    double cell = 0;
    long nx = 0, ny = 0;
    std::vector<uint32_t> start;
    std::vector<uint32_t> entries;
  };
  void build_coarse(Grid* g, bool long_only) const;
  void build_fine();
  bool is_short(const Segment& s) const;
  // Ring search of one grid from p; best2/best_s in and out. Returns the distance within
  // which every segment of the grid has been looked at (infinity when it was searched out).
  double search(const Grid& g, const Point2& p, double* best2, uint32_t* best_s) const;
  double search_fine(const Point2& p, double* best2, uint32_t* best_s) const;
  double dist2(uint32_t s, double px, double py) const;

  double cell_;
  Point2 min_{0, 0}, max_{0, 0};
  std::vector<Segment> segments_;
  Grid coarse_;       // every segment
  Grid coarse_long_;  // the segments too long for the fine grid (when it is used)
  double fine_cell_ = 0;
  // Fine cells that hold something: key (ix << 32 | iy) -> [first, last) in fine_entries_.
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> fine_cells_;
  std::vector<uint32_t> fine_entries_;
  mutable uint32_t hint_ = 0;  // the previous query's nearest segment
  mutable size_t examined_ = 0;
};

}  // namespace host::sim

#endif  // HOST_LIB_SIM_CONTOUR_ERROR_H
