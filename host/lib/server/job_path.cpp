// The plan's tool path as pieces and the machine's place on it (see job_path.h).
#include "host/lib/server/job_path.h"

#include <algorithm>  // std::max, std::min
#include <cmath>      // std::round, std::abs
#include <stdexcept>  // std::length_error, std::logic_error

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
  points_.push_back(PointMm{0, 0});  // a plan starts at the zero
  steps_ = plan.steps.size();
  step_bits_.assign((steps_ + 63) / 64, 0);
  step_base_.assign(step_bits_.size(), 0);
  size_t last_piece = 0;  // the piece of the step before
  walk_tool_path(plan, tol_mm, [&](const ToolMove& m) {
    // A curve sent as several splines is one piece: its first step's.
    const size_t n = ends_.size();
    const size_t piece = m.kind == StepMove::kContinues && n > 0 ? n - 1 : n;
    if (m.step % 64 == 0) step_base_[m.step / 64] = static_cast<uint32_t>(last_piece);
    if (piece == last_piece + 1) {
      step_bits_[m.step / 64] |= uint64_t{1} << (m.step % 64);
    } else if (piece != last_piece) {
      throw std::logic_error("job path: a step's piece is not the one before's or the next");
    }
    last_piece = piece;
    if (m.kind != StepMove::kNew) return;
    // From where the tool stands through the move's points, each as it is kept: the lengths
    // here and in advance() are sums of the same numbers.
    starts_mm_.push_back(length_mm_);
    for (const Point2& q : m.points_mm) {
      const Point2 before = point(points_.size() - 1);
      points_.push_back(PointMm{static_cast<float>(q.x()), static_cast<float>(q.y())});
      length_mm_ += (point(points_.size() - 1) - before).norm();
    }
    if (points_.size() >= kPenDownBit) throw std::length_error("job path: too many points");
    ends_.push_back(static_cast<uint32_t>(points_.size() - 1) | (m.pen_down ? kPenDownBit : 0));
  });
  points_.shrink_to_fit();
  ends_.shrink_to_fit();
  starts_mm_.shrink_to_fit();
}

size_t JobPath::piece_of_step(size_t step) const {
  const uint64_t through_step = (uint64_t{2} << (step % 64)) - 1;  // bits 0 .. step % 64
  return step_base_[step / 64] +
         static_cast<size_t>(__builtin_popcountll(step_bits_[step / 64] & through_step));
}

double JobPath::advance(int step, const Point2& position_mm) {
  if (step < 0) {
    done_mm_ = length_mm_;  // every command has run
    return done_mm_;
  }
  if (ends_.empty() || static_cast<size_t>(step) >= steps_) return done_mm_;
  // The step's piece and the one before: the tool may not have left that yet when its
  // command is reported done. (Not the next one: a rapid home crosses what it passes.)
  const size_t piece = std::min(piece_of_step(static_cast<size_t>(step)), ends_.size() - 1);
  const size_t first = std::max(cursor_piece_, piece == 0 ? 0 : piece - 1);
  double best_distance = 0, best_mm = done_mm_, best_start_mm = cursor_mm_;
  size_t best_piece = cursor_piece_, best_point = cursor_point_;
  bool found = false;
  for (size_t k = first; k <= piece; ++k) {
    const bool at_cursor = k == cursor_piece_;
    // Lengths summed as the constructor summed them: the same numbers to the last bit.
    double along = at_cursor ? cursor_mm_ : starts_mm_[k];
    for (size_t i = at_cursor ? cursor_point_ : begin_of(k); i < end_of(k); ++i) {
      const Point2 a = point(i), b = point(i + 1);
      const double next = along + (b - a).norm();
      double t = 0, distance = 0;
      nearest_on_segment(a, b, position_mm, &t, &distance);
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
    const Point2 end = point(end_of(through));
    if (points.empty() || end != last) emit(end);  // a thinned piece still ends where it ends
    // The length between the rounded ends: each piece starts where the one before ends.
    const double start_mm = um_rounded(starts_mm_[open]);
    out->push_back({{"pen_down", pen_down(open)},
                    {"start_mm", start_mm},
                    {"length_mm", um_rounded(um_rounded(end_mm_of(through)) - start_mm)},
                    {"points_mm", std::move(points)}});
    points = nlohmann::json::array();
  };
  for (size_t k = 0; k < ends_.size(); ++k) {
    // Thinned, a piece joins the one before unless it is a visible piece of another state.
    const bool visible = end_mm_of(k) - starts_mm_[k] >= step_mm;
    if (!is_open || step_mm <= 0 || (visible && pen_down(k) != pen_down(open))) {
      if (is_open) close();
      is_open = true;
      open = k;
      emit(point(begin_of(k)));
    }
    through = k;
    for (size_t i = begin_of(k) + 1; i <= end_of(k); ++i) {
      const Point2 p = point(i);
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
  if (points_.size() + ends_.size() > max_points) {
    Point2 lo = point(0), hi = point(0);
    for (size_t i = 1; i < points_.size(); ++i) {
      lo = lo.cwiseMin(point(i));
      hi = hi.cwiseMax(point(i));
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
  return points_.capacity() * sizeof(PointMm) + ends_.capacity() * sizeof(uint32_t) +
         starts_mm_.capacity() * sizeof(double) + step_bits_.capacity() * sizeof(uint64_t) +
         step_base_.capacity() * sizeof(uint32_t);
}

}  // namespace host::server
