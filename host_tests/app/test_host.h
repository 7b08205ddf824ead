// A small test-side host: builds command frames with the protocol codecs, keeps a window of
// unacknowledged queued frames with go-back-N retransmission (like host/lib/stream), decodes
// replies with the shared parser, and can mangle what it sends (drops, duplicates, CRC
// errors, garbage, random chunking) to test the controller's link handling.
#ifndef HOST_TESTS_APP_TEST_HOST_H
#define HOST_TESTS_APP_TEST_HOST_H

#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "firmware/core/spline.h"
#include "firmware/protocol/codec.h"
#include "firmware/protocol/parser.h"
#include "host_tests/app/fake_board.h"

namespace fake_app {

struct Impairments {
  double drop = 0;       // probability a frame is lost on the way
  double duplicate = 0;  // probability a frame is sent twice
  double corrupt = 0;    // probability one byte of a frame is flipped (CRC error)
  double garbage = 0;    // probability of random bytes before a frame
  int max_chunk = 0;     // 0: all bytes at once; else random 1..max_chunk bytes per ms
};

class TestHost {
 public:
  struct Frame {
    uint8_t letter;
    std::vector<uint8_t> payload;
  };

  explicit TestHost(FakeLink* link, uint32_t seed = 1) : link_(link), rng_(seed) {}

  Impairments impair;
  std::vector<proto::ErrorReply> errors;  // every *E received
  std::vector<proto::AlarmReply> alarms;
  proto::ProbeResultReply probe{};  // the last *T
  int probe_replies = 0;
  proto::StatusReply status{};
  bool have_status = false;
  bool session_open = false;
  proto::SessionReply session{};  // the newest *I
  int acks = 0;
  int timeouts = 0;

  template <typename Msg>
  static Frame make(const Msg& msg) {
    proto::Payload p;
    if (proto::encode(msg, &p) != proto::ErrorCode::kOk) return {0, {}};
    return {uint8_t(Msg::kLetter), std::vector<uint8_t>(p.bytes, p.bytes + p.length)};
  }

  // Queued (ordered) frames to deliver.
  void queue(const Frame& f) { frames_.push_back(f); }
  template <typename Msg>
  void queue(const Msg& msg) {
    queue(make(msg));
  }

  // Real-time and immediate frames go out at once (with their own seq counters).
  template <typename Msg>
  void send_realtime(const Msg& msg) {
    const Frame f = make(msg);
    transmit(f.letter, ++realtime_seq_, f.payload, false);
  }
  void open_session(uint8_t version = proto::kProtocolVersion) {
    session_seq_ = uint8_t(session_seq_ + 1);
    const Frame f = make(proto::SessionCmd{version});
    transmit(f.letter, session_seq_, f.payload, false);
    first_seq_ = uint8_t(session_seq_ + 1);
    frames_.clear();
    base_ = next_ = 0;
    session_open = false;
  }
  void query_status() { transmit(proto::kCmdStatus, status_seq_++, {}, false); }
  void query_probe() { transmit(proto::kCmdProbeResult, status_seq_++, {}, false); }
  // Any frame with a chosen seq, outside the window bookkeeping (for sequence tests).
  void send_raw(uint8_t letter, uint8_t seq, const std::vector<uint8_t>& payload) {
    transmit(letter, seq, payload, false);
  }
  uint8_t first_seq() const { return first_seq_; }

  bool all_acked() const { return base_ == frames_.size(); }
  size_t acked() const { return base_; }

  // One virtual millisecond: read replies, send within the window, retransmit on timeout,
  // move bytes into the controller's receive queue, poll status every 250 ms.
  void step(long now_ms) {
    now_ = now_ms;
    read_replies();
    if (session_open) {
      while (next_ < frames_.size() && next_ - base_ < proto::kWindowFrames) {
        transmit(frames_[next_].letter, uint8_t(first_seq_ + next_), frames_[next_].payload, true);
        if (next_ == base_) sent_at_ = now_;
        ++next_;
      }
      if (base_ < next_ && now_ - sent_at_ > 300) {  // retransmit timer: go back
        ++timeouts;
        next_ = base_;
        sent_at_ = now_;
      }
      if (now_ - last_query_ >= 250) {
        last_query_ = now_;
        query_status();
      }
    }
    deliver();
  }

 private:
  void transmit(uint8_t letter, uint8_t seq, const std::vector<uint8_t>& payload, bool impaired) {
    uint8_t buf[proto::kMaxFrameBytes];
    const uint8_t n = proto::encode_frame(proto::kCommandStart, letter, seq, payload.data(),
                                          uint8_t(payload.size()), buf, sizeof buf);
    std::vector<uint8_t> bytes(buf, buf + n);
    std::uniform_real_distribution<double> u(0, 1);
    if (impaired && u(rng_) < impair.garbage) {
      const int k = 1 + int(rng_() % 12);
      for (int i = 0; i < k; ++i) wire_.push_back(uint8_t(rng_()));
    }
    if (impaired && u(rng_) < impair.drop) return;
    if (impaired && u(rng_) < impair.corrupt)
      bytes[rng_() % bytes.size()] ^= uint8_t(1 + rng_() % 255);
    wire_.insert(wire_.end(), bytes.begin(), bytes.end());
    if (impaired && u(rng_) < impair.duplicate) wire_.insert(wire_.end(), buf, buf + n);
  }

  void deliver() {
    size_t n = wire_.size();
    if (impair.max_chunk > 0) n = std::min(n, size_t(1 + rng_() % impair.max_chunk));
    link_->rx.insert(link_->rx.end(), wire_.begin(), wire_.begin() + long(n));
    wire_.erase(wire_.begin(), wire_.begin() + long(n));
  }

  size_t index_of(uint8_t seq) const { return uint8_t(seq - first_seq_); }

  void read_replies() {
    for (uint8_t b : link_->tx) {
      for (proto::ParseEvent ev = parser_.feed(b); ev != proto::ParseEvent::kNone;
           ev = parser_.poll()) {
        if (ev == proto::ParseEvent::kFrame) on_reply(parser_.frame());
      }
    }
    link_->tx.clear();
  }

  void on_reply(const proto::Frame& f) {
    switch (f.letter) {
      case proto::kReplySession:
        session_open = proto::decode_frame(f, &session) == proto::ErrorCode::kOk;
        break;
      case proto::kReplyAck: {
        ++acks;
        const size_t i = index_of(f.seq);
        if (i >= base_ && i < next_) {
          base_ = i + 1;
          sent_at_ = now_;
        }
        break;
      }
      case proto::kReplyError: {
        proto::ErrorReply r;
        if (proto::decode_frame(f, &r) != proto::ErrorCode::kOk) break;
        errors.push_back(r);
        const bool resend = r.code == proto::ErrorCode::kSeqGap ||
                            r.code == proto::ErrorCode::kBadCrc ||
                            r.code == proto::ErrorCode::kBusy;
        const size_t i = index_of(r.next_expected_seq);
        if (resend && i >= base_ && i <= next_) {
          base_ = i;
          next_ = i;
          sent_at_ = now_;
        }
        break;
      }
      case proto::kReplyStatus: {
        proto::StatusReply r;
        if (proto::decode_frame(f, &r) != proto::ErrorCode::kOk) break;
        status = r;
        have_status = true;
        const size_t i = index_of(r.next_expected_seq);
        if (session_open && i > base_ && i <= next_) base_ = i;
        break;
      }
      case proto::kReplyAlarm: {
        proto::AlarmReply r;
        if (proto::decode_frame(f, &r) == proto::ErrorCode::kOk) alarms.push_back(r);
        break;
      }
      case proto::kReplyProbeResult:
        if (proto::decode_frame(f, &probe) == proto::ErrorCode::kOk) ++probe_replies;
        break;
      default:
        break;
    }
  }

  FakeLink* link_;
  std::mt19937 rng_;
  proto::Parser parser_{proto::kReplyStart};
  std::vector<Frame> frames_;
  std::vector<uint8_t> wire_;
  size_t base_ = 0, next_ = 0;
  uint8_t first_seq_ = 1, session_seq_ = 0, realtime_seq_ = 0, status_seq_ = 0;
  long now_ = 0, sent_at_ = 0, last_query_ = 0;
};

// #B + #D frames for a spline (controls in frames of up to 6, then knots in frames of 15).
inline std::vector<TestHost::Frame> spline_frames(const core::Spline& s, uint16_t feed_um_s,
                                                  int32_t tool_offset_um = 0) {
  std::vector<TestHost::Frame> out;
  proto::SplineHeaderCmd h{s.degree,     s.rational, s.control_count,
                           s.knot_count, feed_um_s,  tool_offset_um};
  out.push_back(TestHost::make(h));
  for (uint16_t i = 0; i < s.control_count; i += proto::kMaxDataControls) {
    proto::SplineDataCmd d{};
    d.control_index = uint8_t(i);
    d.control_n = uint8_t(std::min<int>(proto::kMaxDataControls, s.control_count - i));
    d.knot_index = 0;
    d.knot_n = 0;
    for (int k = 0; k < d.control_n; ++k) d.control[k] = s.control[i + k];
    out.push_back(TestHost::make(d));
  }
  for (uint16_t i = 0; i < s.knot_count; i += proto::kMaxDataKnots) {
    proto::SplineDataCmd d{};
    d.control_index = uint8_t(s.control_count);
    d.control_n = 0;
    d.knot_index = uint8_t(i);
    d.knot_n = uint8_t(std::min<int>(proto::kMaxDataKnots, s.knot_count - i));
    for (int k = 0; k < d.knot_n; ++k) d.knot[k] = s.knot[i + k];
    out.push_back(TestHost::make(d));
  }
  return out;
}

}  // namespace fake_app

#endif  // HOST_TESTS_APP_TEST_HOST_H
