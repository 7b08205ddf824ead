// One pass over a job's commands that keeps only what resuming it at one job command needs
// (the set-up before it, the move before it, that command's frames, the job's travel
// height): a resume of a streamed job re-encodes the plan instead of holding its list.
#ifndef HOST_LIB_STREAM_RESUME_SCAN_H
#define HOST_LIB_STREAM_RESUME_SCAN_H

#include <cstddef>     // size_t
#include <cstdint>     // int32_t, uint16_t
#include <functional>  // std::function
#include <vector>      // std::vector

#include "host/lib/stream/job_encoder.h"  // QueuedCommand

namespace host {

// A job's commands in order (encode_job()'s, starting with #J), one pass per call: a list's,
// or a plan encoded again (pass_over() in command_source.h).
using CommandVisitor = std::function<void(const QueuedCommand&)>;
using JobPass = std::function<void(const CommandVisitor&)>;
JobPass pass_over(const std::vector<QueuedCommand>& job);

// What the job holds around job command job_index (the controller's numbering: every command
// but #J and the spline data frames).
class ResumeScan {
 public:
  ResumeScan(const JobPass& job, int32_t job_index);

  int32_t job_index() const { return job_index_; }     // the job command looked for
  size_t commands() const { return count_; }           // in the whole job
  int32_t job_commands() const { return job_count_; }  // job commands in the whole job
  uint16_t job_id() const { return crc_; }             // job_id_of() the job
  // Stream index of job command job_index; commands() when the job has none (it finished).
  size_t from() const { return from_; }
  bool found() const { return from_ < count_; }
  // That command, then its spline data frames if it is a #B (empty when not found).
  const std::vector<QueuedCommand>& at() const { return at_; }
  // Before it: the newest move (#G #F #C #B and its data frames; empty if none), the newest
  // #U (null if none), the #N that switched the spindle on if it is still on and the dwells
  // right after it (empty if off), the newest #Z or #C (null if none).
  const std::vector<QueuedCommand>& last_move() const { return last_move_; }
  const QueuedCommand* resolution() const { return have_resolution_ ? &resolution_ : nullptr; }
  const std::vector<QueuedCommand>& spindle_on() const { return spindle_; }
  const QueuedCommand* height() const { return have_height_ ? &height_ : nullptr; }
  // The chord tolerance of the #U in force at the command and at the last move.
  int at_tolerance_um() const { return at_tolerance_um_; }
  int last_move_tolerance_um() const { return last_move_tolerance_um_; }
  // The job's pen-up height: its highest #Z (INT32_MIN when it has none).
  int32_t travel_z_um() const { return travel_z_um_; }

 private:
  void add(const QueuedCommand& c);
  void add_before(const QueuedCommand& c);

  int32_t job_index_;
  size_t count_ = 0;
  int32_t job_count_ = 0;
  uint16_t crc_ = 0xFFFF;
  size_t from_ = SIZE_MAX;
  std::vector<QueuedCommand> at_;
  std::vector<QueuedCommand> last_move_;
  QueuedCommand resolution_;
  bool have_resolution_ = false;
  std::vector<QueuedCommand> spindle_;
  bool spindle_dwells_ = false;  // the last command was the #N on or a dwell after it
  QueuedCommand height_;
  bool have_height_ = false;
  int tolerance_um_;
  int at_tolerance_um_;
  int last_move_tolerance_um_;
  int32_t travel_z_um_ = INT32_MIN;
  std::vector<QueuedCommand>* spline_into_ = nullptr;  // collects the open #B's data frames
};

}  // namespace host

#endif  // HOST_LIB_STREAM_RESUME_SCAN_H
