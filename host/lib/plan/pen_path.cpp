// A plot's tool path, compact (see pen_path.h).
#include "host/lib/plan/pen_path.h"

#include <cmath>  // std::abs

namespace host {

void PenPath::add(const Point2& p_mm, bool pen_down) {
  points_.push_back({static_cast<float>(p_mm.x()), static_cast<float>(p_mm.y())});
  down_.push_back(pen_down);
}

void PenPath::each_piece(const std::function<void(const std::vector<Point2>&, bool)>& fn) const {
  std::vector<Point2> piece;
  for (size_t i = 0; i < size(); ++i) {
    if (i > 0 && down_[i] != down_[i - 1]) {
      piece.push_back(point(i));  // this piece ends where the next one begins
      fn(piece, down_[i - 1]);
      piece.clear();
    }
    piece.push_back(point(i));
  }
  if (!piece.empty()) fn(piece, down_.back());
}

void PenPath::thin(double step_mm) {
  const size_t n = size();
  size_t out = 0;
  for (size_t i = 0; i < n; ++i) {
    bool keep = i == 0 || i + 1 == n || down_[i] != down_[out - 1];
    if (!keep) {
      const std::array<float, 2>& k = points_[out - 1];
      keep = std::abs(points_[i][0] - k[0]) >= step_mm || std::abs(points_[i][1] - k[1]) >= step_mm;
    }
    if (keep) {
      points_[out] = points_[i];
      down_[out] = down_[i];
      ++out;
    }
  }
  points_.resize(out);
  down_.resize(out);
}

size_t PenPath::heap_bytes() const {
  // A deque's blocks (512 bytes in libstdc++) and its map of them, about.
  const size_t per_block = 512 / sizeof(points_[0]);
  const size_t blocks = points_.size() / per_block + 1;
  return blocks * (512 + sizeof(void*)) + down_.capacity() / 8;
}

std::vector<std::vector<Point2>> pen_down_pieces(const PenPath& path) {
  std::vector<std::vector<Point2>> down;
  path.each_piece([&down](const std::vector<Point2>& piece, bool pen_down) {
    if (pen_down) down.push_back(piece);
  });
  return down;
}

}  // namespace host
