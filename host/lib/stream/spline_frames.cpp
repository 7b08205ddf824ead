// Spline data frames, #K or #D (see spline_frames.h).
#include "host/lib/stream/spline_frames.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::min, std::copy

#include "firmware/protocol/codec.h"           // proto::encode, proto::decode
#include "firmware/protocol/compact_spline.h"  // put_compact_point, unpack_compact
#include "firmware/protocol/contour_spline.h"  // put_contour_element, unpack_contour
#include "host/lib/plan/contour_form.h"        // contour_elements
#include "host/lib/stream/encode_command.h"    // encode_command

namespace host {

namespace {

// Data bytes of a frame with this header in the controller's payload size.
unsigned data_room(unsigned max_payload, unsigned header_bytes) {
  return std::min<unsigned>(max_payload, proto::kMaxPayload) - header_bytes;
}

// One #D frame: control points from *next_control, then knots from *next_knot once every
// control point is in, as many as room bytes hold.
proto::SplineDataCmd full_data(const core::Spline& sp, unsigned room, unsigned* next_control,
                               unsigned* next_knot) {
  proto::SplineDataCmd data{};
  data.control_index = static_cast<uint8_t>(*next_control);
  data.knot_index = static_cast<uint8_t>(*next_knot);
  unsigned left = room;
  while (*next_control < sp.control_count && data.control_n < proto::kMaxDataControls &&
         left >= proto::kControlPointBytes) {
    data.control[data.control_n++] = sp.control[(*next_control)++];
    left -= proto::kControlPointBytes;
  }
  while (*next_control == sp.control_count && *next_knot < sp.knot_count &&
         data.knot_n < proto::kMaxDataKnots && left >= proto::kKnotBytes) {
    data.knot[data.knot_n++] = sp.knot[(*next_knot)++];
    left -= proto::kKnotBytes;
  }
  return data;
}

// #K frames: points as differences, knots as spans (firmware/protocol/compact_spline.h),
// each frame as full as the payload allows. Knots that repeat share one code. Every point
// fits (variable length); a knot span of 2^31 or more does not, and goes in a #D frame.
void append_compact_data(const core::Spline& sp, int index, int curve, unsigned max_payload,
                         std::vector<QueuedCommand>* out) {
  const unsigned room = data_room(max_payload, proto::kCompactHeaderBytes);
  unsigned next_control = 0;
  unsigned next_knot = 0;
  uint8_t value[proto::kMaxCompactPointBytes];
  while (next_control < sp.control_count || next_knot < sp.knot_count) {
    proto::SplineCompactCmd d{};
    d.control_index = static_cast<uint8_t>(next_control);
    d.knot_index = static_cast<uint8_t>(next_knot);
    auto fits = [&](uint8_t n) { return d.data_n + n <= room; };
    while (next_control < sp.control_count && d.control_n < proto::kMaxCompactControls) {
      core::ControlPoint prev = {0, 0, core::kWeightOneQ14};
      if (next_control > 0) prev = sp.control[next_control - 1];
      const uint8_t n =
          proto::put_compact_point(prev, sp.control[next_control], sp.rational, value);
      if (!fits(n)) break;
      std::copy(value, value + n, d.data + d.data_n);
      d.data_n = static_cast<uint8_t>(d.data_n + n);
      ++d.control_n;
      ++next_control;
    }
    bool wide = false;  // a knot span over kMaxCompactSpan: the knots go in a #D frame
    while (next_control == sp.control_count && next_knot < sp.knot_count &&
           d.knot_n < proto::kMaxCompactKnots) {
      const bool first = next_knot == 0;
      const int32_t prev = first ? 0 : sp.knot[next_knot - 1];
      const int32_t k = sp.knot[next_knot];
      if (!first && k < prev) throw PlanError(fmt::format("step {}: spline knots decrease", index));
      const bool repeat = !first && next_knot + 1 < sp.knot_count && sp.knot[next_knot + 1] == k &&
                          d.knot_n + 2 <= proto::kMaxCompactKnots;
      const uint8_t n = proto::put_compact_knot(prev, k, first, repeat, value);
      if (n == 0) {
        wide = true;
        break;
      }
      if (!fits(n)) break;
      std::copy(value, value + n, d.data + d.data_n);
      d.data_n = static_cast<uint8_t>(d.data_n + n);
      d.knot_n = static_cast<uint8_t>(d.knot_n + (repeat ? 2 : 1));
      next_knot += repeat ? 2 : 1;
    }
    if (d.data_n > 0) out->push_back(encode_command(d, index, curve));
    if (wide) {
      const unsigned full_room = data_room(max_payload, proto::kSplineDataHeaderBytes);
      out->push_back(
          encode_command(full_data(sp, full_room, &next_control, &next_knot), index, curve));
    } else if (d.data_n == 0) {
      // Not reached: a point takes at most 11 bytes, a knot 5, and a payload 12 at least.
      throw PlanError(fmt::format("step {}: a spline value does not fit a #K frame", index));
    }
  }
}

// #Q frames: the first point, then each element as its end point (and an arc's height),
// each frame as full as the payload allows.
void append_contour_data(const core::Spline& sp, const std::vector<proto::ContourElement>& elements,
                         int index, int curve, unsigned max_payload,
                         std::vector<QueuedCommand>* out) {
  const unsigned room = data_room(max_payload, proto::kContourHeaderBytes);
  uint8_t value[proto::kMaxContourElementBytes];
  size_t next = 0;
  bool first = true;
  while (first || next < elements.size()) {
    proto::SplineContourCmd d{};
    d.control_index = static_cast<uint8_t>(first ? 0 : 1 + 2 * next);
    if (first) {
      d.data_n = proto::put_contour_start(sp.control[0].x_um, sp.control[0].y_um, d.data);
      d.control_n = 1;
      first = false;
    }
    while (next < elements.size()) {
      const uint8_t n = proto::put_contour_element(elements[next], value);
      if (d.data_n + n > room) break;
      std::copy(value, value + n, d.data + d.data_n);
      d.data_n = static_cast<uint8_t>(d.data_n + n);
      d.control_n = static_cast<uint8_t>(d.control_n + 2);
      ++next;
    }
    // Not reached: an element takes at most 9 bytes (arcs are short), a payload 14 at least.
    if (d.control_n == 0)
      throw PlanError(fmt::format("step {}: a contour element does not fit a #Q frame", index));
    out->push_back(encode_command(d, index, curve));
  }
}

}  // namespace

void append_spline_data(const core::Spline& sp, int step, int curve, unsigned max_payload,
                        SplineFrames encoding, std::vector<QueuedCommand>* out) {
  if (encoding == SplineFrames::kContour) {
    if (const auto elements = contour_elements(sp)) {
      append_contour_data(sp, *elements, step, curve, max_payload, out);
      return;
    }
  }
  if (encoding != SplineFrames::kFixed) {
    append_compact_data(sp, step, curve, max_payload, out);
    return;
  }
  const unsigned room = data_room(max_payload, proto::kSplineDataHeaderBytes);
  unsigned next_control = 0;
  unsigned next_knot = 0;
  while (next_control < sp.control_count || next_knot < sp.knot_count) {
    out->push_back(encode_command(full_data(sp, room, &next_control, &next_knot), step, curve));
  }
}

bool is_spline_data(uint8_t letter) {
  return proto::command_role(letter) == proto::CommandRole::kSplineData;
}

bool add_spline_data(const QueuedCommand& c, core::Spline* s) {
  const uint8_t length = static_cast<uint8_t>(c.payload.size());
  if (c.payload.size() > proto::kMaxPayload) return false;
  if (c.letter == proto::kCmdSplineData) {
    proto::SplineDataCmd d;
    if (proto::decode(c.payload.data(), length, &d) != proto::ErrorCode::kOk) return false;
    for (unsigned k = 0; k < d.control_n; ++k) s->control[d.control_index + k] = d.control[k];
    for (unsigned k = 0; k < d.knot_n; ++k) s->knot[d.knot_index + k] = d.knot[k];
    return true;
  }
  if (c.letter == proto::kCmdSplineCompact) {
    proto::SplineCompactCmd d;
    if (proto::decode(c.payload.data(), length, &d) != proto::ErrorCode::kOk) return false;
    return proto::unpack_compact(d, s) == proto::ErrorCode::kOk;
  }
  if (c.letter == proto::kCmdSplineContour) {
    proto::SplineContourCmd d;
    if (proto::decode(c.payload.data(), length, &d) != proto::ErrorCode::kOk) return false;
    return proto::unpack_contour(d, s) == proto::ErrorCode::kOk;
  }
  return false;
}

}  // namespace host
