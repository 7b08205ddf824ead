// Job progress (see job_progress.h and docs/protocol.md, #J).
#include "firmware/app/job_progress.h"

#include <string.h>  // memset

#include "firmware/protocol/message_table.h"  // PROTO_I32_MAX
#include "firmware/protocol/wire_codes.h"     // kStatusJob, kStatusJobStarted

namespace app {

// Every member starts at zero: one memset, less code than a store each (no virtuals).
JobProgress::JobProgress() {
  memset(static_cast<void*>(this), 0, sizeof *this);
}

// Numbers the commands that follow (not #D, not #J): job_index, job_index + 1, ... The
// progress moves there once everything queued before the mark has finished (a new job, or
// the resumed part of an old one).
void JobProgress::mark(const proto::JobMarkCmd& c) {
  numbering_ = true;
  next_index_ = c.job_index;
  first_point_ = c.first_point;
  next_id_ = c.job_id;
  next_pending_ = true;
  valid_ = true;
}

void JobProgress::number(QueueItem* item) const {
  if (!numbering_) return;
  item->job_index = next_index_;
  item->job_id = next_id_;
  if (item->kind == ItemKind::kSpline) item->spline.first_point = first_point_;
}

void JobProgress::stored() {
  if (!numbering_) return;
  next_index_ = next_index_ < PROTO_I32_MAX ? next_index_ + 1 : next_index_;
  first_point_ = 0;  // the mark's first point applies to the command right after it
  next_pending_ = false;
}

void JobProgress::finished(const QueueItem& item) {
  if (item.job_index == kNotInJob) return;
  index_ = item.job_index < PROTO_I32_MAX ? item.job_index + 1 : item.job_index;
  point_ = 0;
  id_ = item.job_id;
  started_ = false;
}

void JobProgress::dropping(const CommandQueue& queue) {
  for (uint8_t i = queue.in_flight(); i < queue.size(); ++i) {
    const QueueItem* item = queue.at(i);
    if (item->job_index == kNotInJob) continue;
    next_index_ = item->job_index;
    first_point_ = item->kind == ItemKind::kSpline ? item->spline.first_point : 0;
    next_id_ = item->job_id;
    next_pending_ = true;
    break;
  }
  numbering_ = false;  // until the next #J
}

// The first job command not finished is the first numbered item in the queue (un-numbered
// ones, a setup or a resume's lead-in, may run in front of it; later #J marks number only
// what follows them). If it is the oldest item the tick works on it and says how many of its
// curve points it reached. With no numbered item queued: the command a #J with nothing after
// it (or a drop) named, else what the last finished command left.
bool JobProgress::track(const CommandQueue& queue, const TickStatus& tick, bool stopped) {
  for (uint8_t i = 0; i < queue.size(); ++i) {
    const QueueItem* item = queue.at(i);
    if (item->job_index == kNotInJob) continue;
    const uint16_t first = item->kind == ItemKind::kSpline ? item->spline.first_point : 0;
    if (i != 0) {
      report(item->job_index, first, item->job_id, false);
      return true;
    }
    // After a stop only a command that was executing got anywhere.
    const bool ticked = !stopped || queue.in_flight() != 0;
    const uint32_t point = (uint32_t)first + (!ticked   ? 0
                                              : stopped ? tick.stopped_points
                                                        : tick.item_points);
    const bool started = ticked && (stopped ? tick.stopped_started : tick.item_started) != 0;
    report(item->job_index, point > 0xFFFFUL ? 0xFFFFU : (uint16_t)point, item->job_id, started);
    return true;
  }
  if (next_pending_) report(next_index_, first_point_, next_id_, false);
  return false;
}

// Sets the reported progress. The same command and point again (a resume's #J while its
// lead-in runs) keeps "began to move": the tool was on its path when the job stopped.
void JobProgress::report(int32_t index, uint16_t point, uint16_t id, bool started) {
  const bool same = index == index_ && point == point_ && id == id_;
  started_ = started || (same && started_);
  index_ = index;
  point_ = point;
  id_ = id;
}

uint8_t JobProgress::status_flags() const {
  return (uint8_t)((valid_ ? proto::kStatusJob : 0) |
                   (valid_ && started_ ? proto::kStatusJobStarted : 0));
}

void JobProgress::fill_status(proto::StatusReply* r) const {
  r->job_index = valid_ ? index_ : 0;
  r->curve_point = valid_ ? point_ : 0;
  r->job_id = valid_ ? id_ : 0;
}

}  // namespace app
