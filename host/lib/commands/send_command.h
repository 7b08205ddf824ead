// `engraver send` as a function: a planned job encoded for the controller that answers on a
// link and streamed to it with the windowed sender; or, with a resume point, what is left of
// it. Also the exit code of a job's outcome (send and run).
#ifndef HOST_LIB_COMMANDS_SEND_COMMAND_H
#define HOST_LIB_COMMANDS_SEND_COMMAND_H

#include <cstdint>     // int32_t, uint16_t
#include <functional>  // std::function
#include <memory>      // std::shared_ptr
#include <optional>    // std::optional
#include <ostream>     // std::ostream
#include <string>      // std::string

#include "host/lib/heightmap/height_map.h"
#include "host/lib/plan/job_plan.h"
#include "host/lib/stream/job_encoder.h"  // EncodeOptions
#include "host/lib/stream/link.h"
#include "host/lib/stream/sender.h"

namespace host::commands {

// The tool's exit code for a job's outcome (0 for a completed job).
int exit_code_of(JobOutcome outcome);

// --resume-at INDEX[:POINT]: the job command and curve point a progress line shows.
struct ResumeAt {
  int32_t index = 0;
  uint16_t point = 0;
  std::string text;  // as given, for messages
};
// "12" or "12:40"; anything else ends the command with exit 2 (CommandFailure).
ResumeAt parse_resume_at(const std::string& text);
// Ends the command with exit 2 (CommandFailure: "--resume-at: '...': ...", with the job's
// count of job commands) when the job has no job command at.index, or its curve no point
// at.point: checked on the plan before a link is opened, not after connecting.
void check_resume_at(const JobPlan& plan, const EncodeOptions& encode, const ResumeAt& at);

// --no-zero: a machine that is not zeroed (its status says so, flags bit1) is refused with
// exit 1 (CommandFailure) before anything is sent: its first move would be refused anyway,
// after the set-up had gone out. `command` names the command in the message ("send").
void refuse_unzeroed_machine(Sender& sender, const std::string& command);

struct SendOptions {
  std::string file;                   // named in the log
  SenderOptions sender;               // zeroing, status interval
  EncodeOptions encode;               // the controller's session is added to it
  bool resume = false;                // continue from where the controller says the job stopped
  std::optional<ResumeAt> resume_at;  // continue from there (after a controller restart)
  // The height map the controller follows (sent before the job), already checked against it.
  std::optional<heightmap::HeightMap> map;
  // --probe: probes the blank through the sender and returns the map (checked against the job).
  std::function<heightmap::HeightMap(Sender&)> probe;
  // The operator's controls (signals): called with the sender once it exists, nullptr at the
  // end. While the job streams: holds whatever `while_streaming` returns (keys).
  std::function<void(Sender*)> attach_controls;
  std::function<std::shared_ptr<void>(Sender&)> while_streaming;
  std::function<void(const Progress&)> on_progress;
};

struct SendResult {
  JobOutcome outcome = JobOutcome::kCompleted;
  std::string message;
  SenderStats stats;
  uint16_t job_id = 0;           // the whole job's, also when resumed
  size_t commands = 0;           // streamed: the height map's, then the job's (or what was left)
  bool nothing_left = false;     // resumed a job the controller says has finished: nothing sent
  size_t commands_held_max = 0;  // the most encoded commands held at once (a window, not the job)
};

// How the job ended, in one line: "job aborted: aborted by the operator after 4 of 112
// commands (34 frames, 405 bytes, 0 resent after busy or loss)".
std::string send_ending_text(const SendResult& r);

// Opens a session on the link, encodes the job for that controller as the sender goes and
// streams it (or, with resume/resume_at, the rest of it: the plan is encoded again to find
// the resume point, no list of the job is held), saying on `log` what it does (the ending
// only of a completed job: the caller says how any other ended, once, as its last line). Throws
// CommandFailure when a resume point does not fit the job (exit 1), LinkError when the link fails
// to open a session.
SendResult send_job(Link& link, const JobPlan& plan, const SendOptions& o, std::ostream& log);

}  // namespace host::commands

#endif  // HOST_LIB_COMMANDS_SEND_COMMAND_H
