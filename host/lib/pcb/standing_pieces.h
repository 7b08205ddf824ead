// What a swept tool leaves standing of a rectangle of material, as connected pieces: the
// isolation check's second question (does each copper island stand in a piece of its own).
// One Clipper difference of the whole rectangle visits, at every scan beam, every swept edge
// across the board's width; here the rectangle is cut into columns, each column's difference
// takes only the outlines' parts inside it (clip_path_to_box, linear), and the pieces of
// neighbouring columns that share a stretch of their common side are joined.
#ifndef HOST_LIB_PCB_STANDING_PIECES_H
#define HOST_LIB_PCB_STANDING_PIECES_H

#include <polyclipping/clipper.hpp>  // ClipperLib::Paths

#include <cstddef>  // size_t
#include <vector>   // std::vector

#include "host/lib/pcb/pcb_geometry.h"  // BoxNm

namespace host::pcb {

// One column's piece of standing material: outer boundary, holes, their boxes, and the
// connected piece of the whole rectangle it belongs to.
struct StandingPiece {
  ClipperLib::Path outer;
  ClipperLib::Paths holes;
  BoxNm box;
  std::vector<BoxNm> hole_boxes;
  size_t whole = 0;  // the same number for the column pieces of one connected piece

  // Inside the material (on its boundary counts as inside).
  bool holds(const ClipperLib::IntPoint& p) const;
};

// The pieces of a Clipper result: outer paths (depth 0, 2, 4, ...) with their direct holes
// (`whole` numbers each piece by itself).
std::vector<StandingPiece> pieces_of(const ClipperLib::PolyTree& tree);

// frame minus the non-zero union of `outlines` (closed paths, nm), in columns of about
// column_vertices outline vertices each (at least one column; the frame must not be empty).
std::vector<StandingPiece> standing_pieces(const BoxNm& frame, const ClipperLib::Paths& outlines,
                                           size_t column_vertices = 2000);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_STANDING_PIECES_H
