// Where the sender takes a job's commands from: a list held whole, or a plan encoded as the
// sender goes, of which only the commands not yet acknowledged (and a short history for
// messages) are kept, so a job's memory does not grow with its length.
#ifndef HOST_LIB_STREAM_COMMAND_SOURCE_H
#define HOST_LIB_STREAM_COMMAND_SOURCE_H

#include <cstddef>  // size_t
#include <deque>    // std::deque
#include <vector>   // std::vector

#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/resume_scan.h"  // JobPass

namespace host {

class CommandSource {
 public:
  virtual ~CommandSource() = default;
  // Commands in the whole stream.
  virtual size_t size() const = 0;
  // Command i (< size()), not released yet.
  virtual const QueuedCommand& at(size_t i) = 0;
  // Commands before `index` will not be asked for again (the controller stored them).
  virtual void release_before(size_t index) { (void)index; }
  // Whether command i is still held (messages name only those).
  virtual bool holds(size_t i) const { return i < size(); }
};

// A list held whole by the caller (resumes, set-up frames, tests).
class CommandList : public CommandSource {
 public:
  explicit CommandList(const std::vector<QueuedCommand>& commands) : commands_(commands) {}
  size_t size() const override { return commands_.size(); }
  const QueuedCommand& at(size_t i) override { return commands_[i]; }

 private:
  const std::vector<QueuedCommand>& commands_;
};

// The plan's commands as encode_job() would
// give them (after a set-up, if one is set), encoded step by step as the sender reaches them;
// released commands are dropped. The plan must outlive the source. Throws PlanError as encode_job()
// does.
class EncodedJob : public CommandSource {
 public:
  EncodedJob(const JobPlan& plan, const EncodeOptions& options);
  // The plan's commands only: not the set-up.
  const EncodedJobSummary& summary() const { return summary_; }
  // Commands sent before the job's (a height map, a resume's prefix); only before the first
  // at().
  void set_setup(std::vector<QueuedCommand> setup);
  // More commands before those (a height map before a resume's prefix); only before the
  // first at().
  void prepend_setup(const std::vector<QueuedCommand>& setup);
  // The job from its command `from` on (a resume: resume_prefix() gives `from`); the commands
  // before it are encoded and dropped. Only before the first at().
  void start_at(size_t from);
  size_t size() const override { return setup_count_ + summary_.commands - skip_; }
  const QueuedCommand& at(size_t i) override;
  void release_before(size_t index) override;
  bool holds(size_t i) const override { return i >= first_ && i < first_ + held_.size(); }
  // Commands held now, and the most held at once (the bounded buffer: tests check it).
  size_t held() const { return held_.size(); }
  size_t held_max() const { return held_max_; }

 private:
  EncodedJobSummary summary_;
  size_t setup_count_ = 0;
  size_t skip_ = 0;     // the job's commands before start_at()'s
  size_t skipped_ = 0;  // of those, dropped so far
  JobEncoder encoder_;
  std::deque<QueuedCommand> held_;  // commands first_ .. first_ + held_.size() - 1
  size_t first_ = 0;
  size_t held_max_ = 0;
  std::vector<QueuedCommand> batch_;
};

// The plan's commands as encode_job() gives them, one pass per call (the resume's scans).
JobPass pass_over(const JobPlan& plan, const EncodeOptions& options, uint16_t job_id);

}  // namespace host

#endif  // HOST_LIB_STREAM_COMMAND_SOURCE_H
