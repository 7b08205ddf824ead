// Frames in, replies out (see dispatcher.h and docs/protocol.md section 4).
#include "firmware/app/dispatcher.h"

#include <string.h>  // memcpy, memset

#include "firmware/config/machine_config.h"  // kLinkRxBufferBytes
#include "firmware/core/spline.h"            // kMaxDegree, kMaxControlPoints
#include "firmware/protocol/codec.h"         // write_frame, decode_frame

namespace app {

Dispatcher::Dispatcher() : port_(0), sink_(0), parser_(proto::kCommandStart) {
  // last_error_ up to held_length_ (declared in that order) start at zero (kOk, no session):
  // one memset of the block, less code than a store per member.
  uint8_t* const first = reinterpret_cast<uint8_t*>(&last_error_);
  memset(first, 0, (size_t)(reinterpret_cast<uint8_t*>(&held_length_ + 1) - first));
}

void Dispatcher::init(hal::SerialPort* port, CommandSink* sink) {
  port_ = port;
  sink_ = sink;
}

uint16_t Dispatcher::rejected_frames() const {
  return parser_.rejected_total();
}

void Dispatcher::poll(uint16_t now_ms) {
  flush_tx();
  retry_held();
  const uint16_t rx_errors = port_->take_rx_errors();
  for (uint16_t i = 0; i < rx_errors && i < 16; ++i) parser_.note_rx_error();
  uint8_t byte;
  uint16_t n = 0;
  while (n < kMaxRxBytesPerPoll && port_->read_byte(&byte)) {
    ++n;
    last_byte_ms_ = now_ms;
    on_events(parser_.feed(byte), now_ms);
  }
  // A partial frame that stopped arriving is dropped, its bytes re-scanned.
  if (n == 0 && parser_.in_frame() &&
      (uint16_t)(now_ms - last_byte_ms_) >= (uint16_t)proto::kInterByteTimeoutMs)
    on_events(parser_.expire(), now_ms);
  flush_tx();
}

// The parser's event ev and those it has queued behind it.
void Dispatcher::on_events(proto::ParseEvent ev, uint16_t now_ms) {
  for (; ev != proto::ParseEvent::kNone; ev = parser_.poll()) {
    if (ev == proto::ParseEvent::kFrame) {
      on_frame(parser_.frame(), now_ms);
    } else {
      on_rejected(parser_.last_error(), now_ms);
    }
  }
}

void Dispatcher::on_rejected(proto::ErrorCode code, uint16_t now_ms) {
  last_error_ = code;
  // A corrupted frame: tell the host at once so it resends without waiting for its timer
  // (rate-limited: a burst of noise must not flood the link).
  if (code == proto::ErrorCode::kBadCrc && session_ &&
      (uint16_t)(now_ms - last_error_reply_ms_) >= (uint16_t)kErrorReplyGapMs) {
    last_error_reply_ms_ = now_ms;
    const proto::ErrorReply r = {code, 0, window_.next_expected()};
    reply(r, window_.next_expected());
  }
}

void Dispatcher::on_frame(const proto::Frame& f, uint16_t now_ms) {
  last_valid_ms_ = now_ms;
  switch (f.kind) {
    case proto::FrameKind::kQueued:
      on_queued(f);
      break;
    case proto::FrameKind::kRealtime:
      on_realtime(f);
      break;
    case proto::FrameKind::kImmediate:
      on_immediate(f);
      break;
    default:
      error(f.seq, proto::ErrorCode::kUnknownCommand, 0);
      break;
  }
}

void Dispatcher::on_immediate(const proto::Frame& f) {
  if (f.letter == proto::kCmdStatus) {
    proto::StatusReply r;
    sink_->fill_status(&r);
    r.flags =
        (uint8_t)(r.flags | (held_ ? proto::kStatusFramePending : 0) |
                  (session_ ? proto::kStatusSession : 0) | (aborted_ ? proto::kStatusAborted : 0));
    r.next_expected_seq = window_.next_expected();
    r.last_error = last_error_;
    r.rejected_frames = parser_.rejected_total();
    r.queue_free = sink_->queue_free();
    reply(r, f.seq);
    return;
  }
  if (f.letter == proto::kCmdProbeResult) {  // read-only like #?: any time
    proto::ProbeResultReply r;
    sink_->fill_probe_result(&r);
    reply(r, f.seq);
    return;
  }
  proto::SessionCmd cmd;
  const proto::ErrorCode e = proto::decode_frame(f, &cmd);
  if (e != proto::ErrorCode::kOk) {
    error(f.seq, e, 0);
    return;
  }
  if (cmd.protocol_version < proto::kMinProtocolVersion ||
      cmd.protocol_version > proto::kProtocolVersion) {
    error(f.seq, proto::ErrorCode::kVersionUnsupported, proto::kProtocolVersion);
    return;
  }
  sink_->reset_session();
  window_.reset((uint8_t)(f.seq + 1U));
  realtime_.reset();
  held_ = false;
  session_ = true;
  session_version_ = cmd.protocol_version;
  aborted_ = false;
  proto::SessionReply r;
  r.protocol_version = cmd.protocol_version;
  r.max_payload = proto::kMaxPayload;
  r.window_frames = proto::kWindowFrames;
  r.rx_buffer_bytes = config::kLinkRxBufferBytes;
  r.max_degree = core::kMaxDegree;
  r.max_control_points = core::kMaxControlPoints;
  sink_->fill_session(&r);
  reply(r, f.seq);
}

// Whether a real-time command only stops the machine: such a command is always allowed.
static bool stops_motion(uint8_t letter) {
  return letter == proto::kCmdHold || letter == proto::kCmdAbort;
}

void Dispatcher::on_realtime(const proto::Frame& f) {
  const bool stops = stops_motion(f.letter);
  bool newest = false;  // the seq becomes the reference once the command has acted
  if (!session_) {
    // #H and #X act even before #I. With no session there is no real-time seq to compare
    // with (#I forgets it anyway), so a repeated stop acts again, which is harmless.
    if (!stops) {
      error(f.seq, proto::ErrorCode::kNoSession, 0);
      return;
    }
  } else {
    const proto::SeqClass c = realtime_.classify(f.seq);
    if (c == proto::SeqClass::kDuplicate) {
      ack(f.seq, true);  // done already; never acted on twice
      return;
    }
    // An older #R/#V/#C was superseded and must not undo a later command; an older #H or
    // #X may be the retransmission of a lost stop, and stopping is always allowed.
    newest = c != proto::SeqClass::kStale;
    if (!newest && !stops) {
      error(f.seq, proto::ErrorCode::kSeqStale, 0);
      return;
    }
  }
  const proto::ErrorCode e = sink_->realtime(f);
  if (e != proto::ErrorCode::kOk) {
    error(f.seq, e, 0);
    return;
  }
  if (newest) realtime_.accept(f.seq);  // the newest seq stays the reference
  ack(f.seq, true);
}

// Every outcome is one code: kOk acknowledges (*O), any other is the *E (one call of each).
void Dispatcher::on_queued(const proto::Frame& f) {
  proto::ErrorCode e = proto::ErrorCode::kOk;
  uint8_t detail = 0;
  if (!session_) {
    e = proto::ErrorCode::kNoSession;
  } else if (aborted_) {
    e = proto::ErrorCode::kAborted;
  } else {
    switch (window_.classify(f.seq)) {
      case proto::SeqClass::kNew: {
        // A command of a later version than the session's does not exist in it (detail:
        // the version that brings it).
        const uint8_t since = proto::version_of_command(f.letter);
        if (since > session_version_) {
          e = proto::ErrorCode::kUnknownCommand;
          detail = since;
          break;
        }
        e = sink_->store(f, &detail);
        if (e == proto::ErrorCode::kBusy) {
          hold(f);  // ack delayed until there is room
          return;
        }
        if (e == proto::ErrorCode::kOk) window_.accept(f.seq);
        break;
      }
      case proto::SeqClass::kDuplicate:
        break;  // stored before: acknowledged again, not stored twice
      case proto::SeqClass::kPending:
        return;  // the held copy's ack will come
      case proto::SeqClass::kAhead:
        e = window_.pending() ? proto::ErrorCode::kBusy : proto::ErrorCode::kSeqGap;
        break;
      default:
        e = proto::ErrorCode::kSeqOutOfWindow;
        break;
    }
  }
  if (e == proto::ErrorCode::kOk) {
    ack(f.seq, false);
  } else {
    error(f.seq, e, detail);
  }
}

void Dispatcher::hold(const proto::Frame& f) {
  held_ = true;
  held_letter_ = f.letter;
  held_seq_ = f.seq;
  held_length_ = f.length;
  memcpy(held_payload_, f.payload, f.length);
  window_.mark_pending(f.seq);
}

// Offers the held frame again; stored -> ack now (the delayed acknowledgement).
void Dispatcher::retry_held() {
  if (!held_) return;
  proto::Frame f;
  f.start = proto::kCommandStart;
  f.letter = held_letter_;
  f.seq = held_seq_;
  f.length = held_length_;
  f.kind = proto::FrameKind::kQueued;
  f.payload = held_payload_;
  uint8_t detail = 0;
  const proto::ErrorCode e = sink_->store(f, &detail);
  if (e == proto::ErrorCode::kBusy) return;
  held_ = false;
  window_.clear_pending();
  if (e == proto::ErrorCode::kOk) {
    window_.accept(f.seq);
    ack(f.seq, false);
  } else {
    error(f.seq, e, detail);
  }
}

void Dispatcher::abort_stream() {
  aborted_ = true;
  held_ = false;
  window_.clear_pending();
}

void Dispatcher::send_alarm(proto::Alarm alarm, proto::MachineState state) {
  const proto::AlarmReply r = {alarm, state};
  alarm_seq_ = (uint8_t)(alarm_seq_ + 1U);
  reply(r, alarm_seq_);
}

void Dispatcher::ack(uint8_t seq, bool realtime) {
  const proto::AckReply r = {sink_->queue_free(), sink_->spline_slots_free(), realtime};
  reply(r, seq);
}

void Dispatcher::error(uint8_t seq, proto::ErrorCode code, uint8_t detail) {
  last_error_ = code;
  const proto::ErrorReply r = {code, detail, window_.next_expected()};
  reply(r, seq);
}

namespace {

template <typename Msg>
proto::ErrorCode encode_reply(const void* msg, proto::Payload* out) {
  return proto::encode(*static_cast<const Msg*>(msg), out);
}

}  // namespace

// Encodes a reply into the transmit buffer; if even that is full the reply is dropped (the
// host recovers with #? and its retransmit timer). Per message type only the call: the
// payload and the frame are send_frame's, one copy for every reply.
template <typename Msg>
void Dispatcher::reply(const Msg& msg, uint8_t seq) {
  send_frame(&encode_reply<Msg>, &msg, (uint8_t)Msg::kStart, (uint8_t)Msg::kLetter, seq);
}

// The frame around the encoded payload, shared by every reply.
void Dispatcher::send_frame(ReplyEncoder encode, const void* msg, uint8_t start, uint8_t letter,
                            uint8_t seq) {
  proto::Payload payload;
  if (encode(msg, &payload) != proto::ErrorCode::kOk) return;
  if (kTxBytes - tx_len_ < proto::kMaxFrameBytes) flush_tx();
  const uint8_t size = proto::encode_frame(start, letter, seq, payload.bytes, payload.length,
                                           tx_ + tx_len_, (uint16_t)(kTxBytes - tx_len_));
  if (size == 0) return;
  tx_len_ = (uint16_t)(tx_len_ + size);
  flush_tx();
}

void Dispatcher::flush_tx() {
  if (tx_len_ == 0) return;
  const uint16_t sent = port_->write(tx_, tx_len_);
  if (sent >= tx_len_) {
    tx_len_ = 0;
    return;
  }
  memmove(tx_, tx_ + sent, tx_len_ - sent);
  tx_len_ = (uint16_t)(tx_len_ - sent);
}

}  // namespace app
