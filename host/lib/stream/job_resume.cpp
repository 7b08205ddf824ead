// Resume point from the status, and the stream that continues a job from it.
#include "host/lib/stream/job_resume.h"

#include <fmt/format.h>  // fmt::format

#include "firmware/protocol/codec.h"         // proto::encode, proto::decode
#include "host/lib/plan/counted.h"           // counted: "1 point", "2 points"
#include "host/lib/plan/firmware_points.h"   // firmware_points_um
#include "host/lib/stream/encode_command.h"  // encode_command, decoded
#include "host/lib/stream/spline_frames.h"   // add_spline_data

namespace host {

namespace {

// The spline a #B and its data frames (#D, #K or #Q) carry, and the #B's tool offset.
core::Spline spline_of(const std::vector<QueuedCommand>& frames, int32_t* offset_um) {
  const proto::SplineHeaderCmd h = decoded<proto::SplineHeaderCmd>(frames.front());
  core::Spline sp{};
  sp.degree = h.degree;
  sp.rational = h.rational;
  sp.control_count = h.control_count;
  sp.knot_count = h.knot_count;
  *offset_um = h.tool_offset_um;
  for (size_t i = 1; i < frames.size(); ++i) {
    if (!add_spline_data(frames[i], &sp))
      throw PlanError("resume: the spline data after a job command does not decode");
  }
  return sp;
}

// The curve points the controller walks for a #B and its data frames (its #U chord tolerance).
std::vector<core::PointUm> curve_points(const std::vector<QueuedCommand>& frames,
                                        int tolerance_um) {
  int32_t offset_um = 0;
  const core::Spline sp = spline_of(frames, &offset_um);
  return firmware_points_um({sp}, tolerance_um, offset_um);
}

// Where a move command ends (the last curve point of a #B).
core::PointUm end_of_move(const std::vector<QueuedCommand>& frames, int tolerance_um) {
  const QueuedCommand& c = frames.front();
  if (c.letter == proto::kCmdRapidMove) {
    const auto m = decoded<proto::RapidMoveCmd>(c);
    return {m.x_um, m.y_um};
  }
  if (c.letter == proto::kCmdFeedMove) {
    const auto m = decoded<proto::FeedMoveCmd>(c);
    return {m.x_um, m.y_um};
  }
  if (c.letter == proto::kCmdDrill) {
    const auto m = decoded<proto::DrillCmd>(c);
    return {m.x_um, m.y_um};
  }
  const std::vector<core::PointUm> points = curve_points(frames, tolerance_um);
  return points.empty() ? core::PointUm{0, 0} : points.back();
}

// The commands that take the tool back to `at` and set the job up as it was there, ending
// with the #J that numbers job command at.job_index on (see resume_commands()).
std::vector<QueuedCommand> prefix_of(const ResumeScan& scan, const ResumePoint& at,
                                     const EncodeOptions& options) {
  std::vector<QueuedCommand> out;
  if (scan.resolution() != nullptr) out.push_back(*scan.resolution());
  // Always to the travel height, also from above it (after a restart Z is unknown until the
  // zeroing, which runs before this stream: never travel in X/Y at an unknown height).
  if (scan.travel_z_um() != INT32_MIN) {
    out.push_back(encode_command(proto::ZMoveCmd{scan.travel_z_um(), options.z_rapid_um_per_s}));
  }
  out.push_back(encode_command(proto::RapidMoveCmd{at.x_um, at.y_um}));
  // On again (every stop switched it off), then its run-up.
  out.insert(out.end(), scan.spindle_on().begin(), scan.spindle_on().end());
  // Pen down where it was, unless the command resumed sets the height itself.
  const uint8_t letter = scan.at().front().letter;
  const bool sets_height = letter == proto::kCmdZMove || letter == proto::kCmdDrill;
  const QueuedCommand* height = scan.height();
  if (!sets_height && height != nullptr && height->letter == proto::kCmdZMove) {
    const proto::ZMoveCmd z = decoded<proto::ZMoveCmd>(*height);
    if (z.z_um < scan.travel_z_um()) out.push_back(*height);
  }
  proto::JobMarkCmd mark{};
  mark.job_index = at.job_index;
  mark.first_point = letter == proto::kCmdSplineHeader ? at.curve_point : 0;
  mark.job_id = scan.job_id();
  out.push_back(encode_command(mark));
  return out;
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
    return fmt::format("resume at job command {}: its curve has {}, not {}", job_index,
                       counted(point_count, "point"), curve_point + 1);
  }
  return "";
}

ResumePoint resume_point_at(const JobPass& job, int32_t job_index, uint16_t curve_point,
                            int32_t tool_z_um) {
  return resume_point_at(ResumeScan(job, job_index), curve_point, tool_z_um);
}

ResumePoint resume_point_at(const ResumeScan& scan, uint16_t curve_point, int32_t tool_z_um) {
  const int32_t job_index = scan.job_index();
  if (!scan.found())
    throw PlanError(
        fmt::format("resume at job command {}: the job has no such command", job_index));
  ResumePoint at;
  at.job_index = job_index;
  at.curve_point = curve_point;
  at.started = curve_point > 0;
  at.z_um = tool_z_um;
  at.job_id = scan.job_id();
  if (scan.at().front().letter == proto::kCmdSplineHeader && curve_point > 0) {
    const std::vector<core::PointUm> points = curve_points(scan.at(), scan.at_tolerance_um());
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
  if (scan.last_move().empty()) return at;
  const core::PointUm end = end_of_move(scan.last_move(), scan.last_move_tolerance_um());
  at.x_um = end.x_um;
  at.y_um = end.y_um;
  return at;
}

ResumePoint resume_point_at(const std::vector<QueuedCommand>& job, int32_t job_index,
                            uint16_t curve_point, int32_t tool_z_um) {
  return resume_point_at(pass_over(job), job_index, curve_point, tool_z_um);
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

// Ids in decimal, as send's first line and run's report print them.
std::string resume_mismatch(uint16_t job_id, const ResumePoint& at) {
  if (job_id == at.job_id) return "";
  return fmt::format(
      "the controller's job (id {}) is not this one (id {}): resume with the same file "
      "and the same plan options as the interrupted send",
      at.job_id, job_id);
}

std::string resume_mismatch(const std::vector<QueuedCommand>& job, const ResumePoint& at) {
  return resume_mismatch(job_id_of(job), at);
}

size_t command_of_job_index(const std::vector<QueuedCommand>& job, int32_t job_index) {
  int32_t n = 0;
  for (size_t i = 0; i < job.size(); ++i) {
    if (proto::command_role(job[i].letter) != proto::CommandRole::kJobCommand) continue;
    if (n == job_index) return i;
    ++n;
  }
  return job.size();
}

std::vector<QueuedCommand> resume_prefix(const JobPass& job, const ResumePoint& at,
                                         const EncodeOptions& options, size_t* from) {
  const ResumeScan scan(job, at.job_index);
  *from = scan.from();
  if (!scan.found()) return {};
  return prefix_of(scan, at, options);
}

std::vector<QueuedCommand> resume_commands(const std::vector<QueuedCommand>& job,
                                           const ResumePoint& at, const EncodeOptions& options) {
  size_t from = 0;
  std::vector<QueuedCommand> out = resume_prefix(pass_over(job), at, options, &from);
  if (from < job.size()) out.insert(out.end(), job.begin() + static_cast<long>(from), job.end());
  return out;
}

int32_t job_index_of_curve(const JobPass& job, int curve) {
  int32_t index = 0;
  int32_t found = -1;
  job([&](const QueuedCommand& c) {
    if (found >= 0 || proto::command_role(c.letter) != proto::CommandRole::kJobCommand) return;
    if (c.curve == curve) found = index;
    ++index;
  });
  if (found < 0)
    throw PlanError(fmt::format("continue from curve {}: the job has no such curve", curve));
  return found;
}

std::vector<QueuedCommand> resume_from_curve(const std::vector<QueuedCommand>& job, int first_curve,
                                             const EncodeOptions& options) {
  const int32_t index = job_index_of_curve(pass_over(job), first_curve);
  return resume_commands(job, resume_point_at(job, index, 0, 0), options);
}

std::string describe_resume_point(const JobPass& job, const ResumePoint& at) {
  const ResumeScan scan(job, at.job_index);
  if (!scan.found())
    return fmt::format("job command {} of {}: the job has finished", at.job_index,
                       scan.job_commands());
  const QueuedCommand& c = scan.at().front();
  std::string s =
      fmt::format("job command {} of {} ('{}' {}", at.job_index, scan.job_commands(),
                  static_cast<char>(c.letter), proto::message_name(proto::kCommandStart, c.letter));
  if (c.step >= 0) s += fmt::format(", plan step {}", c.step);
  if (c.curve >= 0) s += fmt::format(", curve {}", c.curve);
  s += ")";
  if (c.letter == proto::kCmdSplineHeader && at.curve_point > 0)
    s += fmt::format(", from curve point {}", at.curve_point);
  if (at.started) s += ", cut short";
  return s;
}

std::string describe_resume_point(const std::vector<QueuedCommand>& job, const ResumePoint& at) {
  return describe_resume_point(pass_over(job), at);
}

}  // namespace host
