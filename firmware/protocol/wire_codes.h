// Wire constants of the host link: frame bytes, command letters, error, state and alarm codes.
// Numbers here are the protocol (docs/protocol.md): never renumber, only append.
#ifndef FIRMWARE_PROTOCOL_WIRE_CODES_H
#define FIRMWARE_PROTOCOL_WIRE_CODES_H

#include <stdint.h>  // uint8_t

#include "firmware/protocol/message_table.h"  // PROTO_MESSAGE_TABLE

namespace proto {

// Protocol version carried in #I / *I. 2: #P #W #N #L, the paused state, travel and feed
// limits in *I. 3: #Q contour frames. The controller speaks every version from
// kMinProtocolVersion (a later one only adds commands) and answers in the one asked for.
static const uint8_t kProtocolVersion = 3;
static const uint8_t kMinProtocolVersion = 2;
static const uint8_t kContourFramesVersion = 3;  // #Q from this version on

// First byte of a frame: '#' host -> controller (commands), '*' controller -> host (replies).
static const uint8_t kCommandStart = '#';
static const uint8_t kReplyStart = '*';

enum {
  kHeaderBytes = 4,  // start, letter, seq, length
  kCrcBytes = 2,     // CRC-16/IBM-3740 (CCITT-FALSE), little-endian
  kMaxPayload = 64,  // largest payload; a longer length byte is rejected at once
  kMaxFrameBytes = kHeaderBytes + kMaxPayload + kCrcBytes,
  kWindowFrames = 8  // ordered frames in flight; also the duplicate window behind next seq
};

// Command and reply letters, from the message table (kCmdText = 'S', kReplyAck = 'O', ...).
// Original command letters kept; new ones added.
#define PROTO_LETTER_CMD(Type, name, letter, role, display, reply, handler, check) \
  static const uint8_t name = letter;
#define PROTO_LETTER_REPLY(Type, name, letter, display, check) static const uint8_t name = letter;
#define PROTO_LETTER_SKIP(...)
PROTO_MESSAGE_TABLE(PROTO_LETTER_CMD, PROTO_LETTER_REPLY, PROTO_LETTER_SKIP, PROTO_LETTER_SKIP,
                    PROTO_LETTER_SKIP, PROTO_LETTER_SKIP)
#undef PROTO_LETTER_CMD
#undef PROTO_LETTER_REPLY
#undef PROTO_LETTER_SKIP

// The protocol version a command letter exists from (a session of an earlier version refuses
// it as an unknown command).
inline uint8_t version_of_command(uint8_t letter) {
  return letter == kCmdSplineContour ? kContourFramesVersion : kMinProtocolVersion;
}

// How the dispatcher treats a frame, by its letter (its role says which letters).
enum class FrameKind : uint8_t {
  kUnknown = 0,    // letter not defined in this direction
  kQueued = 1,     // ordered stream: sequence window, acked when stored, run in order
  kImmediate = 2,  // answered at once, no ordering
  kRealtime = 3    // acted on at once, before queued work
};

// What a command is, from the message table's role column: the kind, and for queued
// commands what they do to the job numbering and the queue (docs/protocol.md, #J).
enum class CommandRole : uint8_t {
  kUnknown = 0,
  kImmediate = 1,   // answered by the dispatcher itself (kind kImmediate)
  kRealtime = 2,    // kind kRealtime
  kJobCommand = 3,  // queued: takes a queue slot; after a #J, the next job index
  kSplineData = 4,  // queued: fills the open spline (part of its #B), no slot, no number
  kJobMark = 5      // queued: #J, numbers what follows, no slot, no number
};

// No command has the letter (command_row()).
static const uint8_t kNoCommandRow = 0xFF;

// The letter's row among the message table's commands (CMD rows, in table order), or
// kNoCommandRow: the one letter look-up that command_role(), the codec's decode_command_row()
// and the application's handler routes share (frame.cpp).
uint8_t command_row(uint8_t letter);

// The role of a command letter (kUnknown: not a command); command_kind() and the host's job
// tools use it.
inline CommandRole command_role(uint8_t letter) {
#define PROTO_ROLE_OF(Type, name, letter_value, role, display, reply, handler, check) \
  (uint8_t) CommandRole::role,
#define PROTO_ROLE_SKIP(...)
  static const uint8_t kRoles[] = {PROTO_MESSAGE_TABLE(PROTO_ROLE_OF, PROTO_ROLE_SKIP,
                                                       PROTO_ROLE_SKIP, PROTO_ROLE_SKIP,
                                                       PROTO_ROLE_SKIP, PROTO_ROLE_SKIP)};
#undef PROTO_ROLE_OF
#undef PROTO_ROLE_SKIP
  const uint8_t row = command_row(letter);
  return row == kNoCommandRow ? CommandRole::kUnknown : (CommandRole)kRoles[row];
}

// Every coded error of the protocol, one list. Frame-level codes come from the parser;
// payload codes from the codecs; the rest from the dispatcher.
enum class ErrorCode : uint8_t {
  kOk = 0,
  // Frame level (parser): the frame is dropped, nothing is executed.
  kBadCrc = 1,          // CRC mismatch
  kLengthTooLarge = 2,  // length byte > kMaxPayload
  kBadLetter = 3,       // byte after the start byte is not 'A'..'Z' or '?'
  kTruncated = 4,       // frame abandoned after the inter-byte timeout
  kRxOverrun = 5,       // UART overrun/framing error or parser backlog full
  // Payload level (codecs).
  kUnknownCommand = 10,  // letter valid in form but not defined
  kPayloadLength = 11,   // payload length wrong for this command
  kFieldRange = 12,      // a field outside its documented range
  // Sequence level (dispatcher + SequenceWindow).
  kSeqGap = 20,              // ordered frame ahead of the expected seq (one was lost)
  kSeqOutOfWindow = 21,      // ordered frame neither expected, duplicate nor near ahead
  kSeqStale = 22,            // real-time frame older than the last one accepted
  kNoSession = 23,           // ordered/real-time frame before #I
  kVersionUnsupported = 24,  // #I asked for a protocol version we do not speak
  // Execution level (dispatcher / machine).
  kBusy = 30,            // no room and one frame already waiting: resend later
  kAlarmActive = 31,     // machine in alarm: clear it first (#C, then #M if needed)
  kAborted = 32,         // stream flushed by #X: send #I to start again
  kBadState = 33,        // command not allowed in this state (e.g. #R while not held)
  kSplineSequence = 34,  // #D without #B, index not the next expected, or too much data
  kGeometry = 35,        // spline rejected by the core; detail = core::GeometryError
  kNotZeroed = 36,       // motion before the machine was zeroed
  kOutOfTravel = 37,     // target outside the configured travel
  kHeightMap = 38        // #A/#E refused; detail = HeightMapError
};

// Detail of kHeightMap: why a height map frame was refused (nothing of it is kept).
enum HeightMapError {
  kHeightMapSequence = 1,  // #E without #A, index not the next expected, or past cols x rows
  kHeightMapSpan = 2       // the completed map spans more than kMaxHeightMapSpanUm (0 counted)
};

// Number of distinct ErrorCode values the parser counts (codes 0..kRxOverrun).
enum { kParserErrorCount = 6 };

// Machine state in the status reply. The application maps its state machine onto these.
enum class MachineState : uint8_t {
  kIdle = 0,     // nothing queued to run, ready
  kRunning = 1,  // executing queued work
  kHolding = 2,  // feed hold requested, decelerating
  kHeld = 3,     // stopped in hold; #R resumes, #X aborts
  kZeroing = 4,  // manual zeroing with the joystick
  kAlarm = 5,    // stopped by an alarm; queued frames are refused
  kPaused = 6    // #P reached: standing still until the operator presses confirm
};

// Alarm codes (status reply and *A). Stable numbers.
enum class Alarm : uint8_t {
  kNone = 0,
  kLimitSwitch = 1,         // a limit switch tripped during motion: position suspect, re-zero
  kDriverFault = 2,         // a TMC246 reported overtemperature / short, or its chain broke
  kPowerLost = 3,           // driver undervoltage: e-stop pressed or supply lost, re-zero
  kFollowingError = 4,      // actual position did not follow the target
  kMotionChipFault = 5,     // TMC428 read-back or SPI check failed
  kPathFault = 6,           // the point generator failed at run time (geometry error)
  kSoftLimit = 7,           // a target outside the travel reached the path controller
  kProbeNoContact = 8,      // #Y reached its z_limit without the probe closing
  kProbeClosedAtStart = 9,  // #Y: the probe input was closed before it moved (clip shorted?)
  kProbeSpindleOn = 10,     // #Y with the spindle on: refused, nothing moved
  kProbeMissing = 11        // #Y on a machine without a probe input: nothing moved
};
// The newest alarm value (the codec's range check).
static const uint8_t kLastAlarm = 11;

// Bits of the status reply's flags byte.
enum {
  kStatusFramePending = 0x01,  // an ordered frame is held, its ack delayed (no room yet)
  kStatusZeroed = 0x02,        // machine zeroed, positions valid
  kStatusSession = 0x04,       // a session is open (#I seen)
  kStatusAborted = 0x08,       // stream flushed by #X, waiting for #I
  kStatusLinkHold = 0x10,      // hold was caused by the link timeout
  kStatusExecuted = 0x20,      // last_executed_seq is valid: something ran since #I
  kStatusJob = 0x40,           // job_index / curve_point are valid: a #J was stored
  kStatusJobStarted = 0x80     // the command at job_index began to move (cut short if dropped)
};

// Timing constants of the protocol (docs/protocol.md "Timing").
enum {
  kInterByteTimeoutMs = 200,  // a partial frame older than this is dropped (kTruncated)
  kLinkTimeoutMs = 2000       // running with no valid frame this long -> feed hold
};

// What a letter means in the command direction (from the message table).
FrameKind command_kind(uint8_t letter);

// The message's name in the table ("feed move (linear XY)"), for messages and logs; 0 for a
// letter not defined in that direction. start is kCommandStart or kReplyStart.
const char* message_name(uint8_t start, uint8_t letter);

}  // namespace proto

#endif  // FIRMWARE_PROTOCOL_WIRE_CODES_H
