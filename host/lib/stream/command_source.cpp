// The streamed job: a first pass counts the commands and makes the job's id (#J carries it),
// the second encodes as the sender asks.
#include "host/lib/stream/command_source.h"

#include <algorithm>  // std::max, std::min
#include <stdexcept>  // std::logic_error

namespace host {

EncodedJob::EncodedJob(const JobPlan& plan, const EncodeOptions& options)
    : summary_(summarize_job(plan, options)), encoder_(plan, options, summary_.job_id) {}

void EncodedJob::set_setup(std::vector<QueuedCommand> setup) {
  if (setup_count_ != 0 || first_ != 0 || !held_.empty())
    throw std::logic_error("EncodedJob: set-up set after the job began");
  setup_count_ = setup.size();
  for (QueuedCommand& c : setup) held_.push_back(std::move(c));
  held_max_ = held_.size();
}

void EncodedJob::prepend_setup(const std::vector<QueuedCommand>& setup) {
  if (first_ != 0 || held_.size() != setup_count_)
    throw std::logic_error("EncodedJob: set-up added after the job began");
  held_.insert(held_.begin(), setup.begin(), setup.end());
  setup_count_ += setup.size();
  held_max_ = std::max(held_max_, held_.size());
}

void EncodedJob::start_at(size_t from) {
  if (first_ != 0 || held_.size() != setup_count_)
    throw std::logic_error("EncodedJob: start set after the job began");
  skip_ = std::min(from, summary_.commands);
}

const QueuedCommand& EncodedJob::at(size_t i) {
  if (i < first_) throw std::logic_error("EncodedJob: command asked for after its release");
  while (i >= first_ + held_.size()) {
    batch_.clear();
    if (!encoder_.next(&batch_)) throw std::logic_error("EncodedJob: command past the job's end");
    for (QueuedCommand& c : batch_) {
      if (skipped_ < skip_)
        ++skipped_;
      else
        held_.push_back(std::move(c));
    }
    held_max_ = std::max(held_max_, held_.size());
  }
  return held_[i - first_];
}

void EncodedJob::release_before(size_t index) {
  while (first_ < index && !held_.empty()) {
    held_.pop_front();
    ++first_;
  }
}

JobPass pass_over(const JobPlan& plan, const EncodeOptions& options, uint16_t job_id) {
  return [&plan, options, job_id](const CommandVisitor& visit) {
    JobEncoder encoder(plan, options, job_id);
    std::vector<QueuedCommand> batch;
    while (encoder.next(&batch)) {
      for (const QueuedCommand& c : batch) visit(c);
      batch.clear();
    }
  };
}

}  // namespace host
