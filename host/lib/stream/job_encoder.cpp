// Job plan -> queued protocol commands (#S #U #Z #F #G #B #D), using the shared codecs.
#include "host/lib/stream/job_encoder.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::min

#include "firmware/protocol/codec.h"  // proto::encode, message structs

namespace host {

namespace {

// Encodes one message into a queued command or throws PlanError with the codec's verdict.
template <typename Msg>
QueuedCommand make(const Msg& msg, int step, int curve) {
  proto::Payload payload;
  const proto::ErrorCode error = proto::encode(msg, &payload);
  if (error != proto::ErrorCode::kOk) {
    throw PlanError(fmt::format("step {}: command '{}' has a field out of range (code {})", step,
                                static_cast<char>(Msg::kLetter), static_cast<int>(error)));
  }
  QueuedCommand c;
  c.letter = static_cast<uint8_t>(Msg::kLetter);
  c.payload.assign(payload.bytes, payload.bytes + payload.length);
  c.step = step;
  c.curve = curve;
  return c;
}

// A feed in um/s as the u16 the protocol carries, or PlanError.
uint16_t feed16(int32_t feed_um_per_s, int step) {
  if (feed_um_per_s < 1 || feed_um_per_s > 65535) {
    throw PlanError(fmt::format("step {}: feed {} um/s outside 1..65535", step, feed_um_per_s));
  }
  return static_cast<uint16_t>(feed_um_per_s);
}

// #B then #D frames carrying the spline's control points, then its knots.
void append_spline(const PlanStep& s, int index, unsigned max_payload,
                   std::vector<QueuedCommand>* out) {
  proto::SplineHeaderCmd header{};
  header.degree = s.spline.degree;
  header.rational = s.spline.rational;
  header.control_count = s.spline.control_count;
  header.knot_count = s.spline.knot_count;
  header.feed_um_per_s = feed16(s.feed_um_per_s, index);
  out->push_back(make(header, index, s.curve));

  const unsigned room =
      std::min<unsigned>(max_payload, proto::kMaxPayload) - proto::kSplineDataHeaderBytes;
  unsigned next_control = 0;
  unsigned next_knot = 0;
  while (next_control < s.spline.control_count || next_knot < s.spline.knot_count) {
    proto::SplineDataCmd data{};
    data.control_index = static_cast<uint8_t>(next_control);
    data.knot_index = static_cast<uint8_t>(next_knot);
    unsigned left = room;
    while (next_control < s.spline.control_count && data.control_n < proto::kMaxDataControls &&
           left >= proto::kControlPointBytes) {
      data.control[data.control_n++] = s.spline.control[next_control++];
      left -= proto::kControlPointBytes;
    }
    while (next_control == s.spline.control_count && next_knot < s.spline.knot_count &&
           data.knot_n < proto::kMaxDataKnots && left >= proto::kKnotBytes) {
      data.knot[data.knot_n++] = s.spline.knot[next_knot++];
      left -= proto::kKnotBytes;
    }
    out->push_back(make(data, index, s.curve));
  }
}

}  // namespace

std::vector<QueuedCommand> encode_job(const JobPlan& plan, const EncodeOptions& options) {
  if (options.max_payload < 16) {
    throw PlanError(fmt::format("controller payload {} bytes is too small", options.max_payload));
  }
  std::vector<QueuedCommand> out;
  if (!options.title.empty()) {
    proto::TextCmd text{};
    text.row = 0;
    text.length = static_cast<uint8_t>(std::min<size_t>(options.title.size(), proto::kLcdColumns));
    for (uint8_t i = 0; i < text.length; ++i) {
      const char ch = options.title[i];
      text.text[i] = (ch >= 0x20 && ch <= 0x7E) ? ch : '?';
    }
    out.push_back(make(text, -1, -1));
  }
  proto::ResolutionCmd resolution{};
  resolution.max_step_um = options.max_step_um;
  resolution.chord_tolerance_um = options.chord_tolerance_um;
  out.push_back(make(resolution, -1, -1));

  for (size_t i = 0; i < plan.steps.size(); ++i) {
    const PlanStep& s = plan.steps[i];
    const int index = static_cast<int>(i);
    if (s.tool_offset_um != 0) {
      throw PlanError(
          fmt::format("step {}: tool-radius offset is not in protocol v1; plan with "
                      "the tool centre on the line",
                      index));
    }
    switch (s.kind) {
      case PlanStep::kPenUp: {
        proto::ZMoveCmd z{s.z_um, options.z_rapid_um_per_s};
        out.push_back(make(z, index, s.curve));
        break;
      }
      case PlanStep::kPenDown: {
        proto::ZMoveCmd z{s.z_um, feed16(s.feed_um_per_s, index)};
        out.push_back(make(z, index, s.curve));
        break;
      }
      case PlanStep::kRapid: {
        proto::RapidMoveCmd r{s.to.x_um, s.to.y_um};
        out.push_back(make(r, index, s.curve));
        break;
      }
      case PlanStep::kFeed: {
        proto::FeedMoveCmd g{s.to.x_um, s.to.y_um, feed16(s.feed_um_per_s, index)};
        out.push_back(make(g, index, s.curve));
        break;
      }
      case PlanStep::kSpline:
        append_spline(s, index, options.max_payload, &out);
        break;
      case PlanStep::kPause:
      case PlanStep::kDwell:
      case PlanStep::kSpindle:
      case PlanStep::kDrill:
        throw PlanError(fmt::format(
            "step {}: pause, dwell, spindle and drill steps are not in protocol v1", index));
    }
  }
  return out;
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
