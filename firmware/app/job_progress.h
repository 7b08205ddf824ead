// Job progress for the status (resume after a lost link or an abort): the #J numbering of
// the commands as they are stored, and the first job command that has not finished, whatever
// #J marks are queued behind it; kept through #I, #X and alarms until the job moves on
// (docs/protocol.md, #J "Progress"). Background loop only; the tick's part comes by snapshot.
#ifndef FIRMWARE_APP_JOB_PROGRESS_H
#define FIRMWARE_APP_JOB_PROGRESS_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/app/command_queue.h"  // CommandQueue, QueueItem
#include "firmware/app/tick_link.h"      // TickStatus
#include "firmware/protocol/messages.h"  // JobMarkCmd, StatusReply

namespace app {

class JobProgress {
 public:
  JobProgress();
  // #J: the commands stored from now on are numbered from the mark.
  void mark(const proto::JobMarkCmd& c);
  // While numbering: the command about to be stored gets the next job index (a spline the
  // mark's first point); stored() once it is.
  void number(QueueItem* item) const;
  void stored();
  // The oldest item finished executing.
  void finished(const QueueItem& item);
  // The queue drops its waiting items (from in_flight() on): the first job command dropped
  // unstarted follows the executing ones; the numbering ends until the next #J.
  void dropping(const CommandQueue& queue);
  // Moves the reported progress to the first job command not finished (see the .cpp).
  // stopped: the tick has dropped its ring. True when a numbered item is queued.
  bool track(const CommandQueue& queue, const TickStatus& tick, bool stopped);
  // A completed stop: a command cut short stays the first unfinished one.
  void stop_completed(const CommandQueue& queue, const TickStatus& tick) {
    if (track(queue, tick, true)) next_pending_ = false;
  }
  // The status's job flags (kStatusJob, kStatusJobStarted), index, point and id.
  uint8_t status_flags() const;
  void fill_status(proto::StatusReply* r) const;

 private:
  void report(int32_t index, uint16_t point, uint16_t id, bool started);

  // The next job command not stored yet: the index and first point the next stored command
  // gets while numbering (a #J sets them), or, after a drop, the first dropped one.
  int32_t next_index_;
  uint16_t first_point_;
  uint16_t next_id_;   // the job_id of that #J
  bool numbering_;     // a #J was stored in this session: stored commands get numbers
  bool next_pending_;  // nothing is stored for next_index yet (a #J with nothing after it)
  bool valid_;         // a #J was stored since power-up: index/point mean something
  uint16_t id_;        // the reported command's job (its #J's job_id)
  int32_t index_;      // first job command not finished
  uint16_t point_;     // curve point the tool heads for in it (points before reached)
  bool started_;       // that command began to move (through a resume's lead-in: it had)
};

}  // namespace app

#endif  // FIRMWARE_APP_JOB_PROGRESS_H
