// Small geometry helpers shared by the PCB planners: copper islands, bounding boxes, unit
// conversion between Clipper's integer nanometres and the planner's millimetres.
#ifndef HOST_LIB_PCB_PCB_GEOMETRY_H
#define HOST_LIB_PCB_PCB_GEOMETRY_H

#include <clipper.hpp>  // ClipperLib::Paths

#include <cmath>       // std::llround
#include <functional>  // std::function
#include <vector>      // std::vector

#include "host/lib/drawing/bspline.h"  // Point2

namespace host::pcb {

// The Clipper types the PCB planners work in (integer nanometres).
using ClipperLib::cInt;
using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

const double kNmPerMm = 1e6;

inline Point2 to_mm(const ClipperLib::IntPoint& p) {
  return Point2(static_cast<double>(p.X) / kNmPerMm, static_cast<double>(p.Y) / kNmPerMm);
}
inline ClipperLib::cInt nm_from_mm(double mm) {
  return static_cast<ClipperLib::cInt>(std::llround(mm * kNmPerMm));
}

// Axis-aligned bounds in nm; empty when min > max.
struct BoxNm {
  ClipperLib::cInt min_x = 1, min_y = 1, max_x = 0, max_y = 0;
  bool empty() const { return min_x > max_x; }
  void add(const ClipperLib::IntPoint& p);
  void add(const ClipperLib::Path& path);
  bool overlaps(const BoxNm& o) const {
    return !empty() && !o.empty() && min_x <= o.max_x && o.min_x <= max_x && min_y <= o.max_y &&
           o.min_y <= max_y;
  }
  bool contains(const ClipperLib::IntPoint& p) const {
    return p.X >= min_x && p.X <= max_x && p.Y >= min_y && p.Y <= max_y;
  }
  bool contains(const BoxNm& o) const {
    return !o.empty() && o.min_x >= min_x && o.max_x <= max_x && o.min_y >= min_y &&
           o.max_y <= max_y;
  }
};
BoxNm box_of(const ClipperLib::Paths& paths);

// Union-find: the root of k's set (parent[k] == k at a root), halving the path on the way.
size_t root_of(std::vector<size_t>* parent, size_t k);
// The box both boxes share (empty if they do not overlap).
BoxNm common_box(const BoxNm& a, const BoxNm& b);

// The part of closed polygons inside a box, per path (Sutherland-Hodgman: linear in the
// vertices, where a Clipper operation sweeps every edge of a large polygon). A concave path
// may come back as one path with edges along the box's sides that double back; they enclose
// no area, so a later non-zero Clipper operation gives the same result as with the whole path.
ClipperLib::Paths clip_to_box(const ClipperLib::Paths& paths, const BoxNm& box);
// The same for one path whose box is known, appended to out.
void clip_path_to_box(const ClipperLib::Path& path, const BoxNm& path_box, const BoxNm& box,
                      ClipperLib::Paths* out);

// One connected piece of copper: an outer boundary (positive) and its holes (negative).
struct Island {
  ClipperLib::Paths paths;  // paths[0] is the outer boundary
  BoxNm box;
  // Holes (indices into paths) that hold no other island: a hatched pour's openings, which
  // separate nothing.
  std::vector<size_t> empty_holes;
};

// Copper split into islands (the union is taken first, so overlapping input is fine).
// An island inside another's hole is an island of its own.
std::vector<Island> copper_islands(const ClipperLib::Paths& copper);

// The islands' paths, island by island (outer, then holes): the copper they split.
ClipperLib::Paths copper_paths(const std::vector<Island>& islands);

// Union of the input under the non-zero rule, orientation normalised (outers positive).
ClipperLib::Paths union_of(const ClipperLib::Paths& paths);

// The union of many pieces (an aperture flash, a stroke, an island with its holes: each a
// region of its own), made strip by strip: the pieces sorted by the middle of their boxes
// in x, cut into groups of about 1 000 vertices, each group united by `united` (which
// returns the union of what it is given), and the strips joined by one last union.
ClipperLib::Paths united_by_strips(
    const std::vector<ClipperLib::Paths>& pieces,
    const std::function<ClipperLib::Paths(const ClipperLib::Paths&)>& united);

// Area-weighted centre of a set of polygons (holes negative), in nm; the first vertex
// when the area vanishes.
ClipperLib::IntPoint centroid(const ClipperLib::Paths& paths);

// Sum of signed areas (nm^2).
double signed_area(const ClipperLib::Paths& paths);

// Closed polygons offset by delta_nm (round joins, the given arc tolerance).
ClipperLib::Paths offset_closed(const ClipperLib::Paths& paths, double delta_nm,
                                double arc_tolerance_nm);
// The same for copper already split into islands, grown (delta_nm > 0): each island keeps
// its holes, and growing distributes over the union, so a large board is grown strip by
// strip (united_by_strips) without uniting its copper again.
ClipperLib::Paths grown_islands(const std::vector<Island>& islands, double delta_nm,
                                double arc_tolerance_nm);

// The union of open paths swept by a disc of radius radius_nm (round ends and joins).
ClipperLib::Paths sweep_open(const ClipperLib::Paths& paths, double radius_nm,
                             double arc_tolerance_nm);

// The same sweep as paths whose non-zero union it is, for a boolean operation that unites
// its operand anyway: each path's outline, built directly (disc_outline.h), not by
// Clipper's offset (the same region to the arcs' chords, in a fraction of the time on
// densely sampled paths), and not united.
ClipperLib::Paths sweep_open_unjoined(const ClipperLib::Paths& paths, double radius_nm,
                                      double arc_tolerance_nm);

// a AND b, a MINUS b (non-zero fill).
ClipperLib::Paths intersection_of(const ClipperLib::Paths& a, const ClipperLib::Paths& b);
ClipperLib::Paths difference_of(const ClipperLib::Paths& a, const ClipperLib::Paths& b);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_PCB_GEOMETRY_H
