// Every wire message, declared once: its letter, role, payload fields (wire type, name,
// range), reply, display name and handler. messages.h builds the structs from it,
// wire_codes.h the letters and command_role(), codec.cpp the field tables its one walker
// encodes, decodes and checks with, frame.cpp command_kind() and message_name() (the display
// names), the application its handler declarations and routing table (command_handlers.h),
// and a test checks docs/protocol.md against it (its tables and its lists of spline data,
// job commands and real-time frames). Adding a command: one CMD row with its fields, the body
// of the handler it names, and its line in docs/protocol.md.
//
// An X-macro: PROTO_MESSAGE_TABLE(CMD, REPLY, FIELD, TEXT, ARRAY, END) calls
//   CMD(Type, letter_name, letter, role, "name", "reply", handler, extra_check)
//   REPLY(Type, letter_name, letter, "name", extra_check)
//   FIELD(Type, wire_type, field, min, max)   one fixed-size field, min..max inclusive
//   TEXT(Type, count, field, max)              the rest of the payload: 0..max characters
//                                              0x20..0x7E; `count` holds how many
//   ARRAY(Type, count, field, element, max)    `count` (an earlier FIELD) elements
//   END(Type)
// in wire order. wire_type: u8 u16 i32; flag (u8 0/1 as bool); state alarm error (u8 enums);
// none (a u8 in the struct, not on the wire: the count of a `rest` array). ARRAY element:
// point (x i32, y i32, weight u16), i32, rest (bytes of any value to the end of the payload).
// role (CommandRole, wire_codes.h; the frame's kind follows from it): kImmediate (answered
// by the dispatcher itself), kRealtime, and the queued kJobCommand (a queue slot; numbered
// after a #J), kSplineData (fills the open spline), kJobMark (#J). extra_check: a function
// of the message for what one field cannot say (no_check when none). handler: the
// application's member for the command (dispatcher_handles for the kImmediate rows, which
// have none).
#ifndef FIRMWARE_PROTOCOL_MESSAGE_TABLE_H
#define FIRMWARE_PROTOCOL_MESSAGE_TABLE_H

// Ranges used below (the numbers are also in docs/protocol.md).
#define PROTO_COORD_MIN (-1000000L)  // core::kMaxCoordinateUm
#define PROTO_COORD_MAX 1000000L
#define PROTO_I32_MIN (-2147483647L - 1L)
#define PROTO_I32_MAX 2147483647L

// clang-format off
#define PROTO_MESSAGE_TABLE(CMD, REPLY, FIELD, TEXT, ARRAY, END)                             \
  CMD(SessionCmd, kCmdSession, 'I', kImmediate, "session start/reset", "`*I` or `*E`",       \
      dispatcher_handles, no_check)                                                          \
    FIELD(SessionCmd, u8, protocol_version, 1, 255)                                          \
  END(SessionCmd)                                                                            \
  CMD(StatusCmd, kCmdStatus, '?', kImmediate, "status query", "`*?`",                        \
      dispatcher_handles, no_check)                                                          \
  END(StatusCmd)                                                                             \
  CMD(HoldCmd, kCmdHold, 'H', kRealtime, "feed hold", "`*O`", on_hold, no_check)             \
  END(HoldCmd)                                                                               \
  CMD(ResumeCmd, kCmdResume, 'R', kRealtime, "resume", "`*O` / `*E`", on_resume, no_check)   \
  END(ResumeCmd)                                                                             \
  CMD(AbortCmd, kCmdAbort, 'X', kRealtime, "abort", "`*O`", on_abort, no_check)              \
  END(AbortCmd)                                                                              \
  CMD(OverrideCmd, kCmdOverride, 'V', kRealtime, "feed override", "`*O` / `*E`",             \
      on_override, no_check)                                                                 \
    FIELD(OverrideCmd, u8, percent, 10, 200)                                                 \
  END(OverrideCmd)                                                                           \
  CMD(ClearAlarmCmd, kCmdClearAlarm, 'C', kRealtime, "clear alarm", "`*O` / `*E`",           \
      on_clear_alarm, no_check)                                                              \
  END(ClearAlarmCmd)                                                                         \
  CMD(TextCmd, kCmdText, 'S', kJobCommand, "LCD text", "`*O` / `*E`", on_text, no_check)     \
    FIELD(TextCmd, u8, row, 0, 1)                                                            \
    TEXT(TextCmd, length, text, 16)                                                          \
  END(TextCmd)                                                                               \
  CMD(SplineHeaderCmd, kCmdSplineHeader, 'B', kJobCommand, "spline header", "`*O` / `*E`",   \
      on_spline_header, check_spline_header)                                                 \
    FIELD(SplineHeaderCmd, u8, degree, 1, 3)                                                 \
    FIELD(SplineHeaderCmd, flag, rational, 0, 1)                                             \
    FIELD(SplineHeaderCmd, u16, control_count, 2, 64)                                        \
    FIELD(SplineHeaderCmd, u16, knot_count, 4, 68)                                           \
    FIELD(SplineHeaderCmd, u16, feed_um_per_s, 1, 65535)                                     \
    FIELD(SplineHeaderCmd, i32, tool_offset_um, -100000, 100000)                             \
  END(SplineHeaderCmd)                                                                       \
  CMD(SplineDataCmd, kCmdSplineData, 'D', kSplineData, "spline data", "`*O` / `*E`",         \
      on_spline_data, check_spline_data)                                                     \
    FIELD(SplineDataCmd, u8, control_index, 0, 64)                                           \
    FIELD(SplineDataCmd, u8, control_n, 0, 6)                                                \
    FIELD(SplineDataCmd, u8, knot_index, 0, 68)                                              \
    FIELD(SplineDataCmd, u8, knot_n, 0, 15)                                                  \
    ARRAY(SplineDataCmd, control_n, control, point, 6)                                       \
    ARRAY(SplineDataCmd, knot_n, knot, i32, 15)                                              \
  END(SplineDataCmd)                                                                         \
  CMD(SplineCompactCmd, kCmdSplineCompact, 'K', kSplineData, "spline data, compact",         \
      "`*O` / `*E`", on_spline_compact, check_spline_compact)                                \
    FIELD(SplineCompactCmd, u8, control_index, 0, 64)                                        \
    FIELD(SplineCompactCmd, u8, control_n, 0, 30)                                            \
    FIELD(SplineCompactCmd, u8, knot_index, 0, 68)                                           \
    FIELD(SplineCompactCmd, u8, knot_n, 0, 60)                                               \
    FIELD(SplineCompactCmd, none, data_n, 1, 60)                                             \
    ARRAY(SplineCompactCmd, data_n, data, rest, 60)                                          \
  END(SplineCompactCmd)                                                                      \
  CMD(SplineContourCmd, kCmdSplineContour, 'Q', kSplineData, "spline data, lines and arcs",  \
      "`*O` / `*E`", on_spline_contour, check_spline_contour)                                \
    FIELD(SplineContourCmd, u8, control_index, 0, 63)                                        \
    FIELD(SplineContourCmd, u8, control_n, 1, 63)                                            \
    FIELD(SplineContourCmd, none, data_n, 1, 62)                                             \
    ARRAY(SplineContourCmd, data_n, data, rest, 62)                                          \
  END(SplineContourCmd)                                                                      \
  CMD(ResolutionCmd, kCmdResolution, 'U', kJobCommand, "resolution", "`*O` / `*E`",          \
      on_resolution, no_check)                                                               \
    FIELD(ResolutionCmd, u16, max_step_um, 1, 65535)                                         \
    FIELD(ResolutionCmd, u16, chord_tolerance_um, 1, 65535)                                  \
  END(ResolutionCmd)                                                                         \
  CMD(FeedMoveCmd, kCmdFeedMove, 'G', kJobCommand, "feed move (linear XY)", "`*O` / `*E`",   \
      on_feed_move, no_check)                                                                \
    FIELD(FeedMoveCmd, i32, x_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                          \
    FIELD(FeedMoveCmd, i32, y_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                          \
    FIELD(FeedMoveCmd, u16, feed_um_per_s, 1, 65535)                                         \
  END(FeedMoveCmd)                                                                           \
  CMD(RapidMoveCmd, kCmdRapidMove, 'F', kJobCommand, "rapid move (linear XY)",               \
      "`*O` / `*E`", on_rapid_move, no_check)                                                \
    FIELD(RapidMoveCmd, i32, x_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                         \
    FIELD(RapidMoveCmd, i32, y_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                         \
  END(RapidMoveCmd)                                                                          \
  CMD(ZMoveCmd, kCmdZMove, 'Z', kJobCommand, "Z-only move", "`*O` / `*E`", on_z_move,        \
      no_check)                                                                              \
    FIELD(ZMoveCmd, i32, z_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                             \
    FIELD(ZMoveCmd, u16, feed_um_per_s, 1, 65535)                                            \
  END(ZMoveCmd)                                                                              \
  CMD(ZeroingCmd, kCmdZeroing, 'M', kJobCommand, "start manual zeroing", "`*O` / `*E`",      \
      on_zeroing, no_check)                                                                  \
    FIELD(ZeroingCmd, u8, axes, 1, 7)                                                        \
  END(ZeroingCmd)                                                                            \
  CMD(PauseCmd, kCmdPause, 'P', kJobCommand, "operator pause", "`*O` / `*E`", on_pause,      \
      no_check)                                                                              \
    TEXT(PauseCmd, length, text, 16)                                                         \
  END(PauseCmd)                                                                              \
  CMD(DwellCmd, kCmdDwell, 'W', kJobCommand, "dwell", "`*O` / `*E`", on_dwell, no_check)     \
    FIELD(DwellCmd, u16, dwell_ms, 1, 65535)                                                 \
  END(DwellCmd)                                                                              \
  CMD(SpindleCmd, kCmdSpindle, 'N', kJobCommand, "spindle on/off", "`*O` / `*E`",            \
      on_spindle, no_check)                                                                  \
    FIELD(SpindleCmd, u8, on, 0, 1)                                                          \
  END(SpindleCmd)                                                                            \
  CMD(DrillCmd, kCmdDrill, 'L', kJobCommand, "drill one hole", "`*O` / `*E`", on_drill,      \
      check_drill)                                                                           \
    FIELD(DrillCmd, i32, x_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                             \
    FIELD(DrillCmd, i32, y_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                             \
    FIELD(DrillCmd, i32, z_start_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                       \
    FIELD(DrillCmd, i32, z_bottom_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                      \
    FIELD(DrillCmd, u16, feed_um_per_s, 1, 65535)                                            \
  END(DrillCmd)                                                                              \
  CMD(JobMarkCmd, kCmdJobMark, 'J', kJobMark, "job mark", "`*O` / `*E`", on_job_mark,        \
      no_check)                                                                              \
    FIELD(JobMarkCmd, i32, job_index, 0, PROTO_I32_MAX)                                      \
    FIELD(JobMarkCmd, u16, first_point, 0, 65535)                                            \
    FIELD(JobMarkCmd, u16, job_id, 0, 65535)                                                 \
  END(JobMarkCmd)                                                                            \
  CMD(ProbeCmd, kCmdProbe, 'Y', kJobCommand, "probe (Z down to contact)", "`*O` / `*E`",     \
      on_probe, no_check)                                                                    \
    FIELD(ProbeCmd, i32, z_limit_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                       \
    FIELD(ProbeCmd, u16, feed_um_per_s, 1, 65535)                                            \
    FIELD(ProbeCmd, u16, retract_um, 0, 65535)                                               \
  END(ProbeCmd)                                                                              \
  CMD(ProbeResultCmd, kCmdProbeResult, 'T', kImmediate, "probe result query", "`*T`",        \
      dispatcher_handles, no_check)                                                          \
  END(ProbeResultCmd)                                                                        \
  CMD(HeightMapHeaderCmd, kCmdHeightMapHeader, 'A', kJobCommand, "height map header",        \
      "`*O` / `*E`", on_height_map_header, check_height_map_header)                          \
    FIELD(HeightMapHeaderCmd, u8, cols, 0, 16)                                               \
    FIELD(HeightMapHeaderCmd, u8, rows, 0, 16)                                               \
    FIELD(HeightMapHeaderCmd, i32, x0_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                  \
    FIELD(HeightMapHeaderCmd, i32, y0_um, PROTO_COORD_MIN, PROTO_COORD_MAX)                  \
    FIELD(HeightMapHeaderCmd, u16, pitch_x_um, 0, 65535)                                     \
    FIELD(HeightMapHeaderCmd, u16, pitch_y_um, 0, 65535)                                     \
  END(HeightMapHeaderCmd)                                                                    \
  CMD(HeightMapDataCmd, kCmdHeightMapData, 'E', kJobCommand, "height map heights",           \
      "`*O` / `*E`", on_height_map_data, check_height_map_data)                              \
    FIELD(HeightMapDataCmd, u8, index, 0, 255)                                               \
    FIELD(HeightMapDataCmd, u8, height_n, 1, 8)                                              \
    ARRAY(HeightMapDataCmd, height_n, height_um, i32, 8)                                     \
  END(HeightMapDataCmd)                                                                      \
  REPLY(AckReply, kReplyAck, 'O', "acknowledge", no_check)                                   \
    FIELD(AckReply, u8, queue_free, 0, 255)                                                  \
    FIELD(AckReply, u8, spline_slots_free, 0, 255)                                           \
    FIELD(AckReply, flag, realtime, 0, 1)                                                    \
  END(AckReply)                                                                              \
  REPLY(ErrorReply, kReplyError, 'E', "error", no_check)                                     \
    FIELD(ErrorReply, error, code, 1, 255)                                                   \
    FIELD(ErrorReply, u8, detail, 0, 255)                                                    \
    FIELD(ErrorReply, u8, next_expected_seq, 0, 255)                                         \
  END(ErrorReply)                                                                            \
  REPLY(SessionReply, kReplySession, 'I', "session opened", no_check)                        \
    FIELD(SessionReply, u8, protocol_version, 1, 255)                                        \
    FIELD(SessionReply, u8, max_payload, 16, 64)                                             \
    FIELD(SessionReply, u8, window_frames, 1, 8)                                             \
    FIELD(SessionReply, u8, queue_slots, 1, 255)                                             \
    FIELD(SessionReply, u16, rx_buffer_bytes, 70, 65535)                                     \
    FIELD(SessionReply, u8, max_degree, 1, 3)                                                \
    FIELD(SessionReply, u8, max_control_points, 2, 64)                                       \
    FIELD(SessionReply, u8, firmware_major, 0, 255)                                          \
    FIELD(SessionReply, u8, firmware_minor, 0, 255)                                          \
    FIELD(SessionReply, i32, travel_x_um, 1, PROTO_COORD_MAX)                                \
    FIELD(SessionReply, i32, travel_y_um, 1, PROTO_COORD_MAX)                                \
    FIELD(SessionReply, i32, travel_z_um, 1, PROTO_COORD_MAX)                                \
    FIELD(SessionReply, u16, max_feed_xy_um_per_s, 1, 65535)                                 \
    FIELD(SessionReply, u16, max_feed_z_um_per_s, 1, 65535)                                  \
  END(SessionReply)                                                                          \
  REPLY(StatusReply, kReplyStatus, '?', "status", no_check)                                  \
    FIELD(StatusReply, state, state, 0, 6)                                                   \
    FIELD(StatusReply, alarm, alarm, 0, 11)                                                  \
    FIELD(StatusReply, u8, flags, 0, 255)                                                    \
    FIELD(StatusReply, u8, override_percent, 10, 200)                                        \
    FIELD(StatusReply, u8, queue_free, 0, 255)                                               \
    FIELD(StatusReply, u8, next_expected_seq, 0, 255)                                        \
    FIELD(StatusReply, u8, last_executed_seq, 0, 255)                                        \
    FIELD(StatusReply, error, last_error, 0, 255)                                            \
    FIELD(StatusReply, i32, x_um, PROTO_I32_MIN, PROTO_I32_MAX)                              \
    FIELD(StatusReply, i32, y_um, PROTO_I32_MIN, PROTO_I32_MAX)                              \
    FIELD(StatusReply, i32, z_um, PROTO_I32_MIN, PROTO_I32_MAX)                              \
    FIELD(StatusReply, u16, rejected_frames, 0, 65535)                                       \
    FIELD(StatusReply, u8, spline_slots_free, 0, 255)                                        \
    FIELD(StatusReply, i32, job_index, 0, PROTO_I32_MAX)                                     \
    FIELD(StatusReply, u16, curve_point, 0, 65535)                                           \
    FIELD(StatusReply, u16, job_id, 0, 65535)                                                \
  END(StatusReply)                                                                           \
  REPLY(AlarmReply, kReplyAlarm, 'A', "alarm notice (unsolicited)", no_check)                \
    FIELD(AlarmReply, alarm, alarm, 0, 11)                                                   \
    FIELD(AlarmReply, state, state, 0, 6)                                                    \
  END(AlarmReply)                                                                            \
  REPLY(ProbeResultReply, kReplyProbeResult, 'T', "probe result", no_check)                  \
    FIELD(ProbeResultReply, u8, result, 0, 2)                                                \
    FIELD(ProbeResultReply, u16, probe_count, 0, 65535)                                      \
    FIELD(ProbeResultReply, i32, x_um, PROTO_I32_MIN, PROTO_I32_MAX)                         \
    FIELD(ProbeResultReply, i32, y_um, PROTO_I32_MIN, PROTO_I32_MAX)                         \
    FIELD(ProbeResultReply, i32, z_um, PROTO_I32_MIN, PROTO_I32_MAX)                         \
  END(ProbeResultReply)
// clang-format on

#endif  // FIRMWARE_PROTOCOL_MESSAGE_TABLE_H
