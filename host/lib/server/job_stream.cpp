// Two cursors over one job's stream: one the sender reads, one the progress reads.
#include "host/lib/server/job_stream.h"

#include <stdexcept>  // std::logic_error

namespace host::server {

JobStream::JobStream(const JobPlan& plan, const EncodeOptions& enc) : plan_(plan), enc_(enc) {
  auto send = std::make_unique<EncodedJob>(plan, enc);
  auto track = std::make_unique<EncodedJob>(plan, enc);
  job_id_ = send->summary().job_id;
  job_commands_ = send->summary().job_commands;
  whole_job_size_ = send->summary().commands;
  wire_bytes_ = send->summary().wire_bytes;
  send_job_ = send.get();
  track_job_ = track.get();
  send_ = std::move(send);
  track_ = std::move(track);
}

void JobStream::start_at(size_t from, std::vector<QueuedCommand> prefix) {
  if (send_job_ == nullptr) throw std::logic_error("JobStream: start_at on a hook's list");
  // The bytes of the job's commands left out.
  size_t index = 0;
  resumed_step_ = -1;
  pass_over(plan_, enc_, job_id_)([&](const QueuedCommand& c) {
    if (index >= from && resumed_step_ < 0) resumed_step_ = c.step;
    if (index++ < from) wire_bytes_ -= frame_bytes(c);
  });
  add_bytes(prefix);
  for (EncodedJob* job : {send_job_, track_job_}) {
    job->set_setup(prefix);
    job->start_at(from);
  }
}

void JobStream::use_list(std::vector<QueuedCommand> list) {
  list_ = std::move(list);
  wire_bytes_ = 0;
  add_bytes(list_);
  send_ = std::make_unique<CommandList>(list_);
  track_ = std::make_unique<CommandList>(list_);
  send_job_ = track_job_ = nullptr;
}

void JobStream::set_setup(const std::vector<QueuedCommand>& frames) {
  if (frames.empty()) return;
  add_bytes(frames);
  if (send_job_ == nullptr) {
    list_.insert(list_.begin(), frames.begin(), frames.end());
    return;
  }
  // After a resume's prefix has been set: the frames go before it.
  for (EncodedJob* job : {send_job_, track_job_}) job->prepend_setup(frames);
}

void JobStream::add_bytes(const std::vector<QueuedCommand>& commands) {
  for (const QueuedCommand& c : commands) wire_bytes_ += frame_bytes(c);
}

template <typename Field>
int JobStream::first_from(size_t index, Field field) {
  int found = -1;
  for (size_t i = index; i < track_->size() && found < 0; ++i) found = field(track_->at(i));
  track_->release_before(std::min(index, track_->size()));
  return found;
}

int JobStream::step_from(size_t index) {
  return first_from(index, [](const QueuedCommand& c) { return c.step; });
}

int JobStream::first_uncut_curve(size_t executed) {
  return first_from(executed, [](const QueuedCommand& c) { return c.curve; });
}

size_t JobStream::first_step_index() {
  for (size_t i = 0; i < track_->size(); ++i) {
    if (track_->at(i).step >= 0) return i;
  }
  return track_->size();
}

size_t JobStream::held_max() const {
  if (send_job_ == nullptr) return list_.size();
  return std::max(send_job_->held_max(), track_job_->held_max());
}

}  // namespace host::server
