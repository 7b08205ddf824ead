// Plans a job file the same way at upload (to refuse what cannot run) and on the machine
// (to send it): the drawing importer and the planner with the job's settings.
#ifndef HOST_LIB_SERVER_JOB_PLANNING_H
#define HOST_LIB_SERVER_JOB_PLANNING_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <string>  // std::string

#include "host/lib/plan/job_plan.h"
#include "host/lib/server/job_record.h"
#include "host/lib/stream/job_encoder.h"

namespace host::server {

// Imports `path` and plans it for a work_w x work_h mm area. ImportError and PlanError name
// `display_name` instead of `path` (the archive path means nothing to the person).
JobPlan plan_file(const std::string& path, const std::string& display_name,
                  const JobPlanSettings& settings, double work_w_mm, double work_h_mm);
// The encoder's options for the job (title, chord tolerance).
EncodeOptions encode_options(const JobPlanSettings& settings, const std::string& title);
// Estimated run time: cut length at the feed, travel at the rapid rate, pen lifts.
double planned_seconds(const JobPlan& plan, const JobPlanSettings& settings);
// The plan for the archive: summary and every step.
nlohmann::json plan_json(const JobPlan& plan);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_PLANNING_H
