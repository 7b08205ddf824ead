// Streams queued commands to the controller with the protocol's flow control: a window of
// unacknowledged frames, delayed acks, go-back-N retransmission driven by status queries,
// real-time hold/resume/abort/override, and a clear verdict at the end.
#ifndef HOST_LIB_STREAM_SENDER_H
#define HOST_LIB_STREAM_SENDER_H

#include <chrono>      // std::chrono
#include <cstdint>     // uint8_t
#include <functional>  // std::function
#include <string>      // std::string
#include <vector>      // std::vector

#include "firmware/protocol/messages.h"  // proto::SessionReply, proto::StatusReply
#include "firmware/protocol/parser.h"    // proto::Parser
#include "host/lib/stream/command_source.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/link.h"
#include "host/lib/stream/link_session.h"
#include "host/lib/stream/operator_requests.h"
#include "host/lib/stream/round_trip_timer.h"
#include "host/lib/stream/send_window.h"
#include "host/lib/stream/stall_watchdog.h"

namespace host {

struct SenderOptions {
  std::chrono::milliseconds status_interval{250};  // keep-alive and progress polling
  std::chrono::milliseconds min_rto{250};          // retransmission timeout floor
  std::chrono::milliseconds reply_timeout{2000};   // #I / real-time frame answer
  std::chrono::milliseconds silence_limit{10000};  // no reply at all: the link is dead
  bool zero_first = true;                          // not zeroed: #M and wait for the operator
  uint8_t zero_axes = proto::kAxisMaskAll;
  // Watchdog: nothing acknowledged, nothing executed, the tool not moved and no state change
  // for this long while the job is not finished -> the job ends as kStalled (0 = off).
  // Waiting for the operator (a hold from here or the panel, zeroing) does not count.
  std::chrono::milliseconds stall_limit{30000};
  // Where time comes from (empty: the wall clock). The one-process simulator gives its
  // machine time here, so every interval and time-out above runs in machine time.
  std::function<std::chrono::steady_clock::time_point()> clock;
  // Asked before each batch of commands goes out (empty: always allowed). A non-empty answer
  // is why nothing more may be sent: the job is aborted (#X) at once with that message (the
  // workshop server: its lease on the job is gone).
  std::function<std::string()> send_veto;
};

// How a job ended; the CLI maps these to exit codes.
enum class JobOutcome {
  kCompleted,  // every command executed, machine idle
  kAborted,    // the operator aborted (#X)
  kAlarm,      // the machine raised an alarm
  kRejected,   // the controller refused a command (execution error)
  kLinkLost,   // the link closed or went silent
  kStalled     // the link answered but the job made no progress (SenderOptions::stall_limit)
};
const char* outcome_name(JobOutcome outcome);
// A machine state as one word (idle, running, holding, held, zeroing, alarm, paused): the
// same token in messages, progress lines and the workshop server's JSON.
const char* machine_state_name(proto::MachineState state);
// The machine stands still for the operator (a hold, a tool-change pause, manual zeroing, an
// alarm): time left estimates (send's progress line, the server's status) leave it out.
bool machine_waits_for_operator(proto::MachineState state);

struct SenderStats {
  size_t frames_sent = 0;  // every frame written, retransmissions included
  size_t bytes_sent = 0;
  size_t retransmits = 0;  // queued frames sent again
  size_t status_queries = 0;
  size_t error_replies = 0;  // *E received
  size_t reply_rejects = 0;  // reply bytes our parser dropped (noise)
  // #R sent because the link watchdog held the job (its link was cut for 2 s and is back).
  size_t link_hold_resumes = 0;
};

struct Progress {
  size_t acked = 0;     // commands stored by the controller
  size_t executed = 0;  // commands whose execution finished
  size_t total = 0;
  proto::StatusReply status{};
};

class Sender {
 public:
  Sender(Link& link, SenderOptions options);

  // #I until *I answers (or throws LinkError). Returns the controller's capabilities.
  proto::SessionReply open_session();
  // One status query and its reply (throws LinkError if none comes).
  proto::StatusReply read_status();
  // Status queries until the machine has come to rest (not running or holding: a #I or #X
  // decelerates along the path first); throws LinkError if that takes longer than `limit`.
  proto::StatusReply read_status_at_rest(std::chrono::milliseconds limit);
  // The controller's last probe result (#T -> *T, protocol 4); LinkError when none comes.
  proto::ProbeResultReply read_probe_result();
  // Sets the feed override now (session open, no job running): the real-time frame, then a
  // status. False when the status shows another override; LinkError when none comes.
  bool set_override(int percent);
  // Sends every command and waits until they have run. on_progress is called at each status.
  JobOutcome run(const std::vector<QueuedCommand>& commands,
                 const std::function<void(const Progress&)>& on_progress);
  // The same from a source the sender releases as the controller stores: it keeps only the
  // window of unacknowledged commands and the 128 before it (EncodedJob streams a plan).
  JobOutcome run(CommandSource& commands, const std::function<void(const Progress&)>& on_progress);

  // Requests from other threads or signal handlers; sent as real-time frames by run().
  void request_hold() { requests_.hold(); }
  void request_resume() { requests_.resume(); }
  // `why` begins the job's message (a string literal: a signal handler may give one).
  void request_abort(const char* why = "aborted by the operator") { requests_.abort(why); }
  void request_override(int percent) { requests_.override_percent(percent); }

  const SenderStats& stats() const { return stats_; }
  // The smoothed round trip the retransmission timer uses (starts at 50 ms).
  std::chrono::milliseconds smoothed_rtt() const { return rtt_.smoothed(); }
  // Why the job ended, for people: names the command, step and curve where relevant.
  const std::string& message() const { return message_; }
  // Commands executed when the job ended, as message() counts them (the last progress
  // report may be a few behind: it comes with a status reply).
  size_t executed() const { return win_.executed; }
  const proto::StatusReply& last_status() const { return last_status_; }
  // Gets a plain line for the log when the sender zeroes the machine itself (#M, the
  // operator confirmed): a log that is not a terminal had no line for it.
  void set_note(std::function<void(const std::string&)> note) { note_ = std::move(note); }

 private:
  struct Inflight;
  void send_frame(uint8_t letter, uint8_t seq, const std::vector<uint8_t>& payload);
  bool pump(std::chrono::milliseconds wait);
  void handle_reply(const proto::Frame& frame);
  void handle_status(const proto::StatusReply& r);
  void handle_ack(const proto::AckReply& ack, uint8_t seq);
  void handle_error(const proto::ErrorReply& r, uint8_t seq);
  void go_back(const proto::ErrorReply& r);
  void start_window(CommandSource& commands);
  bool take_requests(CommandSource& commands, JobOutcome* outcome);
  void fill_window(CommandSource& commands);
  bool job_ended(CommandSource& commands, JobOutcome* outcome);
  void send_realtime(uint8_t letter, const std::vector<uint8_t>& payload);
  std::string request(const std::function<void()>& send, const std::function<bool()>& answered,
                      const char* what);
  bool ensure_zeroed(const std::function<void(const Progress&)>& on_progress);
  void query_status();
  void release_stored(CommandSource& commands);
  void sample_round_trip(size_t index);
  bool status_due(std::chrono::steady_clock::time_point last_poll) const;
  bool resume_may_act() const;
  bool link_hold_to_resume() const;
  std::chrono::steady_clock::time_point now() const;
  bool stalled();
  std::string where(size_t index) const;

  Link& link_;
  SenderOptions options_;
  std::function<void(const std::string&)> note_;
  proto::Parser parser_;
  SenderStats stats_;
  std::string message_;
  proto::StatusReply last_status_{};
  proto::ProbeResultReply last_probe_{};
  bool have_probe_ = false;
  bool have_status_ = false;
  LinkSession session_;  // #I and the un-ordered frames
  SendWindow win_;       // the ordered stream of the current run()
  bool failed_ = false;
  JobOutcome failure_ = JobOutcome::kRejected;
  std::chrono::steady_clock::time_point last_reply_;
  // The last reply byte: a partial reply frame expires 200 ms after it (inter-byte time-out),
  // not 200 ms after the last whole frame (statuses 250 ms apart lost every split reply).
  std::chrono::steady_clock::time_point last_byte_;
  RoundTripTimer rtt_;
  StallWatchdog watchdog_;
  bool operator_hold_ = false;  // the operator asked for a hold (not a stall)
  // A #R went out and no status asked after it came back yet: another resume request is the
  // same one again (a second #R to a machine no longer held is refused, bad_state).
  bool resume_sent_ = false;
  bool status_before_resume_ = false;  // a #? asked before that #R is still to be answered

  OperatorRequests requests_;
};

}  // namespace host

#endif  // HOST_LIB_STREAM_SENDER_H
