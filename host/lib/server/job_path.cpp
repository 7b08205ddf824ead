// The plan's tool path as pieces and the machine's place on it (see job_path.h).
#include "host/lib/server/job_path.h"

#include <algorithm>  // std::max, std::min
#include <cmath>      // std::round

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
  Point2 at(0, 0);  // a plan starts at the zero
  piece_of_step_.resize(plan.steps.size());
  // A new piece from where the tool stands through the move's points.
  auto add = [&](const ToolMove& m) {
    Piece p;
    p.pen_down = m.pen_down;
    p.start_mm = length_mm_;
    p.points_mm.push_back(at);
    p.at_mm.push_back(length_mm_);
    for (const Point2& q : m.points_mm) {
      length_mm_ += (q - p.points_mm.back()).norm();
      p.points_mm.push_back(q);
      p.at_mm.push_back(length_mm_);
    }
    at = p.points_mm.back();
    pieces_.push_back(std::move(p));
  };
  walk_tool_path(plan, tol_mm, [&](const ToolMove& m) {
    // A curve sent as several splines is one piece: its first step's.
    piece_of_step_[m.step] = m.kind == StepMove::kContinues ? pieces_.size() - 1 : pieces_.size();
    if (m.kind == StepMove::kNew) add(m);
  });
}

double JobPath::advance(int step, const Point2& position_mm) {
  if (step < 0) {
    done_mm_ = length_mm_;  // every command has run
    return done_mm_;
  }
  if (pieces_.empty() || static_cast<size_t>(step) >= piece_of_step_.size()) return done_mm_;
  // The step's piece and the one before: the tool may not have left that yet when its
  // command is reported done. (Not the next one: a rapid home crosses what it passes.)
  const size_t piece = std::min(piece_of_step_[step], pieces_.size() - 1);
  const size_t first = std::max(cursor_piece_, piece == 0 ? 0 : piece - 1);
  const size_t last = piece;
  double best_distance = 0, best_mm = done_mm_;
  size_t best_piece = cursor_piece_, best_segment = cursor_segment_;
  bool found = false;
  for (size_t k = first; k <= last; ++k) {
    const Piece& p = pieces_[k];
    for (size_t i = k == cursor_piece_ ? cursor_segment_ : 0; i + 1 < p.points_mm.size(); ++i) {
      double t = 0, distance = 0;
      nearest_on_segment(p.points_mm[i], p.points_mm[i + 1], position_mm, &t, &distance);
      // Nearer by more than a micrometre: a tie goes to the earlier point.
      if (!found || distance < best_distance - 0.001) {
        found = true;
        best_distance = distance;
        best_mm = p.at_mm[i] + t * (p.at_mm[i + 1] - p.at_mm[i]);
        best_piece = k;
        best_segment = i;
      }
    }
  }
  if (found && best_mm >= done_mm_) {
    done_mm_ = best_mm;
    cursor_piece_ = best_piece;
    cursor_segment_ = best_segment;
  }
  return done_mm_;
}

nlohmann::json JobPath::to_json() const {
  nlohmann::json pieces = nlohmann::json::array();
  for (const Piece& p : pieces_) {
    nlohmann::json points = nlohmann::json::array();
    for (const Point2& q : p.points_mm) points.push_back({um_rounded(q.x()), um_rounded(q.y())});
    pieces.push_back({{"pen_down", p.pen_down},
                      {"start_mm", um_rounded(p.start_mm)},
                      {"length_mm", um_rounded(p.at_mm.back() - p.start_mm)},
                      {"points_mm", std::move(points)}});
  }
  return {{"length_mm", um_rounded(length_mm_)}, {"pieces", std::move(pieces)}};
}

}  // namespace host::server
