// Job planning for the server: import, plan, estimate, describe.
#include "host/lib/server/job_planning.h"

#include <malloc.h>  // malloc_trim

#include <algorithm>  // std::min
#include <cmath>      // std::lround
#include <fstream>    // std::ofstream
#include <stdexcept>  // std::runtime_error
#include <utility>    // std::move

#include "firmware/config/machine_config.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/plot/board_plot.h"
#include "host/lib/plot/plan_plot.h"
#include "host/lib/plot/plot.h"
#include "host/lib/server/board_bundle.h"
#include "host/lib/server/board_planning.h"
#include "host/lib/server/data_folder.h"

namespace host::server {

namespace {

// The message with every occurrence of `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

const char* step_name(PlanStep::Kind kind) {
  // In the order of PlanStep::Kind.
  static const char* const kNames[] = {"pen_up", "pen_down", "rapid",   "feed", "spline",
                                       "pause",  "dwell",    "spindle", "drill"};
  static_assert(sizeof(kNames) / sizeof(kNames[0]) == PlanStep::kDrill + 1, "a name per kind");
  return kind <= PlanStep::kDrill ? kNames[kind] : "?";
}

}  // namespace

JobPlan plan_file(const std::string& path, const std::string& display_name,
                  const JobPlanSettings& settings, double work_w_mm, double work_h_mm,
                  const StopAsked& stop) {
  const WorkProgress check = [&stop](const char*, size_t, size_t) {
    if (stop()) throw WorkStopped();
  };
  try {
    Drawing drawing = stop ? import_drawing(path, check) : import_drawing(path);
    PlanOptions o;
    if (stop) o.progress = check;
    o.scale = settings.scale;
    o.margin_mm = settings.margin_mm;
    o.work_width_mm = work_w_mm;
    o.work_height_mm = work_h_mm;
    o.feed_mm_per_s = settings.feed_mm_s;
    return plan_job(std::move(drawing), o);  // the drawing's curves move into the plan
  } catch (const ImportError& e) {
    throw ImportError(replaced(e.what(), path, display_name));
  } catch (const PlanError& e) {
    throw PlanError(display_name + ": " + replaced(e.what(), path, display_name));
  }
}

EncodeOptions encode_options(const JobRecord& job) {
  EncodeOptions e;
  double tol_mm = job.settings.tol_mm;
  if (is_board_job(job)) tol_mm = std::min(tol_mm, pcb::kBoardChordToleranceMm);
  e.chord_tolerance_um = static_cast<uint16_t>(std::lround(tol_mm * 1000.0));
  e.title = std::filesystem::path(job.name).stem().string();
  return e;
}

double planned_seconds(const JobPlan& plan, const JobPlanSettings& settings) {
  const config::MachineConfig m = config::default_machine_config();
  const double rapid_mm_s = m.rapid_feed_um_per_s / 1000.0;
  const double z_mm_s = m.axis[config::kAxisZ].max_speed_um_per_s / 1000.0;
  const double z_travel_mm = defaults::kZUpMm - defaults::kZDownMm;  // pen up to pen down
  return plan.cut_length_mm / settings.feed_mm_s + plan.rapid_length_mm / rapid_mm_s +
         (plan.pen_lifts + 1) * 2.0 * z_travel_mm / z_mm_s;
}

namespace {

// plan.json without its steps.
nlohmann::json plan_summary_json(const JobPlan& plan) {
  nlohmann::json j;
  j["curves"] = plan.curves.size();
  j["pen_lifts"] = plan.pen_lifts;
  j["cut_length_mm"] = plan.cut_length_mm;
  j["rapid_length_mm"] = plan.rapid_length_mm;
  j["offset_mm"] = {plan.offset_mm.x(), plan.offset_mm.y()};
  j["extents_mm"] = {{"min", {plan.extents_mm.min.x(), plan.extents_mm.min.y()}},
                     {"max", {plan.extents_mm.max.x(), plan.extents_mm.max.y()}}};
  return j;
}

nlohmann::json step_json(const PlanStep& s) {
  nlohmann::json step = {{"kind", step_name(s.kind)}, {"curve", s.curve}};
  if (s.kind == PlanStep::kPenUp || s.kind == PlanStep::kPenDown) step["z_um"] = s.z_um;
  if (s.kind == PlanStep::kRapid || s.kind == PlanStep::kFeed || s.kind == PlanStep::kSpline ||
      s.kind == PlanStep::kDrill) {
    step["to_um"] = {s.to.x_um, s.to.y_um};
  }
  if (s.feed_um_per_s != 0) step["feed_um_per_s"] = s.feed_um_per_s;
  return step;
}

}  // namespace

nlohmann::json plan_json(const JobPlan& plan) {
  nlohmann::json j = plan_summary_json(plan);
  nlohmann::json steps = nlohmann::json::array();
  for (const PlanStep& s : plan.steps) steps.push_back(step_json(s));
  j["steps"] = steps;
  return j;
}

void write_plan_json(const std::filesystem::path& path, const JobPlan& plan) {
  // "steps" sorts last among the keys: the summary's text, then the steps one by one (a
  // million steps as one JSON tree took 1.4 GB).
  std::string head = plan_summary_json(plan).dump(1);
  head.resize(head.size() - 2);  // without the closing "\n}"
  std::ofstream out(path, std::ios::binary);
  out << head << ",\n \"steps\": [";
  for (size_t i = 0; i < plan.steps.size(); ++i)
    out << (i == 0 ? "\n  " : ",\n  ") << step_json(plan.steps[i]).dump();
  out << (plan.steps.empty() ? "]\n}\n" : "\n ]\n}\n");
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

void release_freed_memory() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

void restore_job_input(const std::filesystem::path& dir, const JobRecord& job,
                       const std::string& stored) {
  std::filesystem::create_directories(dir);
  if (!is_board_job(job)) {
    write_file(dir / job.input_file, stored);
    return;
  }
  for (const auto& [file, bytes] : unpack_board_bundle(stored)) write_file(dir / file, bytes);
}

JobPlan plan_archived_job(const std::filesystem::path& dir, const JobRecord& job, double work_w_mm,
                          double work_h_mm, bool write_archive, const StopAsked& stop) {
  if (is_board_job(job)) {
    const pcb::BoardJob board = plan_board_folder(dir, job.settings, work_w_mm, work_h_mm);
    if (write_archive) {
      write_plan_json(dir / "plan.json", board.plan);
      BoardPlotInput in;
      in.title = job.name;
      in.job = &board;
      write_board_plot(in, (dir / "plot.svg").string(), (dir / "plot.png").string());
    }
    return board.plan;
  }
  // Not const: returned by move (a copy held a 1 M-line job's plan twice).
  JobPlan plan = plan_file((dir / job.input_file).string(), job.name, job.settings, work_w_mm,
                           work_h_mm, stop);
  if (write_archive) {
    write_plan_json(dir / "plan.json", plan);
    write_plot(plot_input_from_plan(plan, job.name), (dir / "plot.svg").string(),
               (dir / "plot.png").string());
  }
  return plan;
}

}  // namespace host::server
