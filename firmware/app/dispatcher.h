// The dispatcher of the background loop: received bytes -> frame parser -> sequence checks ->
// the command sink (store queued frames, act on real-time ones) -> replies. Holds one queued
// frame with its ack delayed while there is no room (the flow control), never drops data.
#ifndef FIRMWARE_APP_DISPATCHER_H
#define FIRMWARE_APP_DISPATCHER_H

#include <stdint.h>  // uint8_t, uint16_t

#include "firmware/protocol/codec.h"            // Payload
#include "firmware/protocol/frame.h"            // Frame
#include "firmware/protocol/messages.h"         // StatusReply, Alarm
#include "firmware/protocol/parser.h"           // Parser
#include "firmware/protocol/sequence_window.h"  // SequenceWindow, RealtimeSequence
#include "hal/interfaces/serial_port.h"         // SerialPort

namespace app {

// What the dispatcher needs from the rest of the application.
class CommandSink {
 public:
  // A queued frame, next in order: kOk when stored; kBusy when there is no room yet (the
  // frame is held and offered again); any other code rejects it (*E, nothing stored).
  virtual proto::ErrorCode store(const proto::Frame& frame, uint8_t* detail) = 0;
  // A new real-time frame: kOk (acknowledged) or a code for *E.
  virtual proto::ErrorCode realtime(const proto::Frame& frame) = 0;
  // #I: stop motion, clear queues (the dispatcher resets its own stream state).
  virtual void reset_session() = 0;
  // *?: the machine's part of the status (the dispatcher adds the stream's fields).
  virtual void fill_status(proto::StatusReply* reply) = 0;
  // Ordered frames the sink can store right now (in *O and *?).
  virtual uint8_t queue_free() = 0;
  // Splines (#B) the sink can open right now (in *O and *?).
  virtual uint8_t spline_slots_free() = 0;
  // *I: what the application reports (queue slots, travel, feeds, firmware version).
  virtual void fill_session(proto::SessionReply* reply) = 0;
  // *T: the last probe's result (#T).
  virtual void fill_probe_result(proto::ProbeResultReply* reply) = 0;

 protected:
  ~CommandSink() {}
};

class Dispatcher {
 public:
  enum { kTxBytes = 192, kMaxRxBytesPerPoll = 160, kErrorReplyGapMs = 20 };
  Dispatcher();
  void init(hal::SerialPort* port, CommandSink* sink);
  // Drains received bytes (bounded), offers the held frame again, sends queued replies.
  void poll(uint16_t now_ms);
  // Unsolicited alarm notice.
  void send_alarm(proto::Alarm alarm, proto::MachineState state);
  // Marks the stream aborted (#X): queued frames get kAborted until #I; drops a held frame.
  void abort_stream();

  bool session_open() const { return session_; }
  uint8_t session_version() const { return session_version_; }
  bool aborted() const { return aborted_; }
  bool frame_held() const { return held_; }
  uint8_t next_expected() const { return window_.next_expected(); }
  proto::ErrorCode last_error() const { return last_error_; }
  uint16_t rejected_frames() const;
  // Milliseconds since the last CRC-valid frame, modulo 65536 (it wraps after 65.5 s; the
  // link watchdog acts at 2 s, long before).
  uint16_t ms_since_valid(uint16_t now_ms) const { return (uint16_t)(now_ms - last_valid_ms_); }

 private:
  void on_events(proto::ParseEvent ev, uint16_t now_ms);
  void on_frame(const proto::Frame& f, uint16_t now_ms);
  void on_rejected(proto::ErrorCode code, uint16_t now_ms);
  void on_queued(const proto::Frame& f);
  void on_realtime(const proto::Frame& f);
  void on_immediate(const proto::Frame& f);
  void retry_held();
  void hold(const proto::Frame& f);
  void ack(uint8_t seq, bool realtime);
  void error(uint8_t seq, proto::ErrorCode code, uint8_t detail);
  template <typename Msg>
  void reply(const Msg& msg, uint8_t seq);
  // A reply message's encoder (proto::encode of its type) on the message's bytes.
  typedef proto::ErrorCode (*ReplyEncoder)(const void* msg, proto::Payload* out);
  void send_frame(ReplyEncoder encode, const void* msg, uint8_t start, uint8_t letter, uint8_t seq);
  void flush_tx();

  hal::SerialPort* port_;
  CommandSink* sink_;
  proto::Parser parser_;
  proto::SequenceWindow window_;
  proto::RealtimeSequence realtime_;
  // last_error_ to held_length_: zeroed as one block by the constructor.
  proto::ErrorCode last_error_;
  uint16_t last_byte_ms_;
  uint16_t last_valid_ms_;
  uint16_t last_error_reply_ms_;
  uint16_t tx_len_;
  uint8_t alarm_seq_;
  bool session_;
  uint8_t session_version_;  // the protocol version the session was opened in
  bool aborted_;
  bool held_;
  uint8_t held_letter_;
  uint8_t held_seq_;
  uint8_t held_length_;
  uint8_t held_payload_[proto::kMaxPayload];
  uint8_t tx_[kTxBytes];
};

}  // namespace app

#endif  // FIRMWARE_APP_DISPATCHER_H
