// Typed payloads of every command and reply, in wire units. Byte layouts are in codec.cpp and
// docs/protocol.md; each struct names its frame letter and start byte.
#ifndef FIRMWARE_PROTOCOL_MESSAGES_H
#define FIRMWARE_PROTOCOL_MESSAGES_H

#include <stdint.h>  // int32_t, uint16_t, uint8_t

#include "firmware/core/spline.h"          // core::ControlPoint, kMaxControlPoints
#include "firmware/protocol/wire_codes.h"  // letters, ErrorCode, MachineState, Alarm

namespace proto {

enum {
  kLcdRows = 2,
  kLcdColumns = 16,
  kMinOverridePercent = 10,
  kMaxOverridePercent = 200,
  kAxisMaskAll = 0x07,         // bit0 X, bit1 Y, bit2 Z
  kSplineDataHeaderBytes = 4,  // #D: 4 index/count bytes
  kControlPointBytes = 10,     // x, y int32 + weight uint16
  kKnotBytes = 4,              // int32
  kMaxDataControls = (kMaxPayload - kSplineDataHeaderBytes) / kControlPointBytes,  // 6
  kMaxDataKnots = (kMaxPayload - kSplineDataHeaderBytes) / kKnotBytes              // 15
};

// Rational flag in #B's flags byte; the other bits must be 0.
static const uint8_t kSplineFlagRational = 0x01;

// ---- Commands (host -> controller) ----

// #I: open or reset the session (aborts any motion, flushes queues, restarts sequences).
struct SessionCmd {
  enum { kStart = kCommandStart, kLetter = kCmdSession };
  uint8_t protocol_version;  // kProtocolVersion
};

// #?: status query. Empty payload.
struct StatusCmd {
  enum { kStart = kCommandStart, kLetter = kCmdStatus };
};

// #H feed hold, #R resume, #X abort, #C clear alarm: empty payloads.
struct HoldCmd {
  enum { kStart = kCommandStart, kLetter = kCmdHold };
};
struct ResumeCmd {
  enum { kStart = kCommandStart, kLetter = kCmdResume };
};
struct AbortCmd {
  enum { kStart = kCommandStart, kLetter = kCmdAbort };
};
struct ClearAlarmCmd {
  enum { kStart = kCommandStart, kLetter = kCmdClearAlarm };
};

// #V: feed override, applied at once to feed moves and splines (not rapids).
struct OverrideCmd {
  enum { kStart = kCommandStart, kLetter = kCmdOverride };
  uint8_t percent;  // kMinOverridePercent..kMaxOverridePercent, 100 = as programmed
};

// #S: text for the LCD, shown when the queue reaches it.
struct TextCmd {
  enum { kStart = kCommandStart, kLetter = kCmdText };
  uint8_t row;             // 0..kLcdRows-1
  uint8_t length;          // 0..kLcdColumns characters; the rest of the row is cleared
  char text[kLcdColumns];  // printable ASCII 0x20..0x7E
};

// #B: starts a spline; #D frames then deliver its control points and knots in order.
struct SplineHeaderCmd {
  enum { kStart = kCommandStart, kLetter = kCmdSplineHeader };
  uint8_t degree;          // 1..core::kMaxDegree
  bool rational;           // weights other than 1.0 allowed
  uint16_t control_count;  // degree+1..core::kMaxControlPoints
  uint16_t knot_count;     // exactly control_count + degree + 1
  uint16_t feed_um_per_s;  // 1..65535, before override
};

// #D: a run of consecutive control points and/or knots of the spline opened by #B.
struct SplineDataCmd {
  enum { kStart = kCommandStart, kLetter = kCmdSplineData };
  uint8_t control_index;  // index of control[0] in the spline
  uint8_t control_n;      // 0..kMaxDataControls
  uint8_t knot_index;     // index of knot[0] in the spline
  uint8_t knot_n;         // 0..kMaxDataKnots; control_n + knot_n >= 1, payload <= 64 bytes
  core::ControlPoint control[kMaxDataControls];  // |x|,|y| <= kMaxCoordinateUm, weight >= 1
  int32_t knot[kMaxDataKnots];                   // arbitrary units, non-decreasing overall
};

// #U: how finely splines become points.
struct ResolutionCmd {
  enum { kStart = kCommandStart, kLetter = kCmdResolution };
  uint16_t max_step_um;         // 1..65535: longest distance between generated points
  uint16_t chord_tolerance_um;  // 1..65535: largest deviation of a chord from the curve
};

// #G: linear XY move at a feed.
struct FeedMoveCmd {
  enum { kStart = kCommandStart, kLetter = kCmdFeedMove };
  int32_t x_um;  // absolute, |v| <= core::kMaxCoordinateUm
  int32_t y_um;
  uint16_t feed_um_per_s;  // 1..65535, before override
};

// #F: linear XY move at the machine's rapid speed (override does not apply).
struct RapidMoveCmd {
  enum { kStart = kCommandStart, kLetter = kCmdRapidMove };
  int32_t x_um;
  int32_t y_um;
};

// #Z: Z-only move.
struct ZMoveCmd {
  enum { kStart = kCommandStart, kLetter = kCmdZMove };
  int32_t z_um;            // absolute, |v| <= core::kMaxCoordinateUm
  uint16_t feed_um_per_s;  // 1..65535
};

// #M: start manual zeroing of the given axes (joystick + confirm button).
struct ZeroingCmd {
  enum { kStart = kCommandStart, kLetter = kCmdZeroing };
  uint8_t axes;  // 1..kAxisMaskAll
};

// #P: operator pause (M0/M1, tool change). Once everything before it has finished and the
// machine stands still, row 0 of the LCD shows the text and row 1 asks for the confirm
// button; the queue goes on when the operator presses it.
struct PauseCmd {
  enum { kStart = kCommandStart, kLetter = kCmdPause };
  uint8_t length;          // 0..kLcdColumns characters
  char text[kLcdColumns];  // printable ASCII 0x20..0x7E
};

// #W: dwell. Waits with every axis still once everything before it has finished.
struct DwellCmd {
  enum { kStart = kCommandStart, kLetter = kCmdDwell };
  uint16_t dwell_ms;  // 1..65535
};

// #N: spindle on or off, switched once everything before it has finished.
struct SpindleCmd {
  enum { kStart = kCommandStart, kLetter = kCmdSpindle };
  uint8_t on;  // 0 off, 1 on
};

// #L: drill one hole: rapid in X/Y at the travel height (the current Z, raised to
// z_start_um if lower) to (x, y), rapid down to z_start_um, plunge to z_bottom_um at
// feed_um_per_s, rapid back up to z_start_um.
struct DrillCmd {
  enum { kStart = kCommandStart, kLetter = kCmdDrill };
  int32_t x_um;  // absolute, |v| <= core::kMaxCoordinateUm
  int32_t y_um;
  int32_t z_start_um;      // above the board; greater than z_bottom_um
  int32_t z_bottom_um;     // depth of the hole (Z grows upward)
  uint16_t feed_um_per_s;  // plunge feed 1..65535, before override
};

// ---- Replies (controller -> host) ----

// *O: the frame with this seq is stored (queued) or done (real-time).
struct AckReply {
  enum { kStart = kReplyStart, kLetter = kReplyAck };
  uint8_t queue_free;  // ordered frames the controller can store right now
};

// *E: the frame with this seq (or, for frame-level codes, none) was rejected.
struct ErrorReply {
  enum { kStart = kReplyStart, kLetter = kReplyError };
  ErrorCode code;             // never kOk
  uint8_t detail;             // core::GeometryError for kGeometry, else 0 or a hint
  uint8_t next_expected_seq;  // ordered seq the controller waits for
};

// *I: session opened; what the controller can take.
struct SessionReply {
  enum { kStart = kReplyStart, kLetter = kReplySession };
  uint8_t protocol_version;    // kProtocolVersion
  uint8_t max_payload;         // 16..kMaxPayload
  uint8_t window_frames;       // 1..kWindowFrames: ordered frames in flight
  uint8_t queue_slots;         // 1..255: ordered frames storable when idle
  uint16_t rx_buffer_bytes;    // >= kMaxFrameBytes: host keeps unacked bytes below this
  uint8_t max_degree;          // 1..core::kMaxDegree
  uint8_t max_control_points;  // 2..core::kMaxControlPoints
  uint8_t firmware_major;
  uint8_t firmware_minor;
};

// *?: status.
struct StatusReply {
  enum { kStart = kReplyStart, kLetter = kReplyStatus };
  MachineState state;
  Alarm alarm;
  uint8_t flags;             // kStatus* bits
  uint8_t override_percent;  // 10..200
  uint8_t queue_free;
  uint8_t next_expected_seq;  // ordered stream
  uint8_t last_executed_seq;  // newest ordered frame whose execution finished
  ErrorCode last_error;       // newest rejection of any level, kOk if none
  int32_t x_um;               // actual position (from the motion controller)
  int32_t y_um;
  int32_t z_um;
  uint16_t rejected_frames;  // all rejections since power-up, saturating
};

// *A: unsolicited alarm notice (seq counts alarms, not acked by the host).
struct AlarmReply {
  enum { kStart = kReplyStart, kLetter = kReplyAlarm };
  Alarm alarm;
  MachineState state;
};

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_MESSAGES_H
