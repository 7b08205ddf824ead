// Byte layouts of every payload (little-endian fixed-width fields), with range checks shared
// by encode and decode so both sides agree on what is valid.
#include "firmware/protocol/codec.h"

namespace proto {

namespace {

// Little-endian field writer over a Payload; capacity is kMaxPayload.
struct Writer {
  Payload* out;
  void u8(uint8_t v) {
    if (out->length < kMaxPayload) out->bytes[out->length++] = v;
  }
  void u16(uint16_t v) {
    u8((uint8_t)(v & 0xFFU));
    u8((uint8_t)(v >> 8));
  }
  void u32(uint32_t v) {
    u16((uint16_t)(v & 0xFFFFU));
    u16((uint16_t)(v >> 16));
  }
  void i32(int32_t v) { u32((uint32_t)v); }
};

// Little-endian field reader; callers check the total length first.
struct Reader {
  const uint8_t* at;
  uint8_t u8() { return *at++; }
  uint16_t u16() {
    const uint16_t lo = u8();
    return (uint16_t)(lo | ((uint16_t)u8() << 8));
  }
  uint32_t u32() {
    const uint32_t lo = u16();
    return lo | ((uint32_t)u16() << 16);
  }
  int32_t i32() { return (int32_t)u32(); }
};

// Starts an empty payload.
Writer begin(Payload* out) {
  out->length = 0;
  Writer w;
  w.out = out;
  return w;
}

// Starts reading bytes; kPayloadLength unless exactly `expected` bytes are present.
ErrorCode expect_length(const uint8_t* bytes, uint8_t length, uint8_t expected) {
  if (length != expected) return ErrorCode::kPayloadLength;
  if (length > 0 && bytes == 0) return ErrorCode::kPayloadLength;
  return ErrorCode::kOk;
}

Reader reader(const uint8_t* bytes) {
  Reader r;
  r.at = bytes;
  return r;
}

bool coordinate_ok(int32_t v_um) {
  return v_um >= -core::kMaxCoordinateUm && v_um <= core::kMaxCoordinateUm;
}

bool state_ok(uint8_t v) {
  return v <= (uint8_t)MachineState::kPaused;
}
bool alarm_ok(uint8_t v) {
  return v <= (uint8_t)Alarm::kSoftLimit;
}

// ---- range checks, one per message ----

ErrorCode check(const SessionCmd& m) {
  return m.protocol_version >= 1 ? ErrorCode::kOk : ErrorCode::kFieldRange;
}

ErrorCode check(const OverrideCmd& m) {
  return (m.percent >= kMinOverridePercent && m.percent <= kMaxOverridePercent)
             ? ErrorCode::kOk
             : ErrorCode::kFieldRange;
}

ErrorCode check(const TextCmd& m) {
  if (m.row >= kLcdRows || m.length > kLcdColumns) return ErrorCode::kFieldRange;
  for (uint8_t i = 0; i < m.length; ++i) {
    const uint8_t c = (uint8_t)m.text[i];
    if (c < 0x20 || c > 0x7E) return ErrorCode::kFieldRange;
  }
  return ErrorCode::kOk;
}

ErrorCode check(const SplineHeaderCmd& m) {
  if (m.degree < 1 || m.degree > core::kMaxDegree) return ErrorCode::kFieldRange;
  if (m.control_count < (uint16_t)(m.degree + 1U) || m.control_count > core::kMaxControlPoints) {
    return ErrorCode::kFieldRange;
  }
  if (m.knot_count != (uint16_t)(m.control_count + m.degree + 1U)) return ErrorCode::kFieldRange;
  if (m.feed_um_per_s == 0) return ErrorCode::kFieldRange;
  return ErrorCode::kOk;
}

ErrorCode check(const SplineDataCmd& m) {
  if (m.control_n > kMaxDataControls || m.knot_n > kMaxDataKnots) return ErrorCode::kFieldRange;
  if (m.control_n == 0 && m.knot_n == 0) return ErrorCode::kFieldRange;
  const uint16_t bytes =
      (uint16_t)(kSplineDataHeaderBytes + m.control_n * kControlPointBytes + m.knot_n * kKnotBytes);
  if (bytes > kMaxPayload) return ErrorCode::kFieldRange;
  if ((uint16_t)(m.control_index + m.control_n) > core::kMaxControlPoints) {
    return ErrorCode::kFieldRange;
  }
  if ((uint16_t)(m.knot_index + m.knot_n) > core::kMaxKnots) return ErrorCode::kFieldRange;
  for (uint8_t i = 0; i < m.control_n; ++i) {
    const core::ControlPoint& p = m.control[i];
    if (!coordinate_ok(p.x_um) || !coordinate_ok(p.y_um) || p.weight_q14 == 0) {
      return ErrorCode::kFieldRange;
    }
  }
  return ErrorCode::kOk;
}

ErrorCode check(const ResolutionCmd& m) {
  return (m.max_step_um != 0 && m.chord_tolerance_um != 0) ? ErrorCode::kOk
                                                           : ErrorCode::kFieldRange;
}

ErrorCode check(const FeedMoveCmd& m) {
  return (coordinate_ok(m.x_um) && coordinate_ok(m.y_um) && m.feed_um_per_s != 0)
             ? ErrorCode::kOk
             : ErrorCode::kFieldRange;
}

ErrorCode check(const RapidMoveCmd& m) {
  return (coordinate_ok(m.x_um) && coordinate_ok(m.y_um)) ? ErrorCode::kOk : ErrorCode::kFieldRange;
}

ErrorCode check(const ZMoveCmd& m) {
  return (coordinate_ok(m.z_um) && m.feed_um_per_s != 0) ? ErrorCode::kOk : ErrorCode::kFieldRange;
}

ErrorCode check(const ZeroingCmd& m) {
  return (m.axes >= 1 && m.axes <= kAxisMaskAll) ? ErrorCode::kOk : ErrorCode::kFieldRange;
}

ErrorCode check(const PauseCmd& m) {
  if (m.length > kLcdColumns) return ErrorCode::kFieldRange;
  for (uint8_t i = 0; i < m.length; ++i) {
    const uint8_t c = (uint8_t)m.text[i];
    if (c < 0x20 || c > 0x7E) return ErrorCode::kFieldRange;
  }
  return ErrorCode::kOk;
}

ErrorCode check(const DwellCmd& m) {
  return m.dwell_ms != 0 ? ErrorCode::kOk : ErrorCode::kFieldRange;
}

ErrorCode check(const SpindleCmd& m) {
  return m.on <= 1 ? ErrorCode::kOk : ErrorCode::kFieldRange;
}

ErrorCode check(const DrillCmd& m) {
  if (!coordinate_ok(m.x_um) || !coordinate_ok(m.y_um)) return ErrorCode::kFieldRange;
  if (!coordinate_ok(m.z_start_um) || !coordinate_ok(m.z_bottom_um)) return ErrorCode::kFieldRange;
  if (m.z_bottom_um >= m.z_start_um || m.feed_um_per_s == 0) return ErrorCode::kFieldRange;
  return ErrorCode::kOk;
}

ErrorCode check(const ErrorReply& m) {
  return (m.code != ErrorCode::kOk && is_known_error((uint8_t)m.code)) ? ErrorCode::kOk
                                                                       : ErrorCode::kFieldRange;
}

ErrorCode check(const SessionReply& m) {
  if (m.protocol_version < 1) return ErrorCode::kFieldRange;
  if (m.max_payload < 16 || m.max_payload > kMaxPayload) return ErrorCode::kFieldRange;
  if (m.window_frames < 1 || m.window_frames > kWindowFrames) return ErrorCode::kFieldRange;
  if (m.queue_slots < 1) return ErrorCode::kFieldRange;
  if (m.rx_buffer_bytes < kMaxFrameBytes) return ErrorCode::kFieldRange;
  if (m.max_degree < 1 || m.max_degree > core::kMaxDegree) return ErrorCode::kFieldRange;
  if (m.max_control_points < 2 || m.max_control_points > core::kMaxControlPoints) {
    return ErrorCode::kFieldRange;
  }
  return ErrorCode::kOk;
}

ErrorCode check(const StatusReply& m) {
  if (!state_ok((uint8_t)m.state) || !alarm_ok((uint8_t)m.alarm)) return ErrorCode::kFieldRange;
  if (m.override_percent < kMinOverridePercent || m.override_percent > kMaxOverridePercent) {
    return ErrorCode::kFieldRange;
  }
  if (!is_known_error((uint8_t)m.last_error)) return ErrorCode::kFieldRange;
  return ErrorCode::kOk;
}

ErrorCode check(const AlarmReply& m) {
  return (alarm_ok((uint8_t)m.alarm) && state_ok((uint8_t)m.state)) ? ErrorCode::kOk
                                                                    : ErrorCode::kFieldRange;
}

// Encodes an empty payload.
ErrorCode encode_empty(Payload* out) {
  begin(out);
  return ErrorCode::kOk;
}

}  // namespace

bool is_known_error(uint8_t code) {
  return code <= (uint8_t)ErrorCode::kRxOverrun ||
         (code >= (uint8_t)ErrorCode::kUnknownCommand && code <= (uint8_t)ErrorCode::kFieldRange) ||
         (code >= (uint8_t)ErrorCode::kSeqGap && code <= (uint8_t)ErrorCode::kVersionUnsupported) ||
         (code >= (uint8_t)ErrorCode::kBusy && code <= (uint8_t)ErrorCode::kOutOfTravel);
}

// ---- empty payloads: #? #H #R #X #C ----

// Type is a type name: it cannot be parenthesised in `Type*`.
// NOLINTBEGIN(bugprone-macro-parentheses)
#define PROTO_EMPTY_CODEC(Type)                                   \
  ErrorCode encode(const Type&, Payload* out) {                   \
    return encode_empty(out);                                     \
  }                                                               \
  ErrorCode decode(const uint8_t* bytes, uint8_t length, Type*) { \
    return expect_length(bytes, length, 0);                       \
  }
// NOLINTEND(bugprone-macro-parentheses)

PROTO_EMPTY_CODEC(StatusCmd)
PROTO_EMPTY_CODEC(HoldCmd)
PROTO_EMPTY_CODEC(ResumeCmd)
PROTO_EMPTY_CODEC(AbortCmd)
PROTO_EMPTY_CODEC(ClearAlarmCmd)

#undef PROTO_EMPTY_CODEC

// ---- #I: version u8 ----

ErrorCode encode(const SessionCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8(m.protocol_version);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, SessionCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 1);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->protocol_version = r.u8();
  return check(*m);
}

// ---- #V: percent u8 ----

ErrorCode encode(const OverrideCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8(m.percent);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, OverrideCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 1);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->percent = r.u8();
  return check(*m);
}

// ---- #S: row u8, then 0..16 characters ----

ErrorCode encode(const TextCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8(m.row);
  for (uint8_t i = 0; i < m.length; ++i) w.u8((uint8_t)m.text[i]);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, TextCmd* m) {
  if (length < 1 || length > 1 + kLcdColumns || bytes == 0) return ErrorCode::kPayloadLength;
  Reader r = reader(bytes);
  m->row = r.u8();
  m->length = (uint8_t)(length - 1);
  for (uint8_t i = 0; i < m->length; ++i) m->text[i] = (char)r.u8();
  return check(*m);
}

// ---- #B: degree u8, flags u8, control_count u16, knot_count u16, feed u16 ----

ErrorCode encode(const SplineHeaderCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8(m.degree);
  w.u8(m.rational ? kSplineFlagRational : 0);
  w.u16(m.control_count);
  w.u16(m.knot_count);
  w.u16(m.feed_um_per_s);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, SplineHeaderCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 8);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->degree = r.u8();
  const uint8_t flags = r.u8();
  m->rational = (flags & kSplineFlagRational) != 0;
  m->control_count = r.u16();
  m->knot_count = r.u16();
  m->feed_um_per_s = r.u16();
  if ((flags & (uint8_t)~kSplineFlagRational) != 0) return ErrorCode::kFieldRange;
  return check(*m);
}

// ---- #D: control_index, control_n, knot_index, knot_n (u8 each), control_n x (x i32,
// y i32, weight u16), knot_n x i32 ----

ErrorCode encode(const SplineDataCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8(m.control_index);
  w.u8(m.control_n);
  w.u8(m.knot_index);
  w.u8(m.knot_n);
  for (uint8_t i = 0; i < m.control_n; ++i) {
    w.i32(m.control[i].x_um);
    w.i32(m.control[i].y_um);
    w.u16(m.control[i].weight_q14);
  }
  for (uint8_t i = 0; i < m.knot_n; ++i) w.i32(m.knot[i]);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, SplineDataCmd* m) {
  if (length < kSplineDataHeaderBytes || bytes == 0) return ErrorCode::kPayloadLength;
  Reader r = reader(bytes);
  m->control_index = r.u8();
  m->control_n = r.u8();
  m->knot_index = r.u8();
  m->knot_n = r.u8();
  if (m->control_n > kMaxDataControls || m->knot_n > kMaxDataKnots) {
    return ErrorCode::kFieldRange;
  }
  const uint16_t expected = (uint16_t)(kSplineDataHeaderBytes + m->control_n * kControlPointBytes +
                                       m->knot_n * kKnotBytes);
  if (expected != length) return ErrorCode::kPayloadLength;
  for (uint8_t i = 0; i < m->control_n; ++i) {
    m->control[i].x_um = r.i32();
    m->control[i].y_um = r.i32();
    m->control[i].weight_q14 = r.u16();
  }
  for (uint8_t i = 0; i < m->knot_n; ++i) m->knot[i] = r.i32();
  return check(*m);
}

// ---- #U: max_step u16, chord_tolerance u16 ----

ErrorCode encode(const ResolutionCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u16(m.max_step_um);
  w.u16(m.chord_tolerance_um);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, ResolutionCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 4);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->max_step_um = r.u16();
  m->chord_tolerance_um = r.u16();
  return check(*m);
}

// ---- #G: x i32, y i32, feed u16 ----

ErrorCode encode(const FeedMoveCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.i32(m.x_um);
  w.i32(m.y_um);
  w.u16(m.feed_um_per_s);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, FeedMoveCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 10);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->x_um = r.i32();
  m->y_um = r.i32();
  m->feed_um_per_s = r.u16();
  return check(*m);
}

// ---- #F: x i32, y i32 ----

ErrorCode encode(const RapidMoveCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.i32(m.x_um);
  w.i32(m.y_um);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, RapidMoveCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 8);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->x_um = r.i32();
  m->y_um = r.i32();
  return check(*m);
}

// ---- #Z: z i32, feed u16 ----

ErrorCode encode(const ZMoveCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.i32(m.z_um);
  w.u16(m.feed_um_per_s);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, ZMoveCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 6);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->z_um = r.i32();
  m->feed_um_per_s = r.u16();
  return check(*m);
}

// ---- #M: axes u8 ----

ErrorCode encode(const ZeroingCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8(m.axes);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, ZeroingCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 1);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->axes = r.u8();
  return check(*m);
}

// ---- #P: 0..16 characters ----

ErrorCode encode(const PauseCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  for (uint8_t i = 0; i < m.length; ++i) w.u8((uint8_t)m.text[i]);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, PauseCmd* m) {
  if (length > kLcdColumns || (length > 0 && bytes == 0)) return ErrorCode::kPayloadLength;
  Reader r = reader(bytes);
  m->length = length;
  for (uint8_t i = 0; i < m->length; ++i) m->text[i] = (char)r.u8();
  return check(*m);
}

// ---- #W: dwell_ms u16 ----

ErrorCode encode(const DwellCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u16(m.dwell_ms);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, DwellCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 2);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->dwell_ms = r.u16();
  return check(*m);
}

// ---- #N: on u8 ----

ErrorCode encode(const SpindleCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8(m.on);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, SpindleCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 1);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->on = r.u8();
  return check(*m);
}

// ---- #L: x i32, y i32, z_start i32, z_bottom i32, feed u16 ----

ErrorCode encode(const DrillCmd& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.i32(m.x_um);
  w.i32(m.y_um);
  w.i32(m.z_start_um);
  w.i32(m.z_bottom_um);
  w.u16(m.feed_um_per_s);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, DrillCmd* m) {
  const ErrorCode e = expect_length(bytes, length, 18);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->x_um = r.i32();
  m->y_um = r.i32();
  m->z_start_um = r.i32();
  m->z_bottom_um = r.i32();
  m->feed_um_per_s = r.u16();
  return check(*m);
}

// ---- *O: queue_free u8 ----

ErrorCode encode(const AckReply& m, Payload* out) {
  Writer w = begin(out);
  w.u8(m.queue_free);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, AckReply* m) {
  const ErrorCode e = expect_length(bytes, length, 1);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->queue_free = r.u8();
  return ErrorCode::kOk;
}

// ---- *E: code u8, detail u8, next_expected u8 ----

ErrorCode encode(const ErrorReply& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8((uint8_t)m.code);
  w.u8(m.detail);
  w.u8(m.next_expected_seq);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, ErrorReply* m) {
  const ErrorCode e = expect_length(bytes, length, 3);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->code = (ErrorCode)r.u8();
  m->detail = r.u8();
  m->next_expected_seq = r.u8();
  return check(*m);
}

// ---- *I: version, max_payload, window, queue_slots (u8), rx_buffer u16, max_degree,
// max_control_points, fw major, fw minor (u8) ----

ErrorCode encode(const SessionReply& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8(m.protocol_version);
  w.u8(m.max_payload);
  w.u8(m.window_frames);
  w.u8(m.queue_slots);
  w.u16(m.rx_buffer_bytes);
  w.u8(m.max_degree);
  w.u8(m.max_control_points);
  w.u8(m.firmware_major);
  w.u8(m.firmware_minor);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, SessionReply* m) {
  const ErrorCode e = expect_length(bytes, length, 10);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->protocol_version = r.u8();
  m->max_payload = r.u8();
  m->window_frames = r.u8();
  m->queue_slots = r.u8();
  m->rx_buffer_bytes = r.u16();
  m->max_degree = r.u8();
  m->max_control_points = r.u8();
  m->firmware_major = r.u8();
  m->firmware_minor = r.u8();
  return check(*m);
}

// ---- *?: state, alarm, flags, override, queue_free, next_expected, last_executed,
// last_error (u8 each), x, y, z (i32), rejected_frames u16 ----

ErrorCode encode(const StatusReply& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8((uint8_t)m.state);
  w.u8((uint8_t)m.alarm);
  w.u8(m.flags);
  w.u8(m.override_percent);
  w.u8(m.queue_free);
  w.u8(m.next_expected_seq);
  w.u8(m.last_executed_seq);
  w.u8((uint8_t)m.last_error);
  w.i32(m.x_um);
  w.i32(m.y_um);
  w.i32(m.z_um);
  w.u16(m.rejected_frames);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, StatusReply* m) {
  const ErrorCode e = expect_length(bytes, length, 22);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->state = (MachineState)r.u8();
  m->alarm = (Alarm)r.u8();
  m->flags = r.u8();
  m->override_percent = r.u8();
  m->queue_free = r.u8();
  m->next_expected_seq = r.u8();
  m->last_executed_seq = r.u8();
  m->last_error = (ErrorCode)r.u8();
  m->x_um = r.i32();
  m->y_um = r.i32();
  m->z_um = r.i32();
  m->rejected_frames = r.u16();
  return check(*m);
}

// ---- *A: alarm u8, state u8 ----

ErrorCode encode(const AlarmReply& m, Payload* out) {
  Writer w = begin(out);
  const ErrorCode e = check(m);
  if (e != ErrorCode::kOk) return e;
  w.u8((uint8_t)m.alarm);
  w.u8((uint8_t)m.state);
  return ErrorCode::kOk;
}

ErrorCode decode(const uint8_t* bytes, uint8_t length, AlarmReply* m) {
  const ErrorCode e = expect_length(bytes, length, 2);
  if (e != ErrorCode::kOk) return e;
  Reader r = reader(bytes);
  m->alarm = (Alarm)r.u8();
  m->state = (MachineState)r.u8();
  return check(*m);
}

}  // namespace proto
