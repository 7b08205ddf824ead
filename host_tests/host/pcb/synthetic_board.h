// Copper, holes and outlines built in code for the PCB planner tests: rectangles, round
// pads and tracks in integer nanometres, as the Gerber reader would deliver them.
#ifndef HOST_TESTS_HOST_PCB_SYNTHETIC_BOARD_H
#define HOST_TESTS_HOST_PCB_SYNTHETIC_BOARD_H

#include <clipper.hpp>  // ClipperLib

#include <cmath>  // std::cos, std::sin

#include "host/lib/pcb/pcb_geometry.h"
#include "host/lib/pcb/pcb_layer.h"

namespace host::pcb::test {

inline ClipperLib::IntPoint nm(double x_mm, double y_mm) {
  return ClipperLib::IntPoint(nm_from_mm(x_mm), nm_from_mm(y_mm));
}

// Counter-clockwise rectangle.
inline ClipperLib::Path rect(double x0, double y0, double x1, double y1) {
  return ClipperLib::Path{nm(x0, y0), nm(x1, y0), nm(x1, y1), nm(x0, y1)};
}

// Round pad flattened with vertices on the circle (chord error 1 um, as a reader would).
inline ClipperLib::Path pad(double cx, double cy, double r) {
  const int n =
      std::max(8, static_cast<int>(std::ceil(3.14159265358979 / std::acos(1.0 - 0.001 / r))));
  ClipperLib::Path p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979 * i / n;
    p.push_back(nm(cx + r * std::cos(a), cy + r * std::sin(a)));
  }
  return p;
}

// A straight track of the given width with round ends.
inline ClipperLib::Paths track(double x0, double y0, double x1, double y1, double width) {
  ClipperLib::ClipperOffset o;
  o.ArcTolerance = 1000;  // 1 um
  o.AddPath(ClipperLib::Path{nm(x0, y0), nm(x1, y1)}, ClipperLib::jtRound, ClipperLib::etOpenRound);
  ClipperLib::Paths out;
  o.Execute(out, width * kNmPerMm / 2);
  return out;
}

inline PcbLayer copper_layer(const ClipperLib::Paths& polygons, LayerKind kind) {
  PcbLayer l;
  l.path = kind == LayerKind::kCopperBottom ? "test-B.Cu.gbr" : "test-F.Cu.gbr";
  l.kind = kind;
  l.polygons_nm = union_of(polygons);
  return l;
}

inline Hole hole(double x, double y, double d, int tool) {
  Hole h;
  h.at.x = nm_from_mm(x);
  h.at.y = nm_from_mm(y);
  h.diameter_nm = nm_from_mm(d);
  h.tool = tool;
  return h;
}

// A rectangular outline drawn as four separate strokes (as KiCad writes Edge.Cuts), the
// second one reversed and the order shuffled.
inline PcbLayer rect_outline(double x0, double y0, double x1, double y1) {
  PcbLayer l;
  l.path = "test-Edge.Cuts.gbr";
  l.kind = LayerKind::kOutline;
  l.outline_paths_are_open = true;
  l.polygons_nm = {ClipperLib::Path{nm(x0, y0), nm(x1, y0)},
                   ClipperLib::Path{nm(x0, y1), nm(x1, y1)},  // reversed: left to right on top
                   ClipperLib::Path{nm(x1, y0), nm(x1, y1)},
                   ClipperLib::Path{nm(x0, y1), nm(x0, y0)}};
  return l;
}

}  // namespace host::pcb::test

#endif  // HOST_TESTS_HOST_PCB_SYNTHETIC_BOARD_H
