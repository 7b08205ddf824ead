// One field walker for every message: the message table (message_table.h) becomes a field
// list per message (wire type, offset in the struct, range); encode, decode and the range
// check walk that list, so the byte layout and the ranges are written down once.
#include "firmware/protocol/codec.h"

#include "firmware/protocol/compact_spline.h"  // scan_compact
#include "firmware/protocol/contour_spline.h"  // scan_contour

#include <stddef.h>  // offsetof
#include <string.h>  // memcpy

namespace proto {

namespace {

enum WireType {
  kWireU8,
  kWireU16,
  kWireI32,
  kWireFlag,    // u8 0/1 into a bool
  kWireState,   // u8 MachineState
  kWireAlarm,   // u8 Alarm
  kWireError,   // u8 ErrorCode (only the defined values)
  kWireText,    // the rest of the payload, characters 0x20..0x7E
  kWirePoints,  // count x (x i32, y i32, weight u16): coordinates in range, weight >= 1
  kWireKnots,   // count x i32
  kWireBytes,   // u8 of any value to the end of the payload, count in a kWireNone field
  kWireNone,    // a u8 count in the struct, not on the wire
  kWireEnd
};

// Text and arrays have fixed element ranges (kWireText, kWirePoints), so their min and max
// hold the count's offset and the largest count instead: 6 bytes an entry, not 8.
struct FieldSpec {
  uint8_t type;    // WireType
  uint8_t offset;  // of the field in the message struct
  int16_t min;     // range ends as PROTO_LIMIT codes (range_end() decodes them);
  int16_t max;     // text, arrays: count_offset() and max_count()
};

// Of the uint8_t count in the struct (text, arrays).
uint8_t count_offset(const FieldSpec* f) {
  return (uint8_t)f->min;
}
uint8_t max_count(const FieldSpec* f) {
  return (uint8_t)f->max;
}

// Range ends that do not fit 16 bits, stored in FieldSpec as codes kWideLimitCode + i: a
// field table entry is 8 bytes instead of 12 (the tables are flash). Every range end must
// be -32768..32759 or listed here: the static_asserts after the tables check each one.
const int32_t kWideLimits[] = {65535L,   PROTO_COORD_MAX, PROTO_COORD_MIN, 100000L,
                               -100000L, PROTO_I32_MAX,   PROTO_I32_MIN};
enum { kWideLimitCode = 32760, kNoLimitCode = 32767 };  // small values: -32768..32759
#define PROTO_LIMIT(v)                                           \
  ((v) == 65535L                            ? kWideLimitCode + 0 \
   : (v) == PROTO_COORD_MAX                 ? kWideLimitCode + 1 \
   : (v) == PROTO_COORD_MIN                 ? kWideLimitCode + 2 \
   : (v) == 100000L                         ? kWideLimitCode + 3 \
   : (v) == -100000L                        ? kWideLimitCode + 4 \
   : (v) == PROTO_I32_MAX                   ? kWideLimitCode + 5 \
   : (v) == PROTO_I32_MIN                   ? kWideLimitCode + 6 \
   : (v) >= -32768L && (v) < kWideLimitCode ? (int16_t)(v)       \
                                            : (int16_t)kNoLimitCode)
#define PROTO_LIMIT_OK(v) (PROTO_LIMIT(v) != kNoLimitCode)

int32_t range_end(int16_t code) {
  return code >= kWideLimitCode ? kWideLimits[code - kWideLimitCode] : code;
}

#define PROTO_WIRE_u8 kWireU8
#define PROTO_WIRE_u16 kWireU16
#define PROTO_WIRE_i32 kWireI32
#define PROTO_WIRE_flag kWireFlag
#define PROTO_WIRE_state kWireState
#define PROTO_WIRE_alarm kWireAlarm
#define PROTO_WIRE_error kWireError
#define PROTO_WIRE_none kWireNone
#define PROTO_ARRAY_WIRE_point kWirePoints
#define PROTO_ARRAY_WIRE_i32 kWireKnots
#define PROTO_ARRAY_WIRE_rest kWireBytes

// NOLINTBEGIN(bugprone-macro-parentheses): the arguments are type and member names.
#define PROTO_SPEC_CMD(Type, name, letter, role, display, reply, handler, check) \
  const FieldSpec k##Type##Fields[] = {
#define PROTO_SPEC_REPLY(Type, name, letter, display, check) const FieldSpec k##Type##Fields[] = {
#define PROTO_SPEC_FIELD(Type, wire, field, min, max) \
  {PROTO_WIRE_##wire, (uint8_t)offsetof(Type, field), PROTO_LIMIT(min), PROTO_LIMIT(max)},
#define PROTO_SPEC_TEXT(Type, count, field, max) \
  {kWireText, (uint8_t)offsetof(Type, field), (int16_t)offsetof(Type, count), max},
#define PROTO_SPEC_ARRAY(Type, count, field, element, max) \
  {PROTO_ARRAY_WIRE_##element, (uint8_t)offsetof(Type, field), (int16_t)offsetof(Type, count), max},
#define PROTO_SPEC_END(Type) \
  { kWireEnd, 0, 0, 0 }      \
  }                          \
  ;
// NOLINTEND(bugprone-macro-parentheses)
PROTO_MESSAGE_TABLE(PROTO_SPEC_CMD, PROTO_SPEC_REPLY, PROTO_SPEC_FIELD, PROTO_SPEC_TEXT,
                    PROTO_SPEC_ARRAY, PROTO_SPEC_END)
#undef PROTO_SPEC_CMD
#undef PROTO_SPEC_REPLY
#undef PROTO_SPEC_FIELD
#undef PROTO_SPEC_TEXT
#undef PROTO_SPEC_ARRAY
#undef PROTO_SPEC_END

// Every range end has a code (see kWideLimits).
#define PROTO_SKIP(...)
#define PROTO_CHECK_FIELD(Type, wire, field, min, max) \
  static_assert(PROTO_LIMIT_OK(min) && PROTO_LIMIT_OK(max), "add the range end to kWideLimits");
PROTO_MESSAGE_TABLE(PROTO_SKIP, PROTO_SKIP, PROTO_CHECK_FIELD, PROTO_SKIP, PROTO_SKIP, PROTO_SKIP)
#undef PROTO_SKIP
#undef PROTO_CHECK_FIELD
#undef PROTO_LIMIT_OK
#undef PROTO_LIMIT

// ---- little-endian bytes ----

uint16_t get_u16(const uint8_t* p) {
  return (uint16_t)(p[0] | ((uint16_t)p[1] << 8));
}
int32_t get_i32(const uint8_t* p) {
  const uint32_t v = (uint32_t)get_u16(p) | ((uint32_t)get_u16(p + 2) << 16);
  return (int32_t)v;
}
void put_u16(uint8_t* p, uint16_t v) {
  p[0] = (uint8_t)(v & 0xFFU);
  p[1] = (uint8_t)(v >> 8);
}
void put_i32(uint8_t* p, int32_t v) {
  const uint32_t u = (uint32_t)v;
  put_u16(p, (uint16_t)(u & 0xFFFFU));
  put_u16(p + 2, (uint16_t)(u >> 16));
}

// Wire bytes of a one-element field type.
uint8_t scalar_bytes(uint8_t type) {
  if (type == kWireU16) return 2;
  if (type == kWireI32) return 4;
  return 1;
}

bool in_range(int32_t v, int32_t lo, int32_t hi) {
  return v >= lo && v <= hi;
}

// A scalar field's value from the struct, widened.
int32_t load(const uint8_t* msg, const FieldSpec& f) {
  const uint8_t* at = msg + f.offset;
  if (f.type == kWireU16) {
    uint16_t v;
    memcpy(&v, at, sizeof v);
    return v;
  }
  if (f.type == kWireI32) {
    int32_t v;
    memcpy(&v, at, sizeof v);
    return v;
  }
  if (f.type == kWireFlag) {
    bool b;
    memcpy(&b, at, sizeof b);
    return b ? 1 : 0;
  }
  return *at;  // u8 and the u8 enums
}

void store(uint8_t* msg, const FieldSpec& f, int32_t v) {
  uint8_t* at = msg + f.offset;
  if (f.type == kWireU16) {
    const uint16_t u = (uint16_t)v;
    memcpy(at, &u, sizeof u);
  } else if (f.type == kWireI32) {
    memcpy(at, &v, sizeof v);
  } else if (f.type == kWireFlag) {
    const bool b = v != 0;
    memcpy(at, &b, sizeof b);
  } else {
    *at = (uint8_t)v;
  }
}

// Every field inside its range (and the enums inside their lists).
ErrorCode check_fields(const uint8_t* msg, const FieldSpec* f) {
  for (; f->type != kWireEnd; ++f) {
    if (f->type == kWireText || f->type == kWirePoints || f->type == kWireKnots ||
        f->type == kWireBytes) {
      const uint8_t n = msg[count_offset(f)];
      if (n > max_count(f)) return ErrorCode::kFieldRange;
      for (uint8_t i = 0; i < n; ++i) {
        if (f->type == kWireText) {
          const uint8_t c = msg[f->offset + i];
          if (c < 0x20 || c > 0x7E) return ErrorCode::kFieldRange;
        } else if (f->type == kWirePoints) {
          core::ControlPoint p;
          memcpy(&p, msg + f->offset + i * sizeof p, sizeof p);
          if (!in_range(p.x_um, PROTO_COORD_MIN, PROTO_COORD_MAX) ||
              !in_range(p.y_um, PROTO_COORD_MIN, PROTO_COORD_MAX) || p.weight_q14 == 0)
            return ErrorCode::kFieldRange;
        }
      }
      continue;
    }
    const int32_t v = load(msg, *f);
    if (!in_range(v, range_end(f->min), range_end(f->max))) return ErrorCode::kFieldRange;
    if (f->type == kWireState && v > (int32_t)MachineState::kPaused) return ErrorCode::kFieldRange;
    if (f->type == kWireAlarm && v > (int32_t)kLastAlarm) return ErrorCode::kFieldRange;
    if (f->type == kWireError && !is_known_error((uint8_t)v)) return ErrorCode::kFieldRange;
  }
  return ErrorCode::kOk;
}

// Writes the fields (already checked) in wire order.
void write_fields(const uint8_t* msg, const FieldSpec* f, Payload* out) {
  uint8_t* p = out->bytes;
  uint16_t n_out = 0;
  for (; f->type != kWireEnd; ++f) {
    if (f->type == kWireText || f->type == kWirePoints || f->type == kWireKnots ||
        f->type == kWireBytes) {
      const uint8_t n = msg[count_offset(f)];
      for (uint8_t i = 0; i < n; ++i) {
        if (f->type == kWireText || f->type == kWireBytes) {
          p[n_out++] = msg[f->offset + i];
        } else if (f->type == kWirePoints) {
          core::ControlPoint c;
          memcpy(&c, msg + f->offset + i * sizeof c, sizeof c);
          put_i32(p + n_out, c.x_um);
          put_i32(p + n_out + 4, c.y_um);
          put_u16(p + n_out + 8, c.weight_q14);
          n_out = (uint16_t)(n_out + kControlPointBytes);
        } else {
          int32_t k;
          memcpy(&k, msg + f->offset + i * sizeof k, sizeof k);
          put_i32(p + n_out, k);
          n_out = (uint16_t)(n_out + kKnotBytes);
        }
      }
      continue;
    }
    if (f->type == kWireNone) continue;
    const int32_t v = load(msg, *f);
    const uint8_t size = scalar_bytes(f->type);
    if (size == 1) p[n_out] = (uint8_t)v;
    if (size == 2) put_u16(p + n_out, (uint16_t)v);
    if (size == 4) put_i32(p + n_out, v);
    n_out = (uint16_t)(n_out + size);
  }
  out->length = (uint8_t)n_out;
}

// Fills the struct from the payload: kPayloadLength unless the bytes are exactly what the
// fields (and the counts received) call for; kFieldRange for a count or flag the struct
// cannot hold. Ranges are checked afterwards, by check_fields.
ErrorCode read_fields(const uint8_t* bytes, uint8_t length, uint8_t* msg, const FieldSpec* f) {
  if (length > 0 && bytes == 0) return ErrorCode::kPayloadLength;
  uint8_t pos = 0;
  bool bad_flag = false;
  for (; f->type != kWireEnd; ++f) {
    const uint8_t left = (uint8_t)(length - pos);
    if (f->type == kWireText || f->type == kWireBytes) {  // the rest of the payload
      if (left > max_count(f)) return ErrorCode::kPayloadLength;
      msg[count_offset(f)] = left;
      if (left > 0) memcpy(msg + f->offset, bytes + pos, left);  // bytes may be 0 when empty
      pos = length;
      continue;
    }
    if (f->type == kWireNone) continue;  // set by its kWireBytes array
    if (f->type == kWirePoints || f->type == kWireKnots) {
      const uint8_t n = msg[count_offset(f)];
      if (n > max_count(f)) return ErrorCode::kFieldRange;
      const uint8_t each =
          f->type == kWirePoints ? (uint8_t)kControlPointBytes : (uint8_t)kKnotBytes;
      if ((uint16_t)n * each > left) return ErrorCode::kPayloadLength;
      for (uint8_t i = 0; i < n; ++i) {
        const uint8_t* at = bytes + pos + i * each;
        if (f->type == kWirePoints) {
          core::ControlPoint c;
          c.x_um = get_i32(at);
          c.y_um = get_i32(at + 4);
          c.weight_q14 = get_u16(at + 8);
          memcpy(msg + f->offset + i * sizeof c, &c, sizeof c);
        } else {
          const int32_t k = get_i32(at);
          memcpy(msg + f->offset + i * sizeof k, &k, sizeof k);
        }
      }
      pos = (uint8_t)(pos + n * each);
      continue;
    }
    const uint8_t size = scalar_bytes(f->type);
    if (size > left) return ErrorCode::kPayloadLength;
    const uint8_t* at = bytes + pos;
    uint32_t v = 0;  // little-endian, any size
    for (uint8_t k = size; k > 0; --k) v = (v << 8) | at[k - 1];
    if (f->type == kWireFlag && v > 1) bad_flag = true;
    store(msg, *f, (int32_t)v);
    pos = (uint8_t)(pos + size);
  }
  if (pos != length) return ErrorCode::kPayloadLength;
  return bad_flag ? ErrorCode::kFieldRange : ErrorCode::kOk;
}

// ---- what one field cannot say ----

// Every check takes the bytes of its message's struct: one function per check, so the
// messages without one share no_check and the tables point straight at them.
typedef ErrorCode (*ExtraCheck)(const uint8_t* msg);

template <typename Msg>
const Msg& as(const uint8_t* msg) {
  return *reinterpret_cast<const Msg*>(msg);
}

ErrorCode no_check(const uint8_t*) {
  return ErrorCode::kOk;
}

ErrorCode check_spline_header(const uint8_t* msg) {
  const SplineHeaderCmd& m = as<SplineHeaderCmd>(msg);
  if (m.degree > core::kMaxDegree || m.control_count > core::kMaxControlPoints)
    return ErrorCode::kFieldRange;
  if (m.control_count < (uint16_t)(m.degree + 1U)) return ErrorCode::kFieldRange;
  if (m.knot_count != (uint16_t)(m.control_count + m.degree + 1U)) return ErrorCode::kFieldRange;
  return ErrorCode::kOk;
}

ErrorCode check_spline_data(const uint8_t* msg) {
  const SplineDataCmd& m = as<SplineDataCmd>(msg);
  if (m.control_n == 0 && m.knot_n == 0) return ErrorCode::kFieldRange;
  const uint16_t bytes =
      (uint16_t)(kSplineDataHeaderBytes + m.control_n * kControlPointBytes + m.knot_n * kKnotBytes);
  if (bytes > kMaxPayload) return ErrorCode::kFieldRange;
  if ((uint16_t)(m.control_index + m.control_n) > core::kMaxControlPoints)
    return ErrorCode::kFieldRange;
  if ((uint16_t)(m.knot_index + m.knot_n) > core::kMaxKnots) return ErrorCode::kFieldRange;
  return ErrorCode::kOk;
}

// The data holds exactly control_n points then knot_n knots (compact_spline.h).
ErrorCode check_spline_compact(const uint8_t* msg) {
  const SplineCompactCmd& m = as<SplineCompactCmd>(msg);
  if (m.control_n == 0 && m.knot_n == 0) return ErrorCode::kFieldRange;
  if ((uint16_t)(m.control_index + m.control_n) > core::kMaxControlPoints)
    return ErrorCode::kFieldRange;
  if ((uint16_t)(m.knot_index + m.knot_n) > core::kMaxKnots) return ErrorCode::kFieldRange;
  return scan_compact(m);
}

// The data holds exactly the points and elements the indices say (contour_spline.h).
ErrorCode check_spline_contour(const uint8_t* msg) {
  const SplineContourCmd& m = as<SplineContourCmd>(msg);
  if ((uint16_t)(m.control_index + m.control_n) > core::kMaxControlPoints)
    return ErrorCode::kFieldRange;
  return scan_contour(m);
}

ErrorCode check_drill(const uint8_t* msg) {
  const DrillCmd& m = as<DrillCmd>(msg);
  return m.z_bottom_um < m.z_start_um ? ErrorCode::kOk : ErrorCode::kFieldRange;
}

// cols and rows both 0 (no map) or both 2..16; pitches of a map >= 1 mm; its far corner
// inside the coordinate range.
ErrorCode check_height_map_header(const uint8_t* msg) {
  const HeightMapHeaderCmd& m = as<HeightMapHeaderCmd>(msg);
  if (m.cols == 0 && m.rows == 0) return ErrorCode::kOk;
  if (m.cols < 2 || m.rows < 2) return ErrorCode::kFieldRange;
  if (m.pitch_x_um < kMinHeightMapPitchUm || m.pitch_y_um < kMinHeightMapPitchUm)
    return ErrorCode::kFieldRange;
  const int32_t x1 = m.x0_um + (int32_t)(m.cols - 1U) * (int32_t)m.pitch_x_um;
  const int32_t y1 = m.y0_um + (int32_t)(m.rows - 1U) * (int32_t)m.pitch_y_um;
  return x1 <= PROTO_COORD_MAX && y1 <= PROTO_COORD_MAX ? ErrorCode::kOk : ErrorCode::kFieldRange;
}

ErrorCode check_height_map_data(const uint8_t* msg) {
  const HeightMapDataCmd& m = as<HeightMapDataCmd>(msg);
  for (uint8_t i = 0; i < m.height_n; ++i) {
    if (m.height_um[i] > kMaxHeightMapSpanUm || m.height_um[i] < -kMaxHeightMapSpanUm)
      return ErrorCode::kFieldRange;
  }
  return ErrorCode::kOk;
}

template <typename Msg>
const uint8_t* bytes_of(const Msg& m) {
  return reinterpret_cast<const uint8_t*>(&m);
}

// A command's row for decode_command_row (in command_row() order): its fields and extra
// check (on the bytes of the struct).
struct CommandCodec {
  const FieldSpec* fields;
  ExtraCheck check;
};

// NOLINTBEGIN(bugprone-macro-parentheses): the arguments are type and function names.
#define PROTO_CMD_CODEC(Type, name, letter, role, display, reply, handler, check) \
  {k##Type##Fields, &check},
#define PROTO_CMD_CODEC_SKIP(...)
// NOLINTEND(bugprone-macro-parentheses)
const CommandCodec kCommandCodecs[] = {
    PROTO_MESSAGE_TABLE(PROTO_CMD_CODEC, PROTO_CMD_CODEC_SKIP, PROTO_CMD_CODEC_SKIP,
                        PROTO_CMD_CODEC_SKIP, PROTO_CMD_CODEC_SKIP, PROTO_CMD_CODEC_SKIP)};
#undef PROTO_CMD_CODEC
#undef PROTO_CMD_CODEC_SKIP

// encode() of every message: the fields checked, then written (or length 0).
ErrorCode encode_fields(const uint8_t* msg, const FieldSpec* fields, ExtraCheck check,
                        Payload* out) {
  out->length = 0;
  ErrorCode e = check_fields(msg, fields);
  if (e == ErrorCode::kOk) e = check(msg);
  if (e == ErrorCode::kOk) write_fields(msg, fields, out);
  return e;
}

// encode() of a reply: replies are scalar fields only (message_table.h), so this writer has
// no text or array branches (the firmware encodes replies only: it links just this one).
ErrorCode encode_reply_fields(const uint8_t* msg, const FieldSpec* fields, ExtraCheck check,
                              Payload* out) {
  out->length = 0;
  ErrorCode e = check_fields(msg, fields);
  if (e == ErrorCode::kOk) e = check(msg);
  if (e != ErrorCode::kOk) return e;
  uint8_t n_out = 0;
  for (const FieldSpec* f = fields; f->type != kWireEnd; ++f) {
    if (f->type >= kWireText) return ErrorCode::kFieldRange;  // not a reply's field type
    const int32_t v = load(msg, *f);
    const uint8_t size = scalar_bytes(f->type);
    if (size == 1) out->bytes[n_out] = (uint8_t)v;
    if (size == 2) put_u16(out->bytes + n_out, (uint16_t)v);
    if (size == 4) put_i32(out->bytes + n_out, v);
    n_out = (uint8_t)(n_out + size);
  }
  out->length = n_out;
  return ErrorCode::kOk;
}

// decode() of every message: the fields read, then checked.
ErrorCode decode_fields(const uint8_t* bytes, uint8_t length, uint8_t* msg, const FieldSpec* fields,
                        ExtraCheck check) {
  ErrorCode e = read_fields(bytes, length, msg, fields);
  if (e == ErrorCode::kOk) e = check_fields(msg, fields);
  if (e == ErrorCode::kOk) e = check(msg);
  return e;
}

}  // namespace

ErrorCode decode_command_row(uint8_t row, const uint8_t* bytes, uint8_t length, AnyCommand* msg) {
  const CommandCodec& c = kCommandCodecs[row];
  return decode_fields(bytes, length, reinterpret_cast<uint8_t*>(msg), c.fields, c.check);
}

ErrorCode decode_command(uint8_t letter, const uint8_t* bytes, uint8_t length, AnyCommand* msg) {
  const uint8_t row = command_row(letter);
  if (row == kNoCommandRow) return ErrorCode::kUnknownCommand;
  return decode_command_row(row, bytes, length, msg);
}

bool is_known_error(uint8_t code) {
  return code <= (uint8_t)ErrorCode::kRxOverrun ||
         (code >= (uint8_t)ErrorCode::kUnknownCommand && code <= (uint8_t)ErrorCode::kFieldRange) ||
         (code >= (uint8_t)ErrorCode::kSeqGap && code <= (uint8_t)ErrorCode::kVersionUnsupported) ||
         (code >= (uint8_t)ErrorCode::kBusy && code <= (uint8_t)ErrorCode::kHeightMap);
}

// encode / decode / check of every message, each one the walker over its field list.
// NOLINTBEGIN(bugprone-macro-parentheses): the arguments are type and function names.
#define PROTO_CODEC(Type, check, encoder)                                                        \
  ErrorCode check_message(const Type& m) {                                                       \
    const ErrorCode e = check_fields(bytes_of(m), k##Type##Fields);                              \
    return e != ErrorCode::kOk ? e : check(bytes_of(m));                                         \
  }                                                                                              \
  ErrorCode encode(const Type& m, Payload* out) {                                                \
    return encoder(bytes_of(m), k##Type##Fields, &check, out);                                   \
  }                                                                                              \
  ErrorCode decode(const uint8_t* bytes, uint8_t length, Type* m) {                              \
    return decode_fields(bytes, length, reinterpret_cast<uint8_t*>(m), k##Type##Fields, &check); \
  }

#define PROTO_CODEC_CMD(Type, name, letter, role, display, reply, handler, check) \
  PROTO_CODEC(Type, check, encode_fields)
#define PROTO_CODEC_REPLY(Type, name, letter, display, check) \
  PROTO_CODEC(Type, check, encode_reply_fields)
#define PROTO_CODEC_SKIP(...)
// NOLINTEND(bugprone-macro-parentheses)
PROTO_MESSAGE_TABLE(PROTO_CODEC_CMD, PROTO_CODEC_REPLY, PROTO_CODEC_SKIP, PROTO_CODEC_SKIP,
                    PROTO_CODEC_SKIP, PROTO_CODEC_SKIP)
#undef PROTO_CODEC
#undef PROTO_CODEC_CMD
#undef PROTO_CODEC_REPLY
#undef PROTO_CODEC_SKIP

}  // namespace proto
