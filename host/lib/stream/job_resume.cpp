// Resume point from the status, and the stream that continues a job from it.
#include "host/lib/stream/job_resume.h"

#include <fmt/format.h>  // fmt::format

#include "firmware/core/curve_walker.h"      // kDefaultChordToleranceUm
#include "firmware/protocol/codec.h"         // proto::encode, proto::decode
#include "host/lib/plan/firmware_points.h"   // firmware_points_um
#include "host/lib/stream/encode_command.h"  // encode_command
#include "host/lib/stream/spline_frames.h"   // is_spline_data, add_spline_data

namespace host {

namespace {

bool is_job_command(const QueuedCommand& c) {
  return proto::command_role(c.letter) == proto::CommandRole::kJobCommand;
}

template <typename Msg>
Msg decoded(const QueuedCommand& c) {
  Msg m{};
  proto::decode(c.payload.data(), static_cast<uint8_t>(c.payload.size()), &m);
  return m;
}

// The spline a #B at job[b] and its data frames (#D or #K) carry, and the #B's tool offset.
core::Spline spline_at(const std::vector<QueuedCommand>& job, size_t b, int32_t* offset_um) {
  const proto::SplineHeaderCmd h = decoded<proto::SplineHeaderCmd>(job[b]);
  core::Spline sp{};
  sp.degree = h.degree;
  sp.rational = h.rational;
  sp.control_count = h.control_count;
  sp.knot_count = h.knot_count;
  *offset_um = h.tool_offset_um;
  for (size_t i = b + 1; i < job.size() && is_spline_data(job[i].letter); ++i) {
    if (!add_spline_data(job[i], &sp))
      throw PlanError(
          fmt::format("resume: the spline data after job command {} does not decode", b));
  }
  return sp;
}

// The curve points the controller walks for the #B at job[b] (its #U chord tolerance).
std::vector<core::PointUm> curve_points(const std::vector<QueuedCommand>& job, size_t b) {
  int tolerance_um = core::kDefaultChordToleranceUm;
  for (size_t i = 0; i < b; ++i) {
    if (job[i].letter == proto::kCmdResolution)
      tolerance_um = decoded<proto::ResolutionCmd>(job[i]).chord_tolerance_um;
  }
  int32_t offset_um = 0;
  const core::Spline sp = spline_at(job, b, &offset_um);
  return firmware_points_um({sp}, tolerance_um, offset_um);
}

}  // namespace

std::string curve_point_problem(int32_t job_index, size_t point_count, uint16_t curve_point) {
  if (curve_point == 0xFFFF && point_count > 0x10000) {
    return fmt::format(
        "resume at job command {}: its curve has {} points and the controller counts only "
        "65 535, so where the tool stopped on it is not known; resume from the curve's start "
        "with --resume-at {}:0 (that curve is cut again up to where it stopped)",
        job_index, point_count, job_index);
  }
  if (curve_point >= point_count) {
    return fmt::format("resume at job command {}: its curve has {} points, not {}", job_index,
                       point_count, curve_point + 1);
  }
  return "";
}

ResumePoint resume_point_at(const std::vector<QueuedCommand>& job, int32_t job_index,
                            uint16_t curve_point, int32_t tool_z_um) {
  const size_t from = command_of_job_index(job, job_index);
  if (from >= job.size())
    throw PlanError(
        fmt::format("resume at job command {}: the job has no such command", job_index));
  ResumePoint at;
  at.job_index = job_index;
  at.curve_point = curve_point;
  at.started = curve_point > 0;
  at.z_um = tool_z_um;
  at.job_id = job_id_of(job);
  if (job[from].letter == proto::kCmdSplineHeader && curve_point > 0) {
    const std::vector<core::PointUm> points = curve_points(job, from);
    const std::string problem = curve_point_problem(job_index, points.size(), curve_point);
    if (!problem.empty()) throw PlanError(problem);
    // From the last point reached: the chord to curve_point is cut whole.
    at.curve_point = static_cast<uint16_t>(curve_point - 1);
    at.x_um = points[curve_point - 1].x_um;
    at.y_um = points[curve_point - 1].y_um;
    return at;
  }
  at.curve_point = 0;
  // Where the previous move of the job ended (plans start at the zero point).
  size_t last_move = job.size();
  for (size_t i = 0; i < from; ++i) {
    const uint8_t l = job[i].letter;
    if (l == proto::kCmdRapidMove || l == proto::kCmdFeedMove || l == proto::kCmdDrill ||
        l == proto::kCmdSplineHeader)
      last_move = i;
  }
  if (last_move == job.size()) return at;
  const QueuedCommand& c = job[last_move];
  if (c.letter == proto::kCmdRapidMove) {
    const auto m = decoded<proto::RapidMoveCmd>(c);
    at.x_um = m.x_um;
    at.y_um = m.y_um;
  } else if (c.letter == proto::kCmdFeedMove) {
    const auto m = decoded<proto::FeedMoveCmd>(c);
    at.x_um = m.x_um;
    at.y_um = m.y_um;
  } else if (c.letter == proto::kCmdDrill) {
    const auto m = decoded<proto::DrillCmd>(c);
    at.x_um = m.x_um;
    at.y_um = m.y_um;
  } else {
    const std::vector<core::PointUm> points = curve_points(job, last_move);
    if (!points.empty()) {
      at.x_um = points.back().x_um;
      at.y_um = points.back().y_um;
    }
  }
  return at;
}

std::optional<ResumePoint> resume_point_of(const proto::StatusReply& status) {
  if (!(status.flags & proto::kStatusJob)) return std::nullopt;
  ResumePoint p;
  p.job_index = status.job_index;
  p.curve_point = status.curve_point;
  p.started = (status.flags & proto::kStatusJobStarted) != 0;
  p.job_id = status.job_id;
  p.x_um = status.x_um;
  p.y_um = status.y_um;
  p.z_um = status.z_um;
  return p;
}

std::string resume_mismatch(const std::vector<QueuedCommand>& job, const ResumePoint& at) {
  const uint16_t id = job_id_of(job);
  if (id == at.job_id) return "";
  return fmt::format(
      "the controller's job (id {:04X}) is not this one (id {:04X}): resume with the same file "
      "and the same plan options as the interrupted send",
      at.job_id, id);
}

size_t command_of_job_index(const std::vector<QueuedCommand>& job, int32_t job_index) {
  int32_t n = 0;
  for (size_t i = 0; i < job.size(); ++i) {
    if (!is_job_command(job[i])) continue;
    if (n == job_index) return i;
    ++n;
  }
  return job.size();
}

std::vector<QueuedCommand> resume_commands(const std::vector<QueuedCommand>& job,
                                           const ResumePoint& at, const EncodeOptions& options) {
  const size_t from = command_of_job_index(job, at.job_index);
  std::vector<QueuedCommand> out;
  if (from >= job.size()) return out;

  // What the job had set up before `from`: resolution, spindle, the tool's height.
  const QueuedCommand* resolution = nullptr;
  size_t spindle_at = job.size();         // the #N that switched the spindle on, if it is still on
  const QueuedCommand* height = nullptr;  // the newest #Z or #L before `from`
  int32_t travel_z_um = INT32_MIN;        // the job's pen-up height: its highest #Z
  for (size_t i = 0; i < job.size(); ++i) {
    const QueuedCommand& c = job[i];
    if (c.letter == proto::kCmdZMove)
      travel_z_um = std::max(travel_z_um, decoded<proto::ZMoveCmd>(c).z_um);
    if (i >= from) continue;
    if (c.letter == proto::kCmdResolution) resolution = &c;
    if (c.letter == proto::kCmdSpindle)
      spindle_at = decoded<proto::SpindleCmd>(c).on ? i : job.size();
    if (c.letter == proto::kCmdZMove || c.letter == proto::kCmdDrill) height = &c;
  }
  if (resolution != nullptr) out.push_back(*resolution);
  // Always to the travel height, also from above it (after a restart Z is unknown until the
  // zeroing, which runs before this stream: never travel in X/Y at an unknown height).
  if (travel_z_um != INT32_MIN) {
    out.push_back(encode_command(proto::ZMoveCmd{travel_z_um, options.z_rapid_um_per_s}));
  }
  out.push_back(encode_command(proto::RapidMoveCmd{at.x_um, at.y_um}));
  if (spindle_at < job.size()) {
    out.push_back(job[spindle_at]);  // on again (every stop switched it off), then its run-up
    for (size_t i = spindle_at + 1; i < from && job[i].letter == proto::kCmdDwell; ++i)
      out.push_back(job[i]);
  }
  // Pen down where it was, unless the command resumed sets the height itself.
  const bool sets_height =
      job[from].letter == proto::kCmdZMove || job[from].letter == proto::kCmdDrill;
  if (!sets_height && height != nullptr && height->letter == proto::kCmdZMove) {
    const proto::ZMoveCmd z = decoded<proto::ZMoveCmd>(*height);
    if (z.z_um < travel_z_um) out.push_back(*height);  // pen down where it was
  }
  proto::JobMarkCmd mark{};
  mark.job_index = at.job_index;
  mark.first_point = job[from].letter == proto::kCmdSplineHeader ? at.curve_point : 0;
  mark.job_id = job_id_of(job);
  out.push_back(encode_command(mark));
  out.insert(out.end(), job.begin() + static_cast<long>(from), job.end());
  return out;
}

std::vector<QueuedCommand> resume_from_curve(const std::vector<QueuedCommand>& job, int first_curve,
                                             const EncodeOptions& options) {
  int32_t index = 0;
  for (const QueuedCommand& c : job) {
    if (!is_job_command(c)) continue;
    if (c.curve == first_curve) {
      return resume_commands(job, resume_point_at(job, index, 0, 0), options);
    }
    ++index;
  }
  throw PlanError(fmt::format("continue from curve {}: the job has no such curve", first_curve));
}

std::string describe_resume_point(const std::vector<QueuedCommand>& job, const ResumePoint& at) {
  int32_t total = 0;
  for (const QueuedCommand& c : job) total += is_job_command(c) ? 1 : 0;
  const size_t from = command_of_job_index(job, at.job_index);
  if (from >= job.size())
    return fmt::format("job command {} of {}: the job has finished", at.job_index, total);
  const QueuedCommand& c = job[from];
  std::string s =
      fmt::format("job command {} of {} ('{}' {}", at.job_index, total, static_cast<char>(c.letter),
                  proto::message_name(proto::kCommandStart, c.letter));
  if (c.step >= 0) s += fmt::format(", plan step {}", c.step);
  if (c.curve >= 0) s += fmt::format(", curve {}", c.curve);
  s += ")";
  if (c.letter == proto::kCmdSplineHeader && at.curve_point > 0)
    s += fmt::format(", from curve point {}", at.curve_point);
  if (at.started) s += ", cut short";
  return s;
}

}  // namespace host
