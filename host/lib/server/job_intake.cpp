// Upload checks, planning at upload and the archive folder of a new job.
#include "host/lib/server/job_intake.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::max
#include <cctype>     // std::isalnum
#include <fstream>    // std::ofstream

#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/job_plan.h"
#include "host/lib/plot/plan_plot.h"
#include "host/lib/plot/plot.h"
#include "host/lib/server/job_planning.h"

namespace host::server {

namespace fs = std::filesystem;

std::string check_upload_name(const std::string& name) {
  if (name.empty()) return "the file has no name";
  if (name.size() > 200) return "the file name is longer than 200 characters";
  for (unsigned char c : name) {
    if (c < 0x20 || c == 0x7F) return "the file name contains a control character";
    if (c == '/' || c == '\\') return "the file name contains a folder separator";
    if (c == ':') return "the file name contains ':'";
  }
  if (name[0] == '.') return "the file name starts with '.'";
  if (name.find("..") != std::string::npos) return "the file name contains '..'";
  return "";
}

std::string check_tag(const std::string& tag) {
  if (tag.size() > 32) return "tag longer than 32 characters";
  for (unsigned char c : tag) {
    if (!std::isalnum(c) && c != '_' && c != '-') return "tag may hold only A-Z a-z 0-9 _ -";
  }
  return "";
}

std::string check_settings(const JobPlanSettings& s) {
  // Written so that NaN fails every range.
  if (!(s.feed_mm_s >= 0.1 && s.feed_mm_s <= 60.0)) return "feed_mm_s must be 0.1 .. 60";
  if (!(s.tol_mm >= 0.001 && s.tol_mm <= 1.0)) return "tol_mm must be 0.001 .. 1";
  if (!(s.scale >= 1e-3 && s.scale <= 1e3)) return "scale must be 0.001 .. 1000";
  if (!(s.margin_mm >= 0.0 && s.margin_mm <= 100.0)) return "margin_mm must be 0 .. 100";
  return "";
}

std::string archive_input_name(const std::string& upload_name) {
  const size_t dot = upload_name.find_last_of('.');
  if (dot == std::string::npos) return "input";
  std::string ext = upload_name.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::string candidate = "input" + ext;
  return is_archive_file(candidate) ? candidate : "input";
}

JobIntake::JobIntake(JobStore& store, const DataFolder& data, std::vector<MachineFit> machines,
                     size_t max_bytes)
    : store_(store), data_(data), machines_(std::move(machines)), max_bytes_(max_bytes) {}

IntakeResult JobIntake::submit(const Submission& sub) {
  IntakeResult r;
  std::string why = check_upload_name(sub.name);
  if (why.empty()) why = check_tag(sub.tag);
  if (why.empty()) why = check_settings(sub.settings);
  if (why.empty() && (sub.priority < -1000 || sub.priority > 1000)) {
    why = "priority must be -1000 .. 1000";
  }
  if (!why.empty()) {
    r.status = 400;
    r.error = why;
    return r;
  }
  if (sub.content.size() > max_bytes_) {
    r.status = 413;
    r.error = fmt::format("{}: {} bytes, more than the limit of {} bytes", sub.name,
                          sub.content.size(), max_bytes_);
    return r;
  }
  // Plan for the largest work area of any machine; fit is checked per machine below.
  double work_w = 0, work_h = 0;
  for (const MachineFit& m : machines_) {
    work_w = std::max(work_w, m.work_width_mm);
    work_h = std::max(work_h, m.work_height_mm);
  }
  if (machines_.empty()) {
    work_w = 297.0;  // no machine yet: the reference machine's A4 table
    work_h = 210.0;
  }

  const fs::path staging = data_.new_staging_dir();
  try {
    JobRecord job;
    job.key = staging.filename().string();
    job.name = sub.name;
    job.input_file = archive_input_name(sub.name);
    job.priority = sub.priority;
    job.tag = sub.tag;
    job.settings = sub.settings;
    write_file(staging / job.input_file, sub.content);
    const JobPlan plan =
        plan_file((staging / job.input_file).string(), sub.name, sub.settings, work_w, work_h);
    job.width_mm = std::max(0.0, plan.extents_mm.max.x());
    job.height_mm = std::max(0.0, plan.extents_mm.max.y());
    job.planned_s = planned_seconds(plan, sub.settings);
    bool fits = machines_.empty();
    for (const MachineFit& m : machines_) fits = fits || job_fits(job, m);
    if (!fits) {
      throw PlanError(fmt::format("{}: no machine can take it (needs {:.1f} x {:.1f} mm{}{})",
                                  sub.name, job.width_mm, job.height_mm,
                                  job.tag.empty() ? "" : " and tag ", job.tag));
    }
    write_file(staging / "plan.json", plan_json(plan).dump(1) + "\n");
    write_plot(plot_input_from_plan(plan, sub.name), (staging / "plot.svg").string(),
               (staging / "plot.png").string());
    const fs::path dir = data_.job_dir(job.key);
    fs::rename(staging, dir);
    try {
      r.id = store_.add(job, sub.content);
    } catch (...) {
      std::error_code ec;
      fs::remove_all(dir, ec);
      throw;
    }
    r.status = 201;
  } catch (const ImportError& e) {
    r.status = 422;
    r.error = e.what();
  } catch (const PlanError& e) {
    r.status = 422;
    r.error = e.what();
  } catch (const StoreError& e) {
    r.status = 500;
    r.error = e.what();
  } catch (const std::exception& e) {
    r.status = 500;
    r.error = fmt::format("{}: {}", sub.name, e.what());
  } catch (...) {
    r.status = 422;  // a reader threw something that is not an exception class
    r.error = fmt::format("{}: cannot be read as a drawing", sub.name);
  }
  std::error_code ec;
  fs::remove_all(staging, ec);  // gone already when the job was queued
  return r;
}

}  // namespace host::server
