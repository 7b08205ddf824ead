// The one pass of a resume over a job's commands.
#include "host/lib/stream/resume_scan.h"

#include <algorithm>  // std::max

#include "firmware/core/curve_walker.h"      // kDefaultChordToleranceUm
#include "firmware/protocol/codec.h"         // proto:: messages
#include "host/lib/stream/encode_command.h"  // decoded
#include "host/lib/stream/spline_frames.h"   // is_spline_data

namespace host {

namespace {

bool is_move(uint8_t letter) {
  return letter == proto::kCmdRapidMove || letter == proto::kCmdFeedMove ||
         letter == proto::kCmdDrill || letter == proto::kCmdSplineHeader;
}

}  // namespace

JobPass pass_over(const std::vector<QueuedCommand>& job) {
  return [&job](const CommandVisitor& visit) {
    for (const QueuedCommand& c : job) visit(c);
  };
}

ResumeScan::ResumeScan(const JobPass& job, int32_t job_index)
    : job_index_(job_index),
      tolerance_um_(core::kDefaultChordToleranceUm),
      at_tolerance_um_(core::kDefaultChordToleranceUm),
      last_move_tolerance_um_(core::kDefaultChordToleranceUm) {
  job([this](const QueuedCommand& c) { add(c); });
  if (from_ == SIZE_MAX) from_ = count_;
}

void ResumeScan::add(const QueuedCommand& c) {
  const size_t index = count_++;
  crc_ = job_crc_update(crc_, c);
  if (c.letter == proto::kCmdZMove)
    travel_z_um_ = std::max(travel_z_um_, decoded<proto::ZMoveCmd>(c).z_um);
  if (is_spline_data(c.letter)) {
    if (spline_into_ != nullptr) spline_into_->push_back(c);
    return;
  }
  spline_into_ = nullptr;
  const bool job_command = proto::command_role(c.letter) == proto::CommandRole::kJobCommand;
  if (job_command && job_count_++ == job_index_) {
    from_ = index;
    at_tolerance_um_ = tolerance_um_;
    at_.push_back(c);
    if (c.letter == proto::kCmdSplineHeader) spline_into_ = &at_;
  }
  if (from_ == SIZE_MAX) add_before(c);
}

void ResumeScan::add_before(const QueuedCommand& c) {
  if (c.letter == proto::kCmdResolution) {
    resolution_ = c;
    have_resolution_ = true;
    tolerance_um_ = decoded<proto::ResolutionCmd>(c).chord_tolerance_um;
  }
  if (c.letter == proto::kCmdDwell && spindle_dwells_) {
    spindle_.push_back(c);
  } else {
    spindle_dwells_ = false;
  }
  if (c.letter == proto::kCmdSpindle) {
    spindle_.clear();
    if (decoded<proto::SpindleCmd>(c).on) {
      spindle_.push_back(c);
      spindle_dwells_ = true;
    }
  }
  if (c.letter == proto::kCmdZMove || c.letter == proto::kCmdDrill) {
    height_ = c;
    have_height_ = true;
  }
  if (is_move(c.letter)) {
    last_move_.assign(1, c);
    last_move_tolerance_um_ = tolerance_um_;
    if (c.letter == proto::kCmdSplineHeader) spline_into_ = &last_move_;
  }
}

}  // namespace host
