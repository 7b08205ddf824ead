// The commands of a job the workshop runs: the plan encoded as the sender goes (from a resume
// point, after set-up frames), or a resume hook's list; and a second cursor over the same
// stream for its progress (the plan step running, the first uncut curve), so that neither
// holds the whole job.
#ifndef HOST_LIB_SERVER_JOB_STREAM_H
#define HOST_LIB_SERVER_JOB_STREAM_H

#include <cstddef>  // size_t
#include <cstdint>  // uint16_t
#include <memory>   // std::unique_ptr
#include <vector>   // std::vector

#include "host/lib/stream/command_source.h"

namespace host::server {

class JobStream {
 public:
  // The whole plan (which must outlive the stream), as encode_job() gives it.
  JobStream(const JobPlan& plan, const EncodeOptions& enc);
  // The whole job's id (#J) and its job commands' count (what a resume point's index counts),
  // also when it is continued.
  uint16_t job_id() const { return job_id_; }
  size_t job_commands() const { return job_commands_; }
  // Every command of the whole job (its stream indices run to this), also when continued.
  size_t whole_job_size() const { return whole_job_size_; }
  // The job's commands from stream index `from` on, after `prefix` (a resume's).
  void start_at(size_t from, std::vector<QueuedCommand> prefix);
  // A resume hook's whole list instead of the plan's commands.
  void use_list(std::vector<QueuedCommand> list);
  // Frames before everything else (a height map); once, before the first command is read.
  void set_setup(const std::vector<QueuedCommand>& frames);

  CommandSource& source() { return *send_; }
  size_t size() const { return send_->size(); }
  size_t wire_bytes() const { return wire_bytes_; }
  // The plan step of the first command at or after `index` that has one (-1: none). Indices
  // asked for never go back: what is before them is let go.
  int step_from(size_t index);
  // The curve of the first command at or after `executed` that has one (-1: none left).
  int first_uncut_curve(size_t executed);
  // The index of the first command with a plan step (size(): none): the set-up before it
  // (a height map's frames, #J) moves nothing along the path. Asked before step_from.
  size_t first_step_index();
  // A continued run's first plan step of the job's own commands (start_at's `from` on; the
  // prefix's way back may carry earlier steps); -1 when not started part-way.
  int resumed_step() const { return resumed_step_; }
  // The most commands either cursor held at once (bounded: tests check it).
  size_t held_max() const;

 private:
  void add_bytes(const std::vector<QueuedCommand>& commands);
  template <typename Field>
  int first_from(size_t index, Field field);

  const JobPlan& plan_;
  EncodeOptions enc_;
  uint16_t job_id_ = 0;
  size_t job_commands_ = 0;
  size_t whole_job_size_ = 0;
  int resumed_step_ = -1;
  size_t wire_bytes_ = 0;
  std::vector<QueuedCommand> list_;  // a hook's
  std::unique_ptr<CommandSource> send_, track_;
  EncodedJob* send_job_ = nullptr;  // send_ and track_ when they encode the plan
  EncodedJob* track_job_ = nullptr;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_STREAM_H
