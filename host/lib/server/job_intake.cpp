// Upload checks, planning at upload and the archive folder of a new job.
#include "host/lib/server/job_intake.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::max
#include <cctype>     // std::isalnum
#include <fstream>    // std::ofstream
#include <optional>   // std::optional

#include "host/lib/drawing/drawing.h"
#include "host/lib/pcb/board_files.h"
#include "host/lib/pcb/board_job.h"  // pcb::BoardOptions
#include "host/lib/plan/job_plan.h"
#include "host/lib/plot/board_plot.h"
#include "host/lib/plot/plan_plot.h"
#include "host/lib/plot/plot.h"
#include "host/lib/server/board_bundle.h"
#include "host/lib/server/board_height_map.h"  // check_height_map_fields
#include "host/lib/server/job_planning.h"
#include "host/lib/server/zip_upload.h"

namespace host::server {

namespace fs = std::filesystem;

namespace {

// A field refused once the board is planned (it needs the plan): 400, naming the field.
class FieldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace

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

void JobIntake::work_area(double* w_mm, double* h_mm) const {
  // Plan for the largest work area of any machine; fit is checked per machine after.
  *w_mm = 0;
  *h_mm = 0;
  for (const MachineFit& m : machines_) {
    *w_mm = std::max(*w_mm, m.work_width_mm);
    *h_mm = std::max(*h_mm, m.work_height_mm);
  }
  if (machines_.empty()) {
    *w_mm = defaults::work_width_mm();  // no machine yet: the reference machine's table
    *h_mm = defaults::work_height_mm();
  }
}

void JobIntake::stage_drawing(const Submission& sub, const fs::path& staging, JobRecord* job,
                              std::string* stored) const {
  double work_w = 0, work_h = 0;
  work_area(&work_w, &work_h);
  job->input_file = archive_input_name(sub.name);
  write_file(staging / job->input_file, sub.content);
  const JobPlan plan =
      plan_file((staging / job->input_file).string(), sub.name, sub.settings, work_w, work_h);
  job->width_mm = std::max(0.0, plan.extents_mm.max.x());
  job->height_mm = std::max(0.0, plan.extents_mm.max.y());
  job->planned_s = planned_seconds(plan, sub.settings);
  write_plan_json(staging / "plan.json", plan);
  write_plot(plot_input_from_plan(plan, sub.name), (staging / "plot.svg").string(),
             (staging / "plot.png").string());
  *stored = sub.content;
}

void JobIntake::stage_board(const Submission& sub, const std::vector<UploadFile>& files,
                            bool skip_other, const std::string* zip, const fs::path& staging,
                            JobRecord* job, std::string* stored) const {
  double work_w = 0, work_h = 0;
  work_area(&work_w, &work_h);
  const PlannedBoard b =
      plan_board_upload(files, skip_other, job->name, sub.board, job->settings, work_w, work_h);
  const std::string why = check_height_map_fields(store_, data_, sub.board, b);
  if (!why.empty()) throw FieldError(why);
  job->input_file = kBoardManifest;
  for (const auto& [file, bytes] : b.files) write_file(staging / file, bytes);
  if (zip != nullptr) write_file(staging / "input.zip", *zip);  // as it came, all files in it
  const JobPlan& plan = b.job.plan;
  // Holes and their travel reach as far as the cut paths: the extents of every step.
  double w = std::max(0.0, plan.extents_mm.max.x()), h = std::max(0.0, plan.extents_mm.max.y());
  for (const PlanStep& s : plan.steps) {
    if (s.kind == PlanStep::kRapid || s.kind == PlanStep::kDrill || s.kind == PlanStep::kFeed) {
      w = std::max(w, s.to.x_um / 1000.0);
      h = std::max(h, s.to.y_um / 1000.0);
    }
  }
  job->width_mm = w;
  job->height_mm = h;
  job->planned_s = planned_seconds_by_steps(plan);
  write_plan_json(staging / "plan.json", plan);
  BoardPlotInput in;
  in.title = fmt::format("{} ({} side)", job->name, b.manifest["side"].get<std::string>());
  in.job = &b.job;
  write_board_plot(in, (staging / "plot.svg").string(), (staging / "plot.png").string());
  *stored = pack_board_bundle(b.files);
}

IntakeResult JobIntake::submit(const Submission& sub) {
  IntakeResult r;
  // One file in name/content, or a board's files, or a board as one zip file.
  std::vector<UploadFile> files = sub.files;
  bool several = !files.empty();
  if (!several) files.push_back(UploadFile{sub.name, sub.content});
  bool board = several;
  for (const UploadFile& f : files) board = board || is_pcb_upload(f);
  bool skip_other = sub.skip_other_files;
  const std::string* zip = nullptr;
  std::string why;
  for (const UploadFile& f : files) {
    if (several && looks_like_zip(f.content)) {
      why =
          fmt::format("file '{}': a zip file is uploaded alone (it holds the whole board)", f.name);
    }
  }
  if (!several && looks_like_zip(sub.content)) {
    why = check_upload_name(sub.name);
    if (why.empty() && sub.content.size() > max_bytes_) {
      r.status = 413;
      r.error = fmt::format("{}: {} bytes, more than the limit of {} bytes", sub.name,
                            sub.content.size(), max_bytes_);
      return r;
    }
    if (why.empty()) {
      try {
        files = unzip_upload(sub.content, sub.name, max_bytes_, 4 * kMaxFiles);
      } catch (const ZipError& e) {
        r.status = e.too_large() ? 413 : 422;
        r.error = e.what();
        return r;
      }
      zip = &sub.content;
      several = board = skip_other = true;
    }
  }
  if (why.empty() && files.size() > kMaxFiles) {
    why = fmt::format("{} files in one upload; a board takes at most {}", files.size(), kMaxFiles);
  }
  for (const UploadFile& f : files) {
    if (!why.empty()) break;
    why = check_upload_name(f.name);
    if (!why.empty() && several) why = fmt::format("file '{}': {}", f.name, why);
  }
  std::vector<std::string> names;
  for (const UploadFile& f : files) names.push_back(f.name);
  std::string job_name =
      !several || !sub.name.empty() ? sub.name : pcb::board_name_from_files(names);
  if (zip != nullptr) job_name = fs::path(sub.name).stem().string();  // "blinky" of blinky.zip
  if (why.empty() && several) why = check_upload_name(job_name);
  if (why.empty()) why = check_tag(sub.tag);
  if (why.empty()) why = check_settings(sub.settings);
  if (why.empty() && board) why = check_board_settings(sub.board);
  if (why.empty() && board && sub.feed_given) {
    why = fmt::format(
        "feed_mm_s does not apply to a board: it is cut at the board planner's feeds "
        "(isolation {} mm/s, drilling {} mm/s, cut-out {} mm/s)",
        defaults::kBoardFeedMmPerS, defaults::kDrillFeedMmPerS, defaults::kCutFeedMmPerS);
  }
  if (why.empty() && board && sub.tol_given &&
      sub.settings.tol_mm != defaults::kBoardChordToleranceMm) {
    why = fmt::format(
        "tol_mm of a board must be {} (a board is sent with 1 um chords, the controller's "
        "finest: coarser ones cut into the isolation clearance)",
        defaults::kBoardChordToleranceMm);
  }
  if (why.empty() && !board && !sub.board_fields.empty()) {
    why = fmt::format("{} applies to a board (Gerber and Excellon files), not to {}",
                      sub.board_fields.front(), sub.name);
  }
  if (why.empty() && board && sub.board.height_map_from == 0 &&
      std::find(sub.board_fields.begin(), sub.board_fields.end(), "height_map_flip") !=
          sub.board_fields.end()) {
    why = "height_map_flip goes with height_map_from (how that job's map follows the flip)";
  }
  if (why.empty() && board && sub.board.height_map_from != 0) {
    const std::optional<JobRecord> from = store_.get(sub.board.height_map_from);
    if (!from || !is_board_job(*from)) {
      why = fmt::format("height_map_from: no board job {} (the job whose height map to use)",
                        sub.board.height_map_from);
    }
  }
  if (why.empty() && board && sub.settings.scale != 1.0) {
    why = "scale does not apply to a board (Gerber and Excellon give true sizes)";
  }
  if (why.empty() && (sub.priority < -1000 || sub.priority > 1000)) {
    why = "priority must be -1000 .. 1000";
  }
  if (!why.empty()) {
    r.status = 400;
    r.error = why;
    return r;
  }
  size_t total = 0;
  for (const UploadFile& f : files) total += f.content.size();
  if (total > max_bytes_) {
    r.status = 413;
    r.error =
        fmt::format("{}: {} bytes, more than the limit of {} bytes", job_name, total, max_bytes_);
    return r;
  }

  const fs::path staging = data_.new_staging_dir();
  try {
    JobRecord job;
    job.key = staging.filename().string();
    job.name = job_name;
    job.priority = sub.priority;
    job.tag = sub.tag;
    job.settings = sub.settings;
    if (board) {  // what it is cut and sent with, on the record
      job.settings.feed_mm_s = defaults::kBoardFeedMmPerS;
      job.settings.tol_mm = defaults::kBoardChordToleranceMm;
    }
    std::string stored;
    if (board) {
      // A board sits where `engraver board` puts it unless the sender said otherwise.
      if (!sub.margin_given) job.settings.margin_mm = defaults::kBoardMarginMm;
      stage_board(sub, files, skip_other, zip, staging, &job, &stored);
    } else {
      stage_drawing(sub, staging, &job, &stored);
    }
    bool fits = machines_.empty();
    for (const MachineFit& m : machines_) fits = fits || job_fits(job, m);
    if (!fits) {
      throw PlanError(fmt::format("{}: no machine can take it (needs {:.1f} x {:.1f} mm{}{})",
                                  job_name, job.width_mm, job.height_mm,
                                  job.tag.empty() ? "" : " and tag ", job.tag));
    }
    const fs::path dir = data_.job_dir(job.key);
    fs::rename(staging, dir);
    try {
      r.id = store_.add(job, stored);
    } catch (...) {
      std::error_code ec;
      fs::remove_all(dir, ec);
      throw;
    }
    r.status = 201;
  } catch (const FieldError& e) {
    r.status = 400;
    r.error = e.what();
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
    r.error = fmt::format("{}: {}", job_name, e.what());
  } catch (...) {
    r.status = 422;  // a reader threw something that is not an exception class
    r.error = fmt::format("{}: cannot be read as a drawing", job_name);
  }
  std::error_code ec;
  fs::remove_all(staging, ec);  // gone already when the job was queued
  return r;
}

}  // namespace host::server
