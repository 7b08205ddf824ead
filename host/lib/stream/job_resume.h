// Resuming a job after a lost link, an abort or an alarm: where the controller says the job
// stopped (status: the first unfinished job command, the curve point reached), and the
// command stream that continues it from there (pen up, travel, pen down, #J, the rest).
#ifndef HOST_LIB_STREAM_JOB_RESUME_H
#define HOST_LIB_STREAM_JOB_RESUME_H

#include <cstddef>   // size_t
#include <cstdint>   // int32_t, uint16_t
#include <optional>  // std::optional
#include <string>    // std::string
#include <vector>    // std::vector

#include "firmware/protocol/messages.h"  // proto::StatusReply
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/resume_scan.h"  // JobPass

namespace host {

// Where a job stopped, from the controller's status.
struct ResumePoint {
  int32_t job_index = 0;     // first job command not finished (the controller's numbering)
  uint16_t curve_point = 0;  // in that command, if a spline: the curve point the tool heads for
  bool started = false;      // that command began to move (it was cut short)
  uint16_t job_id = 0;       // the controller's job (the #J's job_id; job_id_of())
  int32_t x_um = 0, y_um = 0, z_um = 0;  // where the tool stands
};

// The resume point a status reports; empty when the controller has no job progress (no #J
// since it powered up: a restarted controller).
std::optional<ResumePoint> resume_point_of(const proto::StatusReply& status);

// Empty when `job` is the job the controller ran (same job_id); otherwise why not: a resume
// with another file or other plan options would cut something else.
std::string resume_mismatch(const std::vector<QueuedCommand>& job, const ResumePoint& at);
std::string resume_mismatch(uint16_t job_id, const ResumePoint& at);

// Job commands are the queued commands the controller numbers after a #J: every command of
// the stream except #D (part of its #B) and #J. Index into `job` of job command job_index;
// job.size() when the job has no such command (it finished).
size_t command_of_job_index(const std::vector<QueuedCommand>& job, int32_t job_index);

// The stream that continues `job` (encode_job's output, which starts with #J 0) from `at`:
//   #U as the job set it; #Z to the job's travel height (its highest #Z);
//   #F to where the tool stands; the spindle on again (#N 1 and the dwells after it) if the
//   job had it on there; #Z down to the job's depth there at its plunge feed (if the pen was
//   down); #J job_index first_point; then the job's commands from job_index on.
// A spline cut short restarts at the curve point the tool was heading for (the controller
// walks the curve from its start and moves only from that point: the same points as an
// uninterrupted run); the tool goes there straight from where it stopped, which lies on the
// chord to that point. Any other command cut short is sent again whole: a move runs from the
// stop position to its end (the rest of the same line); a drill cycle drills its hole again.
// Empty when nothing is left to do.
std::vector<QueuedCommand> resume_commands(const std::vector<QueuedCommand>& job,
                                           const ResumePoint& at, const EncodeOptions& options);
// The same without the job's list: the commands before job[*from] (*from: the stream index
// of job command at.job_index, or the job's size with an empty prefix when it finished); the
// caller streams the job from *from on (EncodedJob::start_at).
std::vector<QueuedCommand> resume_prefix(const JobPass& job, const ResumePoint& at,
                                         const EncodeOptions& options, size_t* from);

// The controller counts curve points in 16 bits and stops at 65 535 (the tool is at or past
// that point). Empty when curve point `curve_point` of job command job_index can be resumed
// on a curve of point_count points; otherwise why not (past the end, or a saturated count on
// a longer curve, with what to do instead).
std::string curve_point_problem(int32_t job_index, size_t point_count, uint16_t curve_point);

// A resume point the user gives (after a controller restart, from the last progress line):
// job command job_index, from curve point curve_point if it is a spline. The tool is taken to
// where the job stood there: for a spline from a curve point > 0, that curve point - 1 (the
// last one reached; computed with the controller's own curve walker), else the end of the
// job's previous move. tool_z_um: where the tool stands now (the prefix lifts it first).
// Throws PlanError when job_index is not a job command or the point is past the curve's end.
ResumePoint resume_point_at(const std::vector<QueuedCommand>& job, int32_t job_index,
                            uint16_t curve_point, int32_t tool_z_um);
ResumePoint resume_point_at(const JobPass& job, int32_t job_index, uint16_t curve_point,
                            int32_t tool_z_um);
// The same from a pass already made over the job (its job commands counted, for messages).
ResumePoint resume_point_at(const ResumeScan& scan, uint16_t curve_point, int32_t tool_z_um);

// Continues `job` from the first command of plan curve first_curve (the pen-up and travel
// that lead to it), the tool taken to where the previous move ended: what the workshop
// server's "continue" does with an interrupted job's first uncut curve. A curve that was
// partly cut is cut again from its start (the server knows curves, not curve points).
// Throws PlanError when no command belongs to that curve.
std::vector<QueuedCommand> resume_from_curve(const std::vector<QueuedCommand>& job, int first_curve,
                                             const EncodeOptions& options);
// The job index of the first job command of plan curve `curve`; PlanError when there is none.
int32_t job_index_of_curve(const JobPass& job, int curve);

// "job command 12 of 40 (plan step 7, curve 3), curve point 18" for messages.
std::string describe_resume_point(const std::vector<QueuedCommand>& job, const ResumePoint& at);
std::string describe_resume_point(const JobPass& job, const ResumePoint& at);

}  // namespace host

#endif  // HOST_LIB_STREAM_JOB_RESUME_H
