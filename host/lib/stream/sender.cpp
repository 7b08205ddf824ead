// The streaming sender: window, delayed acks, go-back-N on errors and time-outs, real-time
// frames, keep-alive status polling, and the job verdict.
#include "host/lib/stream/sender.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::max
#include <thread>     // std::this_thread

#include "firmware/protocol/codec.h"  // proto::decode_frame, proto::encode
#include "host/lib/plan/counted.h"    // counted: "1 command", "2 commands"

namespace host {

namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

const char* error_name(proto::ErrorCode code) {
  switch (code) {
    case proto::ErrorCode::kOk:
      return "ok";
    case proto::ErrorCode::kBadCrc:
      return "bad CRC";
    case proto::ErrorCode::kLengthTooLarge:
      return "length too large";
    case proto::ErrorCode::kBadLetter:
      return "bad letter";
    case proto::ErrorCode::kTruncated:
      return "truncated frame";
    case proto::ErrorCode::kRxOverrun:
      return "receive overrun";
    case proto::ErrorCode::kUnknownCommand:
      return "unknown command";
    case proto::ErrorCode::kPayloadLength:
      return "wrong payload length";
    case proto::ErrorCode::kFieldRange:
      return "field out of range";
    case proto::ErrorCode::kSeqGap:
      return "sequence gap";
    case proto::ErrorCode::kSeqOutOfWindow:
      return "sequence out of window";
    case proto::ErrorCode::kSeqStale:
      return "stale real-time frame";
    case proto::ErrorCode::kNoSession:
      return "no session (controller restarted?)";
    case proto::ErrorCode::kVersionUnsupported:
      return "protocol version unsupported";
    case proto::ErrorCode::kBusy:
      return "busy";
    case proto::ErrorCode::kAlarmActive:
      return "machine in alarm";
    case proto::ErrorCode::kAborted:
      return "stream aborted";
    case proto::ErrorCode::kBadState:
      return "not allowed in this state";
    case proto::ErrorCode::kSplineSequence:
      return "spline data out of sequence";
    case proto::ErrorCode::kGeometry:
      return "spline geometry rejected";
    case proto::ErrorCode::kNotZeroed:
      return "machine not zeroed";
    case proto::ErrorCode::kOutOfTravel:
      return "target outside the machine travel";
    case proto::ErrorCode::kHeightMap:
      return "height map refused (out of sequence, or spans more than 1 mm)";
  }
  return "unknown error";
}

const char* alarm_name(proto::Alarm alarm) {
  switch (alarm) {
    case proto::Alarm::kNone:
      return "none";
    case proto::Alarm::kLimitSwitch:
      return "limit switch tripped";
    case proto::Alarm::kDriverFault:
      return "stepper driver fault";
    case proto::Alarm::kPowerLost:
      return "driver power lost (e-stop?)";
    case proto::Alarm::kFollowingError:
      return "following error";
    case proto::Alarm::kMotionChipFault:
      return "motion controller (TMC428) fault";
    case proto::Alarm::kPathFault:
      return "path generation fault";
    case proto::Alarm::kSoftLimit:
      return "soft limit";
    case proto::Alarm::kProbeNoContact:
      return "probe: no contact within the depth limit";
    case proto::Alarm::kProbeClosedAtStart:
      return "probe: input closed before probing (clip shorted?)";
    case proto::Alarm::kProbeSpindleOn:
      return "probe: spindle on";
    case proto::Alarm::kProbeMissing:
      return "probe: this machine has no probe input";
  }
  return "unknown alarm";
}

// Frame-level and gap errors: the frame did not arrive intact; resend from the expected seq.
bool is_resend_error(proto::ErrorCode code) {
  const int v = static_cast<int>(code);
  return (v >= 1 && v <= 5) || code == proto::ErrorCode::kSeqGap;
}

}  // namespace

const char* machine_state_name(proto::MachineState state) {
  switch (state) {
    case proto::MachineState::kIdle:
      return "idle";
    case proto::MachineState::kRunning:
      return "running";
    case proto::MachineState::kHolding:
      return "holding";
    case proto::MachineState::kHeld:
      return "held";
    case proto::MachineState::kZeroing:
      return "zeroing";
    case proto::MachineState::kAlarm:
      return "alarm";
    case proto::MachineState::kPaused:
      return "paused";
  }
  return "unknown";
}

bool machine_waits_for_operator(proto::MachineState state) {
  return state != proto::MachineState::kIdle && state != proto::MachineState::kRunning;
}

const char* outcome_name(JobOutcome outcome) {
  switch (outcome) {
    case JobOutcome::kCompleted:
      return "completed";
    case JobOutcome::kAborted:
      return "aborted";
    case JobOutcome::kAlarm:
      return "alarm";
    case JobOutcome::kRejected:
      return "rejected";
    case JobOutcome::kLinkLost:
      return "link lost";
    case JobOutcome::kStalled:
      return "stalled";
  }
  return "?";
}

Sender::Sender(Link& link, SenderOptions options)
    : link_(link),
      options_(options),
      parser_(proto::kReplyStart),
      last_reply_(now()),
      last_byte_(last_reply_) {}

Clock::time_point Sender::now() const {
  return options_.clock ? options_.clock() : Clock::now();
}

// Writes one command frame.
void Sender::send_frame(uint8_t letter, uint8_t seq, const std::vector<uint8_t>& payload) {
  uint8_t buf[proto::kMaxFrameBytes];
  const uint8_t n = proto::encode_frame(proto::kCommandStart, letter, seq, payload.data(),
                                        static_cast<uint8_t>(payload.size()), buf, sizeof buf);
  if (n == 0) throw LinkError(fmt::format("internal: frame '{}' does not encode", char(letter)));
  link_.write(buf, n);
  stats_.frames_sent++;
  stats_.bytes_sent += n;
}

// Reads what arrives within `wait` and handles every reply frame. True if any frame came.
bool Sender::pump(milliseconds wait) {
  uint8_t buf[512];
  const size_t n = link_.read(buf, sizeof buf, wait);
  if (n > 0) last_byte_ = now();
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    for (proto::ParseEvent ev = parser_.feed(buf[i]); ev != proto::ParseEvent::kNone;
         ev = parser_.poll()) {
      if (ev == proto::ParseEvent::kFrame) {
        handle_reply(parser_.frame());
        any = true;
      } else {
        stats_.reply_rejects++;
      }
    }
  }
  if (n == 0 && parser_.in_frame() &&
      now() - last_byte_ > milliseconds(proto::kInterByteTimeoutMs)) {
    for (proto::ParseEvent ev = parser_.expire(); ev != proto::ParseEvent::kNone;
         ev = parser_.poll()) {
      if (ev == proto::ParseEvent::kFrame) handle_reply(parser_.frame());
    }
  }
  return any;
}

// "command 12 ('B' spline header, plan step 7, curve 3)" for messages (names from the
// message table).
std::string Sender::where(size_t index) const {
  if (win_.commands == nullptr || !win_.commands->holds(index)) return "a command";
  const QueuedCommand& c = win_.commands->at(index);
  const char* name = proto::message_name(proto::kCommandStart, c.letter);
  std::string s = fmt::format("command {} ('{}' {}", index, static_cast<char>(c.letter),
                              name != nullptr ? name : "unknown");
  if (c.step >= 0) s += fmt::format(", plan step {}", c.step);
  if (c.curve >= 0) s += fmt::format(", curve {}", c.curve);
  return s + ")";
}

void Sender::handle_reply(const proto::Frame& frame) {
  last_reply_ = now();
  switch (frame.letter) {
    case proto::kReplySession: {
      proto::SessionReply r;
      if (proto::decode_frame(frame, &r) == proto::ErrorCode::kOk && frame.seq == session_.seq) {
        session_.reply = r;
        session_.open = true;
      }
      break;
    }
    case proto::kReplyProbeResult: {
      proto::ProbeResultReply r;
      if (proto::decode_frame(frame, &r) != proto::ErrorCode::kOk) break;
      last_probe_ = r;
      have_probe_ = true;
      break;
    }
    case proto::kReplyStatus: {
      proto::StatusReply r;
      if (proto::decode_frame(frame, &r) == proto::ErrorCode::kOk) handle_status(r);
      break;
    }
    case proto::kReplyAck: {
      proto::AckReply ack;
      if (proto::decode_frame(frame, &ack) == proto::ErrorCode::kOk) handle_ack(ack, frame.seq);
      break;
    }
    case proto::kReplyError: {
      proto::ErrorReply r;
      if (proto::decode_frame(frame, &r) == proto::ErrorCode::kOk) handle_error(r, frame.seq);
      break;
    }
    case proto::kReplyAlarm: {
      proto::AlarmReply r;
      if (proto::decode_frame(frame, &r) != proto::ErrorCode::kOk) break;
      failed_ = true;
      failure_ = JobOutcome::kAlarm;
      message_ = fmt::format("machine alarm: {}", alarm_name(r.alarm));
      break;
    }
    default:
      break;
  }
}

// *S: what the controller has stored and executed, its room, and lost frames to send again.
void Sender::handle_status(const proto::StatusReply& r) {
  last_status_ = r;
  have_status_ = true;
  session_.status_outstanding = false;
  if (status_before_resume_)
    status_before_resume_ = false;  // asked before the #R: says nothing of it
  else
    resume_sent_ = false;
  win_.queue_free = r.queue_free;
  if (win_.commands == nullptr) return;
  // Everything before next_expected is stored.
  const size_t stored = win_.index_of_seq(r.next_expected_seq);
  if (stored != SIZE_MAX && stored >= win_.base && stored <= win_.next) {
    win_.splines_free = r.spline_slots_free;
    win_.splines_known_at = stored;
  }
  if (stored != SIZE_MAX && stored > win_.base && stored <= win_.next) {
    win_.base = stored;
    win_.oldest_sent = now();
  }
  win_.track_executed(r.last_executed_seq);
  // No frame held: a busy refusal is over (its held frame's *O may have overtaken it).
  if (!(r.flags & proto::kStatusFramePending)) win_.busy_wait = false;
  // Unacknowledged frames past the time-out and none held: they were lost, go back.
  const milliseconds rto = rtt_.timeout(options_.min_rto);
  if (win_.base < win_.next && !(r.flags & proto::kStatusFramePending) &&
      now() - win_.oldest_sent > rto) {
    win_.next = win_.base;
    win_.busy_wait = false;
    win_.oldest_sent = now();
  }
}

// *O: the frame with this seq and every one before it is stored.
void Sender::handle_ack(const proto::AckReply& ack, uint8_t seq) {
  // v2: a real-time frame's *O says so; its seq is the real-time counter's, not the
  // ordered stream's.
  if (ack.realtime) {
    if (seq == session_.realtime_seq) session_.realtime_acked = true;
    return;
  }
  win_.queue_free = ack.queue_free;
  const size_t index = win_.index_of_seq(seq);
  if (index != SIZE_MAX && index >= win_.base && index < win_.next) {
    win_.splines_free = ack.spline_slots_free;
    win_.splines_known_at = index + 1;
    sample_round_trip(index);
    if (win_.queue_free >= 2 && win_.limit < win_.frames) ++win_.limit;
    win_.base = index + 1;  // acks are cumulative: the controller stores strictly in order
    win_.oldest_sent = now();
    win_.busy_wait = false;
  }
}

// *E: a frame to send again (lost, or refused for room), or the end of the job.
void Sender::handle_error(const proto::ErrorReply& r, uint8_t seq) {
  stats_.error_replies++;
  if (r.code == proto::ErrorCode::kSeqStale) return;  // superseded real-time frame
  // An older controller names its version: open the session in that one.
  if (r.code == proto::ErrorCode::kVersionUnsupported && !session_.open &&
      r.detail >= proto::kMinProtocolVersion && r.detail < session_.version) {
    session_.version = r.detail;
    session_.version_lowered = true;
    return;
  }
  if (win_.commands != nullptr && (is_resend_error(r.code) || r.code == proto::ErrorCode::kBusy)) {
    go_back(r);
    return;
  }
  if (win_.commands == nullptr && is_resend_error(r.code)) return;  // a lost #I/#?: we retry
  failed_ = true;
  failure_ = r.code == proto::ErrorCode::kAlarmActive ? JobOutcome::kAlarm
             : r.code == proto::ErrorCode::kAborted   ? JobOutcome::kAborted
                                                      : JobOutcome::kRejected;
  std::string detail;
  if (r.code == proto::ErrorCode::kGeometry) detail = fmt::format(" (geometry code {})", r.detail);
  message_ = fmt::format("controller refused {}: {}{}", where(win_.index_of_seq(seq)),
                         error_name(r.code), detail);
}

// Go-back-N from the frame the controller expects (a gap, a damaged frame, busy).
void Sender::go_back(const proto::ErrorReply& r) {
  const size_t expected = win_.index_of_seq(r.next_expected_seq);
  // One lost frame makes every later frame of the window answer seq_gap with the same
  // expected seq: go back once, not once per reply (the resent frames are on their way).
  if (r.code == proto::ErrorCode::kSeqGap && expected == win_.last_gap_expected &&
      now() - win_.last_gap_at < rtt_.timeout(options_.min_rto)) {
    return;
  }
  if (r.code == proto::ErrorCode::kSeqGap) {
    win_.last_gap_expected = expected;
    win_.last_gap_at = now();
  }
  win_.busy_wait = (r.code == proto::ErrorCode::kBusy);
  if (expected != SIZE_MAX && expected >= win_.base && expected <= win_.next) {
    win_.base = expected;
    // Busy: the expected frame is the one the controller holds; resend after it.
    win_.next = win_.busy_wait ? std::min(win_.next, expected + 1) : expected;
  }
  // The store is full (spline data can fill it before the queue's slot count says so):
  // send one frame at a time until acks show room again.
  if (win_.busy_wait) win_.limit = 1;
}

// The watchdog: true once nothing changed for stall_limit (acks, executions, position, state).
bool Sender::stalled() {
  const StallWatchdog::Seen s{win_.base,         win_.executed,     last_status_.x_um,
                              last_status_.y_um, last_status_.z_um, last_status_.state};
  const auto t = now();
  // Waiting for a person is not a stall: a hold asked for here or at the machine's panel,
  // zeroing, or a pause (#P) until the operator confirms. A hold the controller made because it
  // heard nothing is.
  const bool held =
      s.state == proto::MachineState::kHeld || s.state == proto::MachineState::kHolding ||
      s.state == proto::MachineState::kZeroing || s.state == proto::MachineState::kPaused;
  const bool waits_for_operator =
      operator_hold_ || (held && !(last_status_.flags & proto::kStatusLinkHold));
  return watchdog_.stalled(s, waits_for_operator, t, options_.stall_limit);
}

// The retransmission timer's round trip: smoothed (1/8 gain) over frames acknowledged at
// their first sending; a frame held by the controller (ack delayed for room) or sent again
// says nothing about the link and is left out.
void Sender::sample_round_trip(size_t index) {
  if (have_status_ && (last_status_.flags & proto::kStatusFramePending)) return;
  rtt_.acknowledged(index, now());
}

void Sender::query_status() {
  send_frame(proto::kCmdStatus, session_.status_seq++, {});
  stats_.status_queries++;
  session_.status_outstanding = true;
  session_.status_sent = now();
}

// Time for the next status query: each interval, or with a zero interval as soon as the
// previous one was answered (a lost query or reply is given up after 50 ms).
// A resume means something only to a machine in a hold: one this sender asked for, or one
// the last status shows (the panel's, the link watchdog's), unless a #R already went out
// since. Anything else would be refused (bad_state) and end the job.
bool Sender::resume_may_act() const {
  if (operator_hold_) return true;
  if (resume_sent_ || !have_status_) return false;
  return last_status_.state == proto::MachineState::kHolding ||
         last_status_.state == proto::MachineState::kHeld;
}

// A hold the link watchdog made (2 s without a frame: the link was cut) and nobody else
// asked for: the operator's hold (here or at the panel, no link flag) waits for the operator.
bool Sender::link_hold_to_resume() const {
  if (operator_hold_ || resume_sent_ || !have_status_) return false;
  if (!(last_status_.flags & proto::kStatusLinkHold)) return false;
  return last_status_.state == proto::MachineState::kHolding ||
         last_status_.state == proto::MachineState::kHeld;
}

bool Sender::status_due(Clock::time_point last_poll) const {
  if (options_.status_interval.count() > 0) {
    return now() - last_poll >= options_.status_interval;
  }
  return !session_.status_outstanding || now() - session_.status_sent > milliseconds(50);
}

proto::SessionReply Sender::open_session() {
  session_.open = false;
  // Again in an older version each time the controller names one (a few at most).
  while (!session_.open) {
    session_.version_lowered = false;
    const std::string failed = request(
        [this] {
          session_.seq = static_cast<uint8_t>(session_.seq + 1);
          proto::SessionCmd cmd{session_.version};
          proto::Payload p;
          proto::encode(cmd, &p);
          send_frame(proto::kCmdSession, session_.seq,
                     std::vector<uint8_t>(p.bytes, p.bytes + p.length));
        },
        [this] { return session_.open || failed_ || session_.version_lowered; }, "session reply");
    if (failed_) throw LinkError(message_);
    if (!failed.empty()) throw LinkError(failed);
  }
  win_.first_seq = static_cast<uint8_t>(session_.seq + 1);
  session_.realtime_seq = 0;
  return session_.reply;
}

// A request sent again each reply timeout until `answered`. It fails (the reason returned,
// empty on success) once nothing at all was heard for the silence limit, counted from the
// request at the earliest: the link is dead, as a stream judges it; or when the controller,
// still talking, left 5 tries unanswered.
std::string Sender::request(const std::function<void()>& send,
                            const std::function<bool()>& answered, const char* what) {
  const auto asked = now();
  for (int unanswered = 0;;) {
    const auto sent = now();
    send();
    while (!answered() && now() - sent < options_.reply_timeout) pump(milliseconds(5));
    if (answered()) return {};
    if (now() - std::max(last_reply_, asked) >= options_.silence_limit) {
      return fmt::format("{}: no reply for {} ms", link_.name(), options_.silence_limit.count());
    }
    if (last_reply_ >= sent && ++unanswered == 5) {
      return fmt::format("{}: no {} from the controller", link_.name(), what);
    }
  }
}

proto::StatusReply Sender::read_status() {
  have_status_ = false;
  const std::string failed =
      request([this] { query_status(); }, [this] { return have_status_; }, "status reply");
  if (!failed.empty()) throw LinkError(failed);
  return last_status_;
}

proto::ProbeResultReply Sender::read_probe_result() {
  have_probe_ = false;
  const std::string failed =
      request([this] { send_frame(proto::kCmdProbeResult, session_.status_seq++, {}); },
              [this] { return have_probe_; }, "probe result");
  if (!failed.empty()) throw LinkError(failed);
  return last_probe_;
}

proto::StatusReply Sender::read_status_at_rest(milliseconds limit) {
  const auto deadline = now() + limit;
  for (;;) {
    const proto::StatusReply s = read_status();
    if (s.state != proto::MachineState::kRunning && s.state != proto::MachineState::kHolding)
      return s;
    if (now() > deadline) {
      throw LinkError(fmt::format("{}: the machine did not come to rest within {} ms", link_.name(),
                                  limit.count()));
    }
    pump(milliseconds(20));
  }
}

// Sends a real-time frame and waits for its ack, retrying with the same seq.
void Sender::send_realtime(uint8_t letter, const std::vector<uint8_t>& payload) {
  session_.realtime_seq = static_cast<uint8_t>(session_.realtime_seq + 1);
  session_.realtime_acked = false;
  for (int attempt = 0; attempt < 3 && !session_.realtime_acked; ++attempt) {
    send_frame(letter, session_.realtime_seq, payload);
    const auto deadline = now() + options_.reply_timeout;
    while (!session_.realtime_acked && now() < deadline) pump(milliseconds(5));
  }
}

bool Sender::set_override(int percent) {
  send_realtime(proto::kCmdOverride, {static_cast<uint8_t>(percent)});
  return read_status().override_percent == percent;  // the machine's word, any version
}

// Starts manual zeroing if the machine is not zeroed and waits for the operator's confirm.
bool Sender::ensure_zeroed(const std::function<void(const Progress&)>& on_progress) {
  have_status_ = false;
  std::string failed =
      request([this] { query_status(); }, [this] { return have_status_; }, "status reply");
  if (!failed.empty()) {
    failed_ = true;
    failure_ = JobOutcome::kLinkLost;
    message_ = std::move(failed);
    return false;
  }
  if ((last_status_.flags & proto::kStatusZeroed) || !options_.zero_first) return true;
  proto::ZeroingCmd zero{options_.zero_axes};
  proto::Payload p;
  proto::encode(zero, &p);
  QueuedCommand c;
  c.letter = proto::kCmdZeroing;
  c.payload.assign(p.bytes, p.bytes + p.length);
  const std::vector<QueuedCommand> one{c};
  CommandList one_list(one);
  CommandSource* saved = win_.commands;
  win_.commands = &one_list;
  win_.base = win_.next = win_.executed = 0;
  auto last_poll = now();
  bool aborted = false;
  while (!failed_) {
    if (requests_.abort_asked()) {
      aborted = true;  // win_.commands must not be left on the list that dies here
      break;
    }
    if (win_.next == 0) {
      send_frame(c.letter, win_.first_seq, c.payload);
      win_.next = 1;
      win_.oldest_sent = now();
    }
    if (status_due(last_poll)) {
      query_status();
      last_poll = now();
      if (win_.base == 1 && (last_status_.flags & proto::kStatusZeroed)) break;
      Progress progress;
      progress.status = last_status_;
      if (on_progress) on_progress(progress);
    }
    pump(milliseconds(5));
    if (now() - last_reply_ > options_.silence_limit) {
      failed_ = true;
      failure_ = JobOutcome::kLinkLost;
      message_ =
          fmt::format("{}: no reply for {} ms", link_.name(), options_.silence_limit.count());
    }
  }
  win_.commands = saved;
  if (failed_ || aborted) return false;
  win_.first_seq = static_cast<uint8_t>(win_.first_seq + 1);
  if (note_) {
    note_(
        "zeroed the machine (#M): its zero is the tool's position when the zeroing was "
        "confirmed");
  }
  return true;
}

// Lets go of what the controller has stored, but for the 128 commands before it (replies
// name commands by an 8-bit seq up to 128 back) and those the spline slot count still needs.
void Sender::release_stored(CommandSource& commands) {
  constexpr size_t kHistory = 128;
  const size_t keep_from = std::min(win_.base, win_.splines_known_at);
  if (keep_from > kHistory) commands.release_before(keep_from - kHistory);
  rtt_.release_before(win_.base);
}

JobOutcome Sender::run(const std::vector<QueuedCommand>& commands,
                       const std::function<void(const Progress&)>& on_progress) {
  CommandList list(commands);
  return run(list, on_progress);
}

// Sets the window up for a new ordered stream of commands.
void Sender::start_window(CommandSource& commands) {
  win_.commands = &commands;
  rtt_.start(true);
  win_.base = win_.next = win_.executed = 0;
  win_.busy_wait = false;
  win_.queue_free = session_.reply.queue_slots;
  win_.splines_free = SendWindow::kSplineSlotsUnknown;
  win_.splines_known_at = 0;
  win_.frames =
      std::max<size_t>(1, std::min<size_t>(session_.reply.window_frames, proto::kWindowFrames));
  win_.limit = win_.frames;
  win_.high_water = 0;
  last_reply_ = now();
  watchdog_.start(now());
  operator_hold_ = false;
  resume_sent_ = false;
  status_before_resume_ = false;
}

// The operator's requests as real-time frames; an abort (or a veto on sending more) ends
// the job: true, with *outcome set.
bool Sender::take_requests(CommandSource& commands, JobOutcome* outcome) {
  if (requests_.abort_asked()) {
    send_realtime(proto::kCmdAbort, {});
    message_ = fmt::format("{} after {} of {}", requests_.abort_cause(), win_.executed,
                           counted(commands.size(), "command"));
    *outcome = JobOutcome::kAborted;
    return true;
  }
  if (requests_.take_hold()) {
    send_realtime(proto::kCmdHold, {});
    operator_hold_ = true;
  }
  if (requests_.take_resume()) {
    if (resume_may_act()) {
      send_realtime(proto::kCmdResume, {});
      resume_sent_ = true;
      status_before_resume_ = session_.status_outstanding;
    }
    operator_hold_ = false;
  }
  if (const int pct = requests_.take_override()) {
    send_realtime(proto::kCmdOverride, {static_cast<uint8_t>(pct)});
  }
  if (link_hold_to_resume()) {
    // The link is back (this status came through it): the job goes on along its path, its
    // queue kept through the feed hold, as if it had never stopped.
    send_realtime(proto::kCmdResume, {});
    resume_sent_ = true;
    status_before_resume_ = session_.status_outstanding;
    stats_.link_hold_resumes++;
  }
  if (failed_) {
    *outcome = failure_;
    return true;
  }
  if (win_.next < commands.size() && options_.send_veto) {
    std::string veto = options_.send_veto();
    if (!veto.empty()) {
      send_realtime(proto::kCmdAbort, {});
      message_ = std::move(veto);
      *outcome = JobOutcome::kAborted;
      return true;
    }
  }
  return false;
}

// Fills the window (frames and bytes) unless the controller said busy.
void Sender::fill_window(CommandSource& commands) {
  const size_t rx_bytes = std::max<size_t>(session_.reply.rx_buffer_bytes, proto::kMaxFrameBytes);
  size_t inflight_bytes = 0;
  release_stored(commands);
  for (size_t i = win_.base; i < win_.next; ++i) inflight_bytes += frame_bytes(commands.at(i));
  // In flight may be what the queue has room for plus the one frame it can hold.
  while (!win_.busy_wait && win_.next < commands.size() && win_.next - win_.base < win_.limit &&
         win_.next - win_.base <= win_.queue_free &&
         inflight_bytes + frame_bytes(commands.at(win_.next)) <= rx_bytes &&
         (commands.at(win_.next).letter != proto::kCmdSplineHeader || win_.spline_room())) {
    const QueuedCommand& command = commands.at(win_.next);
    if (win_.next == win_.base) win_.oldest_sent = now();
    send_frame(command.letter, static_cast<uint8_t>(win_.first_seq + win_.next), command.payload);
    inflight_bytes += frame_bytes(command);
    if (win_.next < win_.high_water) stats_.retransmits++;
    rtt_.sent(win_.next, win_.next < win_.high_water, now());  // Karn: again, no sample
    ++win_.next;
    win_.high_water = std::max(win_.high_water, win_.next);
  }
}

// How the job ends now, if it does: every command executed and the machine idle, no
// progress for the stall limit, or no reply for the silence limit.
bool Sender::job_ended(CommandSource& commands, JobOutcome* outcome) {
  if (win_.base == commands.size() && win_.executed == commands.size() && have_status_ &&
      last_status_.state == proto::MachineState::kIdle) {
    message_ = commands.size() == 1
                   ? std::string("the 1 command executed")
                   : fmt::format("all {} executed", counted(commands.size(), "command"));
    win_.first_seq = static_cast<uint8_t>(win_.first_seq + commands.size());
    *outcome = JobOutcome::kCompleted;
    return true;
  }
  if (stalled()) {
    std::string why;
    if (last_status_.flags & proto::kStatusLinkHold)
      why = "; the controller holds the job: it heard nothing from the host for 2 s";
    else if (last_status_.flags & proto::kStatusFramePending)
      why = "; the controller holds a frame it has no room for";
    message_ = fmt::format(
        "no progress for {} s: {} of {} executed, {} stored; machine {} at "
        "({:.3f}, {:.3f}, {:.3f}) mm{}",
        options_.stall_limit.count() / 1000.0, win_.executed, counted(commands.size(), "command"),
        win_.base, machine_state_name(last_status_.state), last_status_.x_um / 1000.0,
        last_status_.y_um / 1000.0, last_status_.z_um / 1000.0, why);
    *outcome = JobOutcome::kStalled;
    return true;
  }
  if (now() - last_reply_ > options_.silence_limit) {
    message_ = fmt::format("{}: no reply for {} ms after {} of {} executed", link_.name(),
                           options_.silence_limit.count(), win_.executed,
                           counted(commands.size(), "command"));
    *outcome = JobOutcome::kLinkLost;
    return true;
  }
  return false;
}

JobOutcome Sender::run(CommandSource& commands,
                       const std::function<void(const Progress&)>& on_progress) {
  // However run() ends (a throw from on_progress too), it keeps no pointer to the commands:
  // a later status reply must not read a list that is gone.
  struct Forget {
    CommandSource*& commands;
    ~Forget() { commands = nullptr; }
  } forget{win_.commands};
  if (!session_.open) open_session();
  failed_ = false;
  rtt_.start(false);  // no round-trip samples from the zeroing frame
  if (!ensure_zeroed(on_progress)) {
    if (requests_.abort_asked()) {
      send_realtime(proto::kCmdAbort, {});
      message_ = std::string(requests_.abort_cause()) + " while zeroing";
      return JobOutcome::kAborted;
    }
    return failure_;
  }
  start_window(commands);
  auto last_poll = now() - options_.status_interval;
  JobOutcome outcome = JobOutcome::kCompleted;
  const auto report = [&] {
    Progress progress;
    progress.acked = win_.base;
    progress.executed = win_.executed;
    progress.total = commands.size();
    progress.status = last_status_;
    if (on_progress && have_status_) on_progress(progress);
  };
  while (!take_requests(commands, &outcome)) {
    fill_window(commands);
    if (status_due(last_poll)) {
      query_status();
      last_poll = now();
      report();
    }
    pump(milliseconds(1));
    if (job_ended(commands, &outcome)) {
      // The last report of a completed job says all of it done (a progress line ended at
      // 111/112 before "all 112 commands executed").
      if (outcome == JobOutcome::kCompleted) report();
      break;
    }
  }
  return outcome;
}

}  // namespace host
