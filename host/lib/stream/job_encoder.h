// Turns a job plan into the ordered command frames of the protocol (payloads; the sender
// adds sequence numbers), packing spline data to the controller's payload size.
#ifndef HOST_LIB_STREAM_JOB_ENCODER_H
#define HOST_LIB_STREAM_JOB_ENCODER_H

#include <cstdint>  // uint8_t
#include <string>   // std::string
#include <vector>   // std::vector

#include "firmware/protocol/messages.h"  // proto::SessionReply
#include "host/lib/plan/job_defaults.h"
#include "host/lib/plan/job_plan.h"

namespace host {

// One queued command: its letter and payload, and where in the job it came from.
struct QueuedCommand {
  uint8_t letter = 0;
  std::vector<uint8_t> payload;
  int step = -1;   // index into JobPlan::steps, -1 for set-up frames
  int curve = -1;  // index into JobPlan::curves, -1 if none
};

// How spline data goes on the wire.
enum class SplineFrames {
  kFixed,    // #D: fixed-width points and knots
  kCompact,  // #K: differences (a knot span of 2^31 or more in a #D frame)
  kContour   // #Q for a spline of lines and arcs in contour form (protocol 3), else #K
};

struct EncodeOptions {
  unsigned max_payload = 64;     // from the controller's *I
  uint16_t max_step_um = 1000;   // #U: longest distance between generated points
  uint16_t chord_tolerance_um =  // #U: chord error
      static_cast<uint16_t>(defaults::kChordToleranceMm * 1000 + 0.5);
  // #Z feed for pen-up moves: the reference machine's fastest Z, the controller's (*I) once
  // use_session() has seen it.
  uint16_t z_rapid_um_per_s = defaults::z_rapid_um_per_s();
  std::string title;                              // #S row 0 at the start (cut to 16 characters)
  SplineFrames splines = SplineFrames::kContour;  // set from the controller: use_session()
  // The controller's *I: when set, every target is checked against its travel first.
  const proto::SessionReply* controller = nullptr;
};

// What the controller's *I says about the encoding: its payload size, its fastest Z feed
// (pen-up moves), and #Q frames only from protocol version 3 on (an older controller gets #K
// frames).
void use_session(const proto::SessionReply& caps, EncodeOptions* o);

// The whole job as queued commands, in order, starting with #J 0 (job numbering). Tool offsets go
// in the spline header (the controller offsets; a straight feed with an offset becomes a degree-1
// spline). Throws PlanError on a step the protocol cannot carry (a feed above 65535 um/s, an offset
// beyond 100 mm) or, with options.controller, a target outside that controller's travel.
std::vector<QueuedCommand> encode_job(const JobPlan& plan, const EncodeOptions& options);

// The same commands one plan step at a time, for a sender that streams them (a job of a
// million steps is then never held encoded). job_id goes in the first #J (summarize_job()
// computes it in a first pass). The plan must outlive the encoder.
class JobEncoder {
 public:
  JobEncoder(const JobPlan& plan, const EncodeOptions& options, uint16_t job_id);
  // Appends the next commands (first the #J, title and #U; then each step's); false when
  // every step has been encoded. Throws PlanError as encode_job() does.
  bool next(std::vector<QueuedCommand>* out);

 private:
  void append_preamble(std::vector<QueuedCommand>* out) const;
  const JobPlan& plan_;
  EncodeOptions options_;
  uint16_t job_id_;
  bool started_ = false;
  size_t step_ = 0;
  core::PointUm at_ = {0, 0};  // where the tool is in X/Y (plans start at the zero point)
};

// What encode_job() would return, counted without keeping the commands.
struct EncodedJobSummary {
  size_t commands = 0;
  // Of them, the job commands (command_role kJobCommand): what a resume point's job command
  // index counts ("job command J of N").
  size_t job_commands = 0;
  size_t wire_bytes = 0;  // wire_bytes() of the commands
  uint16_t job_id = 0;    // job_id_of() the commands
};
EncodedJobSummary summarize_job(const JobPlan& plan, const EncodeOptions& options);

// The job's identity for #J and the status (send --resume checks it): CRC-16 over the
// letters and payloads of every command but #J.
uint16_t job_id_of(const std::vector<QueuedCommand>& commands);
// job_id_of() one command at a time (start from 0xFFFF).
uint16_t job_crc_update(uint16_t crc, const QueuedCommand& command);

// Bytes one command takes on the wire as a frame (header + payload + CRC).
size_t frame_bytes(const QueuedCommand& command);
// Bytes the commands take on the wire as frames.
size_t wire_bytes(const std::vector<QueuedCommand>& commands);

}  // namespace host

#endif  // HOST_LIB_STREAM_JOB_ENCODER_H
