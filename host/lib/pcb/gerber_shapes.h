// Plane geometry for the Gerber reader: aperture shapes, strokes and arcs as Clipper paths in
// integer nanometres. Curves become inscribed polygons whose chord error is at most `tol_nm`.
#ifndef HOST_LIB_PCB_GERBER_SHAPES_H
#define HOST_LIB_PCB_GERBER_SHAPES_H

#include <clipper.hpp>  // ClipperLib::Path, Paths

#include <vector>  // std::vector

#include "host/lib/pcb/pcb_geometry.h"  // BoxNm

namespace host::pcb {

struct VecNm {
  double x = 0;
  double y = 0;
};

// Segments for a full circle of radius r so that the chord error is at most tol (>= 8).
int circle_segments(double r_nm, double tol_nm);

ClipperLib::IntPoint to_int(VecNm p);

// Counter-clockwise (positive) polygons.
ClipperLib::Path circle_path(VecNm centre, double diameter_nm, double tol_nm);
ClipperLib::Path rect_path(VecNm centre, double w_nm, double h_nm);
ClipperLib::Path obround_path(VecNm centre, double w_nm, double h_nm, double tol_nm);
// Regular polygon with its first vertex at `rotation_deg` from the centre.
ClipperLib::Path regular_polygon_path(VecNm centre, double diameter_nm, int vertices,
                                      double rotation_deg);

// A straight stroke of a round tool: two half circles joined (the "stadium").
ClipperLib::Path capsule_path(VecNm a, VecNm b, double diameter_nm, double tol_nm);

// The convex hull of points (for a convex aperture swept along a line).
ClipperLib::Path convex_hull(ClipperLib::Path points);

// Points along an arc from angle a0 sweeping `sweep` radians (negative = clockwise), the
// radius going linearly from r0 to r1; the start point is not appended, the end point is.
void append_arc(ClipperLib::Path& out, VecNm centre, double r0_nm, double r1_nm, double a0,
                double sweep, double tol_nm);

// Rotates points about the origin.
void rotate_path(ClipperLib::Path& path, double degrees);
void translate_paths(ClipperLib::Paths& paths, ClipperLib::cInt dx, ClipperLib::cInt dy);

// Makes the outer boundary counter-clockwise (a region contour may be either way round).
void make_positive(ClipperLib::Path& path);

// Paths whose boxes meet `box` go to `touched`, the others to `kept`.
void split_by_box(const ClipperLib::Paths& all, const BoxNm& box, ClipperLib::Paths& touched,
                  ClipperLib::Paths& kept);

// Union of `base` and many small objects (object k is paths[starts[k]] up to the next start:
// an outer and its holes), strip by strip (united_by_strips): one union over a whole board
// costs time in proportion to vertices times the edges across the board.
ClipperLib::Paths union_objects(const ClipperLib::Paths& paths, const std::vector<size_t>& starts,
                                const ClipperLib::Paths& base);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_GERBER_SHAPES_H
