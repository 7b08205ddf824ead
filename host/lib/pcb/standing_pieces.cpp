// Standing material in columns, joined across the columns' common sides (standing_pieces.h).
#include "host/lib/pcb/standing_pieces.h"

#include <algorithm>  // std::sort, std::lower_bound, std::upper_bound, std::min, std::max
#include <numeric>    // std::iota

namespace host::pcb {

bool StandingPiece::holds(const IntPoint& p) const {
  if (!box.contains(p) || ClipperLib::PointInPolygon(p, outer) == 0) return false;
  for (size_t h = 0; h < holes.size(); ++h) {
    if (hole_boxes[h].contains(p) && ClipperLib::PointInPolygon(p, holes[h]) != 0) return false;
  }
  return true;
}

namespace {

// Outer nodes of the tree (depth 0, 2, 4, ...) become pieces with their direct holes.
void collect_pieces(const ClipperLib::PolyNode& node, std::vector<StandingPiece>* out) {
  for (const ClipperLib::PolyNode* o : node.Childs) {
    StandingPiece p;
    p.outer = o->Contour;
    p.box.add(o->Contour);
    for (const ClipperLib::PolyNode* h : o->Childs) {
      p.holes.push_back(h->Contour);
      BoxNm hb;
      hb.add(h->Contour);
      p.hole_boxes.push_back(hb);
      collect_pieces(*h, out);
    }
    out->push_back(std::move(p));
  }
}

const cInt kBeyondSideNm = 1000;

BoxNm box_around(BoxNm b, cInt margin) {
  b.min_x -= margin;
  b.min_y -= margin;
  b.max_x += margin;
  b.max_y += margin;
  return b;
}

// A stretch of a piece's boundary on a column side: y from lo to hi.
struct SideStretch {
  cInt lo, hi;
  size_t piece;
};

// Where pieces [first, last) have material on the vertical line x: their outer boundaries'
// stretches there, sorted. (Were a hole to touch its outer boundary along x, what it takes
// away would count as material and join pieces that are apart: a reported unseparated pair,
// never a missed one. The outlines are cut beyond the sides so that Clipper has no edges
// along them to give so.)
std::vector<SideStretch> stretches_on(const std::vector<StandingPiece>& pieces, size_t first,
                                      size_t last, cInt x) {
  std::vector<SideStretch> out;
  for (size_t k = first; k < last; ++k) {
    const Path& outer = pieces[k].outer;
    if (pieces[k].box.min_x > x || pieces[k].box.max_x < x) continue;
    for (size_t i = 0; i < outer.size(); ++i) {
      const IntPoint& u = outer[i];
      const IntPoint& v = outer[(i + 1) % outer.size()];
      if (u.X == x && v.X == x && u.Y != v.Y)
        out.push_back(SideStretch{std::min(u.Y, v.Y), std::max(u.Y, v.Y), k});
    }
  }
  std::sort(out.begin(), out.end(),
            [](const SideStretch& a, const SideStretch& b) { return a.lo < b.lo; });
  return out;
}

}  // namespace

std::vector<StandingPiece> pieces_of(const ClipperLib::PolyTree& tree) {
  std::vector<StandingPiece> pieces;
  collect_pieces(tree, &pieces);
  for (size_t k = 0; k < pieces.size(); ++k) pieces[k].whole = k;
  return pieces;
}

std::vector<StandingPiece> standing_pieces(const BoxNm& frame, const Paths& outlines,
                                           size_t column_vertices) {
  size_t vertices = 0;
  std::vector<BoxNm> boxes(outlines.size());
  for (size_t i = 0; i < outlines.size(); ++i) {
    vertices += outlines[i].size();
    boxes[i].add(outlines[i]);
  }
  const cInt width = frame.max_x - frame.min_x;
  const cInt columns = std::max<cInt>(
      1, std::min<cInt>(width, static_cast<cInt>(vertices / std::max<size_t>(column_vertices, 1))));
  std::vector<cInt> sides(static_cast<size_t>(columns) + 1);  // column j: sides[j] .. sides[j + 1]
  for (cInt j = 0; j <= columns; ++j) sides[j] = frame.min_x + width * j / columns;

  // Each outline goes to every column its box reaches.
  std::vector<std::vector<size_t>> in_column(sides.size() - 1);
  for (size_t i = 0; i < outlines.size(); ++i) {
    if (!boxes[i].overlaps(frame)) continue;
    // First column whose right side is at or right of the box, last whose left side is at
    // or left of it.
    const size_t first = static_cast<size_t>(
        std::lower_bound(sides.begin() + 1, sides.end(), boxes[i].min_x) - (sides.begin() + 1));
    const size_t last = static_cast<size_t>(
        std::upper_bound(sides.begin(), sides.end() - 1, boxes[i].max_x) - sides.begin());
    for (size_t j = first; j < last && j < in_column.size(); ++j) in_column[j].push_back(i);
  }

  std::vector<StandingPiece> pieces;
  std::vector<size_t> column_start;  // the column's first piece
  for (size_t j = 0; j < in_column.size(); ++j) {
    column_start.push_back(pieces.size());
    BoxNm column = frame;
    column.min_x = sides[j];
    column.max_x = sides[j + 1];
    // The outlines are cut a little beyond the column, so that their cut edges do not run
    // along its sides (Clipper may then give what they take away as a hole touching the
    // piece's outer boundary there, which would join what the cut separates).
    const BoxNm reach = box_around(column, kBeyondSideNm);
    ClipperLib::Clipper c;
    c.AddPath(Path{IntPoint(column.min_x, column.min_y), IntPoint(column.max_x, column.min_y),
                   IntPoint(column.max_x, column.max_y), IntPoint(column.min_x, column.max_y)},
              ClipperLib::ptSubject, true);
    Paths parts;  // each outline cut to the column, its box known: no copy of it
    for (size_t i : in_column[j]) clip_path_to_box(outlines[i], boxes[i], reach, &parts);
    c.AddPaths(parts, ClipperLib::ptClip, true);
    ClipperLib::PolyTree tree;
    c.Execute(ClipperLib::ctDifference, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    collect_pieces(tree, &pieces);
  }
  column_start.push_back(pieces.size());

  // Pieces of neighbouring columns that share a stretch of their common side are one.
  std::vector<size_t> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t j = 0; j + 1 < in_column.size(); ++j) {
    const cInt x = sides[j + 1];
    const std::vector<SideStretch> left =
        stretches_on(pieces, column_start[j], column_start[j + 1], x);
    const std::vector<SideStretch> right =
        stretches_on(pieces, column_start[j + 1], column_start[j + 2], x);
    size_t a = 0, b = 0;
    while (a < left.size() && b < right.size()) {
      if (std::min(left[a].hi, right[b].hi) > std::max(left[a].lo, right[b].lo)) {
        parent[root_of(&parent, left[a].piece)] = root_of(&parent, right[b].piece);
      }
      if (left[a].hi < right[b].hi) {
        ++a;
      } else {
        ++b;
      }
    }
  }
  // Wholes numbered in the order of their first column piece.
  std::vector<size_t> number(pieces.size(), pieces.size());
  size_t wholes = 0;
  for (size_t k = 0; k < pieces.size(); ++k) {
    size_t& n = number[root_of(&parent, k)];
    if (n == pieces.size()) n = wholes++;
    pieces[k].whole = n;
  }
  return pieces;
}

}  // namespace host::pcb
