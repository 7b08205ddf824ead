// Resume point from the status, and the stream that continues a job from it.
#include "host/lib/stream/job_resume.h"

#include <fmt/format.h>  // fmt::format

#include "firmware/protocol/codec.h"  // proto::encode, proto::decode

namespace host {

namespace {

bool is_job_command(const QueuedCommand& c) {
  return c.letter != proto::kCmdSplineData && c.letter != proto::kCmdJobMark;
}

template <typename Msg>
QueuedCommand command_of(const Msg& msg) {
  proto::Payload payload;
  if (proto::encode(msg, &payload) != proto::ErrorCode::kOk) {
    throw PlanError(fmt::format("resume: command '{}' has a field out of range",
                                static_cast<char>(Msg::kLetter)));
  }
  QueuedCommand c;
  c.letter = static_cast<uint8_t>(Msg::kLetter);
  c.payload.assign(payload.bytes, payload.bytes + payload.length);
  return c;
}

template <typename Msg>
Msg decoded(const QueuedCommand& c) {
  Msg m{};
  proto::decode(c.payload.data(), static_cast<uint8_t>(c.payload.size()), &m);
  return m;
}

}  // namespace

std::optional<ResumePoint> resume_point_of(const proto::StatusReply& status) {
  if (!(status.flags & proto::kStatusJob)) return std::nullopt;
  ResumePoint p;
  p.job_index = status.job_index;
  p.curve_point = status.curve_point;
  p.started = (status.flags & proto::kStatusJobStarted) != 0;
  p.x_um = status.x_um;
  p.y_um = status.y_um;
  p.z_um = status.z_um;
  return p;
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
  if (travel_z_um != INT32_MIN && at.z_um < travel_z_um) {
    out.push_back(command_of(proto::ZMoveCmd{travel_z_um, options.z_rapid_um_per_s}));
  }
  out.push_back(command_of(proto::RapidMoveCmd{at.x_um, at.y_um}));
  if (spindle_at < job.size()) {
    out.push_back(job[spindle_at]);  // on again (every stop switched it off), then its run-up
    for (size_t i = spindle_at + 1; i < from && job[i].letter == proto::kCmdDwell; ++i)
      out.push_back(job[i]);
  }
  if (height != nullptr && height->letter == proto::kCmdZMove) {
    const proto::ZMoveCmd z = decoded<proto::ZMoveCmd>(*height);
    if (z.z_um < travel_z_um) out.push_back(*height);  // pen down where it was
  }
  proto::JobMarkCmd mark{};
  mark.job_index = at.job_index;
  mark.first_point = job[from].letter == proto::kCmdSplineHeader ? at.curve_point : 0;
  out.push_back(command_of(mark));
  out.insert(out.end(), job.begin() + static_cast<long>(from), job.end());
  return out;
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
