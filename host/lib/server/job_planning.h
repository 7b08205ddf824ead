// Plans a job file the same way at upload (to refuse what cannot run) and on the machine
// (to send it): the drawing importer and the planner with the job's settings.
#ifndef HOST_LIB_SERVER_JOB_PLANNING_H
#define HOST_LIB_SERVER_JOB_PLANNING_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <filesystem>  // std::filesystem::path
#include <functional>  // std::function
#include <string>      // std::string

#include "host/lib/plan/job_plan.h"
#include "host/lib/server/job_record.h"
#include "host/lib/stream/job_encoder.h"

namespace host::server {

// Asked as planning reports its stages (every few thousand curves, every read block): true
// ends it with WorkStopped (drawing.h), so a server that stops, or a job aborted while it is
// planned, does not wait a large job's minute of planning out.
using StopAsked = std::function<bool()>;

// Imports `path` and plans it for a work_w x work_h mm area. ImportError and PlanError name
// `display_name` instead of `path` (the archive path means nothing to the person).
JobPlan plan_file(const std::string& path, const std::string& display_name,
                  const JobPlanSettings& settings, double work_w_mm, double work_h_mm,
                  const StopAsked& stop = nullptr);
// The encoder's options for the job: its name (without extension) as the title, and its
// chord tolerance, for a board at most pcb::kBoardChordToleranceMm (the controller's chords
// come out of the isolation clearance).
EncodeOptions encode_options(const JobRecord& job);
// Estimated run time: cut length at the feed, travel at the rapid rate, pen lifts.
double planned_seconds(const JobPlan& plan, const JobPlanSettings& settings);
// The plan for the archive: summary and every step.
nlohmann::json plan_json(const JobPlan& plan);
// The same written to `path` step by step (the archive's plan.json of a large job).
void write_plan_json(const std::filesystem::path& path, const JobPlan& plan);

// Gives the pages of freed memory back to the system: glibc keeps them in each thread's
// arena, so a planned job's drawing (hundreds of MB for a million lines) stayed resident
// while the job was cut. Call after a large plan's temporaries are gone.
void release_freed_memory();

// Writes a job's input into its archive folder from the bytes the store keeps (a server
// sharing the queue runs a job uploaded to another): the file, or a board's files.
void restore_job_input(const std::filesystem::path& dir, const JobRecord& job,
                       const std::string& stored);
// Plans a job (drawing or board) from its archive folder for a machine's work area; with
// write_archive also writes plan.json and the plot there. `stop`: as plan_file's (a drawing).
JobPlan plan_archived_job(const std::filesystem::path& dir, const JobRecord& job, double work_w_mm,
                          double work_h_mm, bool write_archive, const StopAsked& stop = nullptr);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_PLANNING_H
