// Typed payloads of every command and reply, in wire units, built from the message table
// (message_table.h); each struct names its frame letter and start byte.
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
  kMaxDataKnots = (kMaxPayload - kSplineDataHeaderBytes) / kKnotBytes,             // 15
  kCompactHeaderBytes = 4,                              // #K: indices and counts
  kMaxCompactData = kMaxPayload - kCompactHeaderBytes,  // 60
  kMaxCompactControls = kMaxCompactData / 2,            // 30: x and y take a byte at least
  kMaxCompactKnots = kMaxCompactData,                   // 60: a knot takes a byte at least
  kContourHeaderBytes = 2,                              // #Q: index and count
  kMaxContourData = kMaxPayload - kContourHeaderBytes,  // 62
  kMaxHeightMapSide = 16,                               // #A: at most 16 x 16 grid points
  kMaxHeightsPerFrame = 8,      // #E: heights in one frame (a queue item holds them)
  kMinHeightMapPitchUm = 1000,  // #A: grid points at least 1 mm apart
  kMaxHeightMapSpanUm = 1000    // #E: |height| and the map's span (with 0) at most 1 mm
};

// The C type of each wire type of the message table.
#define PROTO_CTYPE_u8 uint8_t
#define PROTO_CTYPE_u16 uint16_t
#define PROTO_CTYPE_i32 int32_t
#define PROTO_CTYPE_flag bool
#define PROTO_CTYPE_state MachineState
#define PROTO_CTYPE_alarm Alarm
#define PROTO_CTYPE_error ErrorCode
#define PROTO_CTYPE_point core::ControlPoint
#define PROTO_CTYPE_none uint8_t
#define PROTO_CTYPE_rest uint8_t

// One struct per message, fields in wire order, with its start byte and letter
// (docs/protocol.md gives the meaning of every field).
// NOLINTBEGIN(bugprone-macro-parentheses): the arguments are type and member names.
#define PROTO_STRUCT_CMD(Type, name, letter, role, display, reply, handler, check) \
  struct Type {                                                                    \
    enum { kStart = kCommandStart, kLetter = letter };
#define PROTO_STRUCT_REPLY(Type, name, letter, display, check) \
  struct Type {                                                \
    enum { kStart = kReplyStart, kLetter = letter };
#define PROTO_STRUCT_FIELD(Type, wire, field, min, max) PROTO_CTYPE_##wire field;
#define PROTO_STRUCT_TEXT(Type, count, field, max) \
  uint8_t count;                                   \
  char field[max];
#define PROTO_STRUCT_ARRAY(Type, count, field, element, max) PROTO_CTYPE_##element field[max];
#define PROTO_STRUCT_END(Type) \
  }                            \
  ;
// NOLINTEND(bugprone-macro-parentheses)
PROTO_MESSAGE_TABLE(PROTO_STRUCT_CMD, PROTO_STRUCT_REPLY, PROTO_STRUCT_FIELD, PROTO_STRUCT_TEXT,
                    PROTO_STRUCT_ARRAY, PROTO_STRUCT_END)
#undef PROTO_STRUCT_CMD
#undef PROTO_STRUCT_REPLY
#undef PROTO_STRUCT_FIELD
#undef PROTO_STRUCT_TEXT
#undef PROTO_STRUCT_ARRAY
#undef PROTO_STRUCT_END

// The table's sizes agree with the constants above.
static_assert(sizeof(((TextCmd*)0)->text) == kLcdColumns, "#S text is one LCD row");
static_assert(sizeof(((SplineDataCmd*)0)->control) == kMaxDataControls * sizeof(core::ControlPoint),
              "#D control points: as many as fit a payload");
static_assert(sizeof(((SplineDataCmd*)0)->knot) == kMaxDataKnots * sizeof(int32_t),
              "#D knots: as many as fit a payload");
static_assert(sizeof(((SplineCompactCmd*)0)->data) == kMaxCompactData,
              "#K data: the rest of a payload");
static_assert(sizeof(((SplineContourCmd*)0)->data) == kMaxContourData,
              "#Q data: the rest of a payload");
static_assert(sizeof(((HeightMapDataCmd*)0)->height_um) == kMaxHeightsPerFrame * sizeof(int32_t),
              "#E heights: as many as a queue item carries");

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_MESSAGES_H
