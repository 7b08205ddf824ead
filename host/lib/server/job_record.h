// A job as the server keeps it: where it is in its life, what it needs from a machine,
// where its files are and how far it got.
#ifndef HOST_LIB_SERVER_JOB_RECORD_H
#define HOST_LIB_SERVER_JOB_RECORD_H

#include <cstdint>  // int64_t
#include <string>   // std::string
#include <vector>   // std::vector

#include "host/lib/plan/job_defaults.h"

namespace host::server {

enum class JobState {
  kQueued,       // waiting for a free machine that fits
  kRunning,      // claimed by a machine (a server) and being sent
  kCompleted,    // every command executed
  kAborted,      // the operator aborted it on the machine
  kFailed,       // alarm, command refused by the controller, or it could not be planned
  kInterrupted,  // link lost or server stopped mid-job: resumable or re-queueable
  kCancelled     // removed from the queue before it ran
};
const char* state_name(JobState state);
// Throws std::invalid_argument for an unknown name.
JobState state_from_name(const std::string& name);
// Completed, aborted, failed or cancelled: the job will not run again unless re-queued.
bool is_final(JobState state);

// How a job is planned (kept with the job so a restart or another server plans it the same).
struct JobPlanSettings {
  double feed_mm_s = defaults::feed_mm_per_s();
  double tol_mm = defaults::kChordToleranceMm;
  double scale = defaults::kScale;
  double margin_mm = defaults::kMarginMm;
};

struct JobRecord {
  int64_t id = 0;
  std::string key;         // archive folder name: random hex made by the server, never user input
  std::string name;        // the upload's file name, for people only (never a path)
  std::string input_file;  // file name inside the archive folder ("input.dxf")
  JobState state = JobState::kQueued;
  int priority = 0;  // higher runs first; equal: oldest first
  std::string tag;   // tool or material the machine must be marked with; "" = any machine
  JobPlanSettings settings;
  double width_mm = 0;     // the machine's work area must reach x = width_mm ...
  double height_mm = 0;    // ... and y = height_mm (the plan's extents, margin included)
  double planned_s = 0;    // estimated run time from the planned motion
  std::string machine;     // where it runs or ran
  std::string owner;       // the server that claimed it
  std::string message;     // why it ended (or why it was interrupted)
  int64_t executed = 0;    // commands executed when it ended
  int64_t total = 0;       // commands in the job
  int resume_curve = -1;   // interrupted: first curve not fully cut (-1: none known)
  int start_curve = -1;    // queued to continue from this curve (-1: from the start)
  int64_t created_ms = 0;  // Unix time, ms
  int64_t started_ms = 0;
  int64_t finished_ms = 0;
  // Where the controller last said the job stood (saved as it runs, and when it ends), in the
  // numbering of the whole job (docs/protocol.md, #J): the first job command not finished,
  // its curve point, and the controller's job_id of that progress. -1: none known.
  int64_t resume_index = -1;
  int resume_point = 0;
  int resume_job_id = -1;
  int64_t lease_epoch = 0;  // the owner's lease the job was claimed under (JobStore)
};

// What a machine offers; a job fits when its extents and tag do.
struct MachineFit {
  double work_width_mm = defaults::work_width_mm();
  double work_height_mm = defaults::work_height_mm();
  std::vector<std::string> tags;
  // Queued jobs this machine leaves for now (map_source.h: waiting for another job's map).
  std::vector<int64_t> not_now_ids;
};
bool job_fits(const JobRecord& job, const MachineFit& fit);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_RECORD_H
