// Job plan -> queued protocol commands (#J #S #U #Z #F #G #B #D #P #W #N #L), using the shared
// codecs.
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/spline_frames.h"  // append_spline_data

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::min

#include "firmware/protocol/codec.h"         // proto::encode, message structs
#include "firmware/protocol/crc16.h"         // proto::crc16_update
#include "host/lib/stream/encode_command.h"  // encode_command

namespace host {

namespace {

// A feed in um/s as the u16 the protocol carries, or PlanError.
uint16_t feed16(int32_t feed_um_per_s, int step) {
  if (feed_um_per_s < 1 || feed_um_per_s > 65535) {
    throw PlanError(fmt::format("step {}: feed {} um/s outside 1..65535", step, feed_um_per_s));
  }
  return static_cast<uint16_t>(feed_um_per_s);
}

// #B then the data frames (#K compact, or #D) carrying the spline's control points, then
// its knots.
void append_spline(const PlanStep& s, int index, unsigned max_payload, SplineFrames encoding,
                   std::vector<QueuedCommand>* out) {
  proto::SplineHeaderCmd header{};
  header.degree = s.spline().degree;
  header.rational = s.spline().rational;
  const size_t control_count = s.spline().control.size();
  const size_t knot_count = s.spline().knot.size();
  header.control_count = static_cast<uint16_t>(control_count);
  header.knot_count = static_cast<uint16_t>(knot_count);
  header.feed_um_per_s = feed16(s.feed_um_per_s, index);
  header.tool_offset_um = s.tool_offset_um;
  out->push_back(encode_command(header, index, s.curve));
  append_spline_data(s.spline().firmware(), index, s.curve, max_payload, encoding, out);
}

// #P with the operator message: the LCD row holds 16 characters, the rest is cut; characters
// the LCD cannot show become '?'.
proto::PauseCmd pause_command(const std::string& text) {
  proto::PauseCmd pause{};
  pause.length = static_cast<uint8_t>(std::min<size_t>(text.size(), proto::kLcdColumns));
  for (uint8_t i = 0; i < pause.length; ++i) {
    const char ch = text[i];
    pause.text[i] = (ch >= 0x20 && ch <= 0x7E) ? ch : '?';
  }
  return pause;
}

// A coordinate the controller would refuse with kOutOfTravel, as a PlanError naming the step.
void check_travel(int32_t um, int32_t travel_um, char axis, int step) {
  if (um < -travel_um || um > travel_um) {
    throw PlanError(
        fmt::format("step {}: {} {:.3f} mm is outside the controller's {} travel of +-{:.3f} mm",
                    step, axis, um / 1000.0, axis, travel_um / 1000.0));
  }
}

void check_step_fits(const PlanStep& s, const proto::SessionReply& c, int step) {
  switch (s.kind) {
    case PlanStep::kPenUp:
    case PlanStep::kPenDown:
      check_travel(s.z_um, c.travel_z_um, 'Z', step);
      break;
    case PlanStep::kRapid:
    case PlanStep::kFeed:
      check_travel(s.to.x_um, c.travel_x_um, 'X', step);
      check_travel(s.to.y_um, c.travel_y_um, 'Y', step);
      break;
    case PlanStep::kSpline:
      for (const core::ControlPoint& p : s.spline().control) {
        check_travel(p.x_um, c.travel_x_um, 'X', step);
        check_travel(p.y_um, c.travel_y_um, 'Y', step);
      }
      break;
    case PlanStep::kDrill:
      check_travel(s.to.x_um, c.travel_x_um, 'X', step);
      check_travel(s.to.y_um, c.travel_y_um, 'Y', step);
      check_travel(s.z_start_um, c.travel_z_um, 'Z', step);
      check_travel(s.z_um, c.travel_z_um, 'Z', step);
      break;
    default:
      break;
  }
}

// A degree-1 spline from a to b (two control points, clamped knots).
core::Spline straight_spline(const core::PointUm& a, const core::PointUm& b) {
  core::Spline s{};
  s.degree = 1;
  s.rational = false;
  s.control_count = 2;
  s.knot_count = 4;
  s.control[0] = {a.x_um, a.y_um, core::kWeightOneQ14};
  s.control[1] = {b.x_um, b.y_um, core::kWeightOneQ14};
  s.knot[0] = s.knot[1] = 0;
  s.knot[2] = s.knot[3] = 1000;
  return s;
}

}  // namespace

void use_session(const proto::SessionReply& caps, EncodeOptions* o) {
  o->max_payload = caps.max_payload;
  o->z_rapid_um_per_s = caps.max_feed_z_um_per_s;
  if (caps.protocol_version < proto::kContourFramesVersion && o->splines == SplineFrames::kContour)
    o->splines = SplineFrames::kCompact;
}

JobEncoder::JobEncoder(const JobPlan& plan, const EncodeOptions& options, uint16_t job_id)
    : plan_(plan), options_(options), job_id_(job_id) {
  if (options.max_payload < 16) {
    throw PlanError(fmt::format("controller payload {} bytes is too small", options.max_payload));
  }
}

void JobEncoder::append_preamble(std::vector<QueuedCommand>* out) const {
  // Job numbering from here (the controller reports progress by it; send --resume).
  out->push_back(encode_command(proto::JobMarkCmd{0, 0, job_id_}, -1, -1));
  if (!options_.title.empty()) {
    proto::TextCmd text{};
    text.row = 0;
    text.length = static_cast<uint8_t>(std::min<size_t>(options_.title.size(), proto::kLcdColumns));
    for (uint8_t i = 0; i < text.length; ++i) {
      const char ch = options_.title[i];
      text.text[i] = (ch >= 0x20 && ch <= 0x7E) ? ch : '?';
    }
    out->push_back(encode_command(text, -1, -1));
  }
  proto::ResolutionCmd resolution{};
  resolution.max_step_um = options_.max_step_um;
  resolution.chord_tolerance_um = options_.chord_tolerance_um;
  out->push_back(encode_command(resolution, -1, -1));
}

bool JobEncoder::next(std::vector<QueuedCommand>* out) {
  if (!started_) {
    started_ = true;
    append_preamble(out);
    return true;
  }
  if (step_ >= plan_.steps.size()) return false;
  const EncodeOptions& options = options_;
  const PlanStep& s = plan_.steps[step_];
  const int index = static_cast<int>(step_);
  ++step_;
  if (options.controller != nullptr) check_step_fits(s, *options.controller, index);
  const core::PointUm from = at_;
  if (s.kind == PlanStep::kRapid || s.kind == PlanStep::kFeed || s.kind == PlanStep::kSpline ||
      s.kind == PlanStep::kDrill)
    at_ = s.to;
  switch (s.kind) {
    case PlanStep::kPenUp: {
      proto::ZMoveCmd z{s.z_um, options.z_rapid_um_per_s};
      out->push_back(encode_command(z, index, s.curve));
      break;
    }
    case PlanStep::kPenDown: {
      proto::ZMoveCmd z{s.z_um, feed16(s.feed_um_per_s, index)};
      out->push_back(encode_command(z, index, s.curve));
      break;
    }
    case PlanStep::kRapid: {
      proto::RapidMoveCmd r{s.to.x_um, s.to.y_um};
      out->push_back(encode_command(r, index, s.curve));
      break;
    }
    case PlanStep::kFeed: {
      if (s.tool_offset_um != 0) {
        // The controller offsets curves only: a straight line with an offset goes as a
        // degree-1 spline from where the tool is.
        PlanStep line = s;
        line.set_spline(StepSpline(straight_spline(from, s.to)));
        append_spline(line, index, options.max_payload, options.splines, out);
        break;
      }
      proto::FeedMoveCmd g{s.to.x_um, s.to.y_um, feed16(s.feed_um_per_s, index)};
      out->push_back(encode_command(g, index, s.curve));
      break;
    }
    case PlanStep::kSpline:
      append_spline(s, index, options.max_payload, options.splines, out);
      break;
    case PlanStep::kPause:
      out->push_back(encode_command(pause_command(s.text()), index, s.curve));
      break;
    case PlanStep::kDwell:
      // Longer than one #W can carry: several in a row (nothing happens between them).
      for (uint32_t left = s.dwell_ms; left > 0;) {
        const uint16_t ms = static_cast<uint16_t>(std::min<uint32_t>(left, 65535));
        out->push_back(encode_command(proto::DwellCmd{ms}, index, s.curve));
        left -= ms;
      }
      break;
    case PlanStep::kSpindle:
      out->push_back(encode_command(proto::SpindleCmd{static_cast<uint8_t>(s.spindle_on ? 1 : 0)},
                                    index, s.curve));
      break;
    case PlanStep::kDrill: {
      if (s.z_um >= s.z_start_um) {
        throw PlanError(fmt::format("step {}: drill bottom Z {} um is not below its start {} um",
                                    index, s.z_um, s.z_start_um));
      }
      const proto::DrillCmd d{s.to.x_um, s.to.y_um, s.z_start_um, s.z_um,
                              feed16(s.feed_um_per_s, index)};
      out->push_back(encode_command(d, index, s.curve));
      break;
    }
  }
  return true;
}

EncodedJobSummary summarize_job(const JobPlan& plan, const EncodeOptions& options) {
  EncodedJobSummary sum;
  JobEncoder encoder(plan, options, 0);
  std::vector<QueuedCommand> batch;
  uint16_t crc = 0xFFFF;
  while (encoder.next(&batch)) {
    for (const QueuedCommand& c : batch) {
      sum.commands++;
      if (proto::command_role(c.letter) == proto::CommandRole::kJobCommand) sum.job_commands++;
      sum.wire_bytes += frame_bytes(c);
      crc = job_crc_update(crc, c);
    }
    batch.clear();
  }
  sum.job_id = crc;
  return sum;
}

std::vector<QueuedCommand> encode_job(const JobPlan& plan, const EncodeOptions& options) {
  std::vector<QueuedCommand> out;
  // At least one command per step: a million feeds then grow no copy of the list.
  out.reserve(plan.steps.size() + 8);
  JobEncoder encoder(plan, options, 0);  // its job_id is set at the end
  while (encoder.next(&out)) {
  }
  out.front() = encode_command(proto::JobMarkCmd{0, 0, job_id_of(out)}, -1, -1);
  return out;
}

uint16_t job_crc_update(uint16_t crc, const QueuedCommand& c) {
  if (c.letter == proto::kCmdJobMark) return crc;
  crc = proto::crc16_update(crc, c.letter);
  for (uint8_t b : c.payload) crc = proto::crc16_update(crc, b);
  return crc;
}

uint16_t job_id_of(const std::vector<QueuedCommand>& commands) {
  uint16_t crc = 0xFFFF;
  for (const QueuedCommand& c : commands) crc = job_crc_update(crc, c);
  return crc;
}

size_t frame_bytes(const QueuedCommand& command) {
  return proto::kHeaderBytes + command.payload.size() + proto::kCrcBytes;
}

size_t wire_bytes(const std::vector<QueuedCommand>& commands) {
  size_t total = 0;
  for (const QueuedCommand& c : commands) total += frame_bytes(c);
  return total;
}

}  // namespace host
