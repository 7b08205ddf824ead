// The plan's tool path as pieces and the machine's place on it (see job_path.h).
#include "host/lib/server/job_path.h"

#include <algorithm>  // std::max, std::min
#include <cmath>      // std::round, std::abs
#include <stdexcept>  // std::length_error

#include "host/lib/plan/tool_path_walk.h"

namespace host::server {

namespace {

// Micrometres are all the page can show; shorter numbers keep a large job's path small.
double um_rounded(double v_mm) {
  return std::round(v_mm * 1000.0) / 1000.0;
}

// Where on segment a-b the point p is nearest: the parameter 0..1 and the distance.
void nearest_on_segment(const Point2& a, const Point2& b, const Point2& p, double* t,
                        double* distance) {
  const Point2 d = b - a;
  const double len2 = d.squaredNorm();
  *t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  *distance = (a + *t * d - p).norm();
}

}  // namespace

JobPath::JobPath(const JobPlan& plan, double tol_mm) {
  if (plan.steps.size() >= UINT32_MAX) throw std::length_error("job path: too many steps");
  points_.push_back(Point2(0, 0));  // a plan starts at the zero
  piece_of_step_.resize(plan.steps.size());
  walk_tool_path(plan, tol_mm, [&](const ToolMove& m) {
    // A curve sent as several splines is one piece: its first step's.
    const size_t n = pieces_.size();
    piece_of_step_[m.step] = static_cast<uint32_t>(m.kind == StepMove::kContinues ? n - 1 : n);
    if (m.kind != StepMove::kNew) return;
    Piece p;  // from where the tool stands through the move's points
    p.pen_down = m.pen_down;
    p.start_mm = length_mm_;
    for (const Point2& q : m.points_mm) {
      length_mm_ += (q - points_.back()).norm();
      points_.push_back(q);
    }
    if (points_.size() >= UINT32_MAX) throw std::length_error("job path: too many points");
    p.end = static_cast<uint32_t>(points_.size() - 1);
    pieces_.push_back(p);
  });
  points_.shrink_to_fit();
  pieces_.shrink_to_fit();
}

double JobPath::advance(int step, const Point2& position_mm) {
  if (step < 0) {
    done_mm_ = length_mm_;  // every command has run
    return done_mm_;
  }
  if (pieces_.empty() || static_cast<size_t>(step) >= piece_of_step_.size()) return done_mm_;
  // The step's piece and the one before: the tool may not have left that yet when its
  // command is reported done. (Not the next one: a rapid home crosses what it passes.)
  const size_t piece = std::min<size_t>(piece_of_step_[step], pieces_.size() - 1);
  const size_t first = std::max(cursor_piece_, piece == 0 ? 0 : piece - 1);
  double best_distance = 0, best_mm = done_mm_, best_start_mm = cursor_mm_;
  size_t best_piece = cursor_piece_, best_point = cursor_point_;
  bool found = false;
  for (size_t k = first; k <= piece; ++k) {
    const bool at_cursor = k == cursor_piece_;
    // Lengths summed as the constructor summed them: the same numbers to the last bit.
    double along = at_cursor ? cursor_mm_ : pieces_[k].start_mm;
    for (size_t i = at_cursor ? cursor_point_ : begin_of(k); i < pieces_[k].end; ++i) {
      const double next = along + (points_[i + 1] - points_[i]).norm();
      double t = 0, distance = 0;
      nearest_on_segment(points_[i], points_[i + 1], position_mm, &t, &distance);
      // Nearer by more than a micrometre: a tie goes to the earlier point.
      if (!found || distance < best_distance - 0.001) {
        found = true;
        best_distance = distance;
        best_mm = along + t * (next - along);
        best_piece = k;
        best_point = i;
        best_start_mm = along;
      }
      along = next;
    }
  }
  if (found && best_mm >= done_mm_) {
    done_mm_ = best_mm;
    cursor_piece_ = best_piece;
    cursor_point_ = best_point;
    cursor_mm_ = best_start_mm;
  }
  return done_mm_;
}

bool JobPath::thinned(double step_mm, size_t max_points, nlohmann::json* out) const {
  *out = nlohmann::json::array();
  size_t count = 0;
  nlohmann::json points;
  Point2 last(0, 0);
  size_t open = 0, through = 0;  // the output piece: from piece `open` through `through`
  bool is_open = false;
  auto emit = [&](const Point2& p) {
    points.push_back({um_rounded(p.x()), um_rounded(p.y())});
    last = p;
    ++count;
  };
  auto close = [&] {
    const Point2& end = points_[pieces_[through].end];
    if (points.empty() || end != last) emit(end);  // a thinned piece still ends where it ends
    // The length between the rounded ends: each piece starts where the one before ends.
    const double start_mm = um_rounded(pieces_[open].start_mm);
    out->push_back({{"pen_down", pieces_[open].pen_down},
                    {"start_mm", start_mm},
                    {"length_mm", um_rounded(um_rounded(end_mm_of(through)) - start_mm)},
                    {"points_mm", std::move(points)}});
    points = nlohmann::json::array();
  };
  for (size_t k = 0; k < pieces_.size(); ++k) {
    // Thinned, a piece joins the one before unless it is a visible piece of another state.
    const bool visible = end_mm_of(k) - pieces_[k].start_mm >= step_mm;
    if (!is_open || step_mm <= 0 || (visible && pieces_[k].pen_down != pieces_[open].pen_down)) {
      if (is_open) close();
      is_open = true;
      open = k;
      emit(points_[begin_of(k)]);
    }
    through = k;
    for (size_t i = begin_of(k) + 1; i <= pieces_[k].end; ++i) {
      const Point2& p = points_[i];
      if (step_mm <= 0 || std::abs(p.x() - last.x()) >= step_mm ||
          std::abs(p.y() - last.y()) >= step_mm)
        emit(p);
    }
    if (count > max_points) return false;
  }
  if (is_open) close();
  return count <= max_points;
}

nlohmann::json JobPath::to_json(size_t max_points) const {
  nlohmann::json pieces;
  double step_mm = 0;
  // Each piece repeats the point it starts at.
  if (points_.size() + pieces_.size() > max_points) {
    Point2 lo = points_[0], hi = points_[0];
    for (const Point2& p : points_) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    // Half a pixel of a 1 000-pixel view, then coarser until it fits.
    step_mm = std::max(0.001, (hi - lo).maxCoeff() / 2000);
    while (!thinned(step_mm, max_points, &pieces)) step_mm *= 2;
  } else {
    thinned(0, max_points, &pieces);
  }
  return {{"length_mm", um_rounded(length_mm_)},
          {"thinned_to_mm", um_rounded(step_mm)},
          {"pieces", std::move(pieces)}};
}

size_t JobPath::heap_bytes() const {
  return points_.capacity() * sizeof(Point2) + pieces_.capacity() * sizeof(Piece) +
         piece_of_step_.capacity() * sizeof(uint32_t);
}

}  // namespace host::server
