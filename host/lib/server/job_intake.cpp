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
#include "host/lib/server/job_record_fields.h"
#include "host/lib/server/map_source.h"  // map_source_refusal
#include "host/lib/server/time_left.h"   // planned_seconds_by_steps
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

std::string check_upload_name(const std::string& name, const std::string& what) {
  if (name.empty()) return what == kFileName ? "the file has no name" : what + " is empty";
  if (name.size() > 200) return what + " is longer than 200 characters";
  for (unsigned char c : name) {
    if (c < 0x20 || c == 0x7F) return what + " contains a control character";
    if (c == '/' || c == '\\') return what + " contains a folder separator";
    if (c == ':') return what + " contains ':'";
  }
  if (name[0] == '.') return what + " starts with '.'";
  if (name.find("..") != std::string::npos) return what + " contains '..'";
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
  // The ranges are the field table's (job_record_fields.h); NaN fails every one.
  JobRecord job;
  job.settings = s;
  for (size_t i = 0; i < kJobFieldCount; ++i) {
    const JobField& f = kJobFields[i];
    if (f.type != FieldType::kDouble) continue;
    const std::string why = field_range_error(f, std::get<double>(field_value(job, f)));
    if (!why.empty()) return why;
  }
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

// The upload's files: one file, a board's files, or a board's zip file unpacked.
struct JobIntake::UploadedFiles {
  // A drawing on disk (Submission::content_file) is files[0] with its first bytes only (what
  // tells a board from a drawing); its bytes are in `file`, content null. Otherwise content is
  // the one file's bytes (null for several files).
  std::vector<UploadFile> files;
  const std::string* content = nullptr;
  fs::path file;
  size_t bytes = 0;         // of every file
  bool several = false;     // a board's files (given as several, or unpacked from a zip)
  bool board = false;       // Gerber/Excellon: planned as a board
  bool skip_other = false;  // leave out files that are neither (a folder's or a zip's read-me)
  const std::string* zip = nullptr;  // the upload as it came, when it was one zip file
  std::string job_name;
};

void JobIntake::stage_drawing(const Submission& sub, const UploadedFiles& up,
                              const fs::path& staging, JobRecord* job, std::string* stored) const {
  double work_w = 0, work_h = 0;
  work_area(&work_w, &work_h);
  job->input_file = archive_input_name(sub.name);
  const fs::path input = staging / job->input_file;
  if (up.content != nullptr) {
    write_file(input, *up.content);
  } else {
    fs::copy_file(up.file, input);  // on disk only
  }
  {
    const JobPlan plan = plan_file(input.string(), sub.name, sub.settings, work_w, work_h,
                                   [this] { return stopping_.load(); });
    job->width_mm = std::max(0.0, plan.extents_mm.max.x());
    job->height_mm = std::max(0.0, plan.extents_mm.max.y());
    job->planned_s = planned_seconds(plan, sub.settings);
    write_plan_json(staging / "plan.json", plan);
    write_plot(plot_input_from_plan(plan, sub.name), (staging / "plot.svg").string(),
               (staging / "plot.png").string());
  }
  // Read once the plan is gone, and only for a store that keeps it.
  if (store_.keeps_input()) *stored = up.content != nullptr ? *up.content : read_file(input);
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

namespace {

IntakeResult refused(int status, const std::string& why) {
  IntakeResult r;
  r.status = status;
  r.error = why;
  return r;
}

// A zip among several files, a zip that cannot be unpacked, too many files or a bad name:
// why ("" when fine); *status says how it is refused.
std::string check_files(const Submission& sub, size_t max_bytes, size_t max_files,
                        JobIntake::UploadedFiles* up, int* status) {
  *status = 400;
  for (const UploadFile& f : up->files) {
    if (up->several && looks_like_zip(f.content)) {
      return fmt::format("file '{}': a zip file is uploaded alone (it holds the whole board)",
                         f.name);
    }
  }
  if (!up->several && up->content != nullptr && looks_like_zip(*up->content)) {
    const std::string why = check_upload_name(sub.name);
    if (!why.empty()) return why;
    if (up->content->size() > max_bytes) {
      *status = 413;
      return fmt::format("{}: {} bytes, more than the limit of {} bytes", sub.name,
                         up->content->size(), max_bytes);
    }
    try {
      up->files = unzip_upload(*up->content, sub.name, max_bytes, 4 * max_files);
    } catch (const ZipError& e) {
      *status = e.too_large() ? 413 : 422;
      return e.what();
    }
    up->zip = up->content;
    up->content = nullptr;
    up->bytes = 0;
    for (const UploadFile& f : up->files) up->bytes += f.content.size();
    up->several = up->board = up->skip_other = true;
  }
  if (up->files.size() > max_files) {
    return fmt::format("{} files in one upload; a board takes at most {}", up->files.size(),
                       max_files);
  }
  for (const UploadFile& f : up->files) {
    const std::string why = check_upload_name(f.name);
    if (!why.empty()) return up->several ? fmt::format("file '{}': {}", f.name, why) : why;
  }
  return "";
}

// The upload's name as the job's: the file's, the board's given name, the files' common name,
// or a zip's name without .zip.
std::string job_name_of(const Submission& sub, const JobIntake::UploadedFiles& up) {
  if (up.zip != nullptr) return fs::path(sub.name).stem().string();  // "blinky" of blinky.zip
  if (!up.several || !sub.name.empty()) return sub.name;
  std::vector<std::string> names;
  for (const UploadFile& f : up.files) names.push_back(f.name);
  return pcb::board_name_from_files(names);
}

// What a board's name is, for its refusal: what the sender gave (the form's field 'name', an
// inbox folder's name), or what it was made from (an outside tester's field 'name' was
// refused as "the file name").
std::string board_name_what(const Submission& sub, const JobIntake::UploadedFiles& up) {
  if (up.zip != nullptr) return "the zip file's name";
  if (!sub.name.empty()) return sub.name_source;
  return "the files' common name";
}

// The fields against the kind of job (a board's fields and a drawing's): why not ("" fine).
std::string check_fields(const Submission& sub, bool board) {
  std::string why = check_tag(sub.tag);
  if (why.empty()) why = check_settings(sub.settings);
  if (why.empty() && board) why = check_board_settings(sub.board);
  if (!why.empty()) return why;
  if (board && sub.feed_given) {
    return fmt::format(
        "feed_mm_s does not apply to a board: it is cut at the board planner's feeds "
        "(isolation {} mm/s, drilling {} mm/s, cut-out {} mm/s)",
        defaults::kBoardFeedMmPerS, defaults::kDrillFeedMmPerS, defaults::kCutFeedMmPerS);
  }
  if (board && sub.tol_given && sub.settings.tol_mm != defaults::kBoardChordToleranceMm) {
    return fmt::format(
        "tol_mm of a board must be {} (a board is sent with 1 um chords, the controller's "
        "finest: coarser ones cut into the isolation clearance)",
        defaults::kBoardChordToleranceMm);
  }
  if (!board && !sub.board_fields.empty()) {
    return fmt::format("{} applies to a board (Gerber and Excellon files), not to {}",
                       sub.board_fields.front(), sub.name);
  }
  if (board && sub.board.height_map_from == 0 &&
      std::find(sub.board_fields.begin(), sub.board_fields.end(), "height_map_flip") !=
          sub.board_fields.end()) {
    return "height_map_flip goes with height_map_from (how that job's map follows the flip)";
  }
  // Read only when the job probes: a spacing without probe_first would be ignored.
  if (board && !sub.board.probe_first &&
      std::find(sub.board_fields.begin(), sub.board_fields.end(), "probe_spacing_mm") !=
          sub.board_fields.end()) {
    return "probe_spacing_mm goes with probe_first=1 (the pitch of the grid it probes)";
  }
  if (board && sub.settings.scale != 1.0) {
    return "scale does not apply to a board (Gerber and Excellon give true sizes)";
  }
  return field_range_error(*job_field_by_json_key("priority"), sub.priority);
}

}  // namespace

IntakeResult JobIntake::submit(const Submission& sub) {
  // One file in name/content (or content_file), or a board's files, or a board as one zip.
  UploadedFiles up;
  up.files = sub.files;
  up.several = !up.files.empty();
  std::string read;  // a board's or zip's bytes from content_file
  if (!up.several) {
    up.content = &sub.content;
    if (!sub.content_file.empty()) {
      std::error_code ec;
      const uintmax_t size = fs::file_size(sub.content_file, ec);
      if (ec) return refused(500, fmt::format("{}: {}", sub.name, ec.message()));
      if (size > max_bytes_) {
        return refused(413, fmt::format("{}: {} bytes, more than the limit of {} bytes", sub.name,
                                        size, max_bytes_));
      }
      try {
        std::string head = read_file_head(sub.content_file, 4096);
        if (looks_like_zip(head) || is_pcb_upload(UploadFile{sub.name, head})) {
          read = read_file(sub.content_file);
        } else {
          up.files.push_back(UploadFile{sub.name, std::move(head)});
          up.content = nullptr;
          up.file = sub.content_file;
          up.bytes = size;
        }
      } catch (const std::exception& e) {
        return refused(500, e.what());
      }
      if (up.content != nullptr) up.content = &read;
    }
    if (up.content != nullptr) {
      // A drawing's bytes are not copied: its first ones tell it from a board's file.
      UploadFile f{sub.name, up.content->substr(0, 4096)};
      if (is_pcb_upload(f)) f.content = *up.content;
      up.files.push_back(std::move(f));
      up.bytes = up.content->size();
    }
  } else {
    for (const UploadFile& f : up.files) up.bytes += f.content.size();
  }
  up.board = up.several;
  for (const UploadFile& f : up.files) up.board = up.board || is_pcb_upload(f);
  up.skip_other = sub.skip_other_files;
  int status = 400;
  std::string why = check_files(sub, max_bytes_, kMaxFiles, &up, &status);
  if (!why.empty()) return refused(status, why);
  up.job_name = job_name_of(sub, up);
  if (up.several) why = check_upload_name(up.job_name, board_name_what(sub, up));
  if (why.empty()) why = check_fields(sub, up.board);
  if (why.empty() && up.board && sub.board.height_map_from != 0)
    why = map_source_refusal(store_, data_, sub.board.height_map_from);
  if (!why.empty()) return refused(400, why);
  if (up.bytes > max_bytes_) {
    return refused(413, fmt::format("{}: {} bytes, more than the limit of {} bytes", up.job_name,
                                    up.bytes, max_bytes_));
  }
  return plan_and_queue(sub, up);
}

// The job's record as the upload gives it (what the plan adds comes later).
JobRecord JobIntake::new_record(const Submission& sub, const UploadedFiles& up,
                                const fs::path& staging) const {
  JobRecord job;
  job.key = staging.filename().string();
  job.name = up.job_name;
  job.priority = sub.priority;
  job.tag = sub.tag;
  job.settings = sub.settings;
  if (up.board) {  // what it is cut and sent with, on the record
    job.settings.feed_mm_s = defaults::kBoardFeedMmPerS;
    job.settings.tol_mm = defaults::kBoardChordToleranceMm;
    // A board sits where `engraver board` puts it unless the sender said otherwise.
    if (!sub.margin_given) job.settings.margin_mm = defaults::kBoardMarginMm;
  }
  return job;
}

IntakeResult JobIntake::plan_and_queue(const Submission& sub, const UploadedFiles& up) {
  IntakeResult r;
  const std::string& job_name = up.job_name;
  if (stopping_) {
    return refused(503, fmt::format("{}: the server is stopping: not queued (send it again once "
                                    "the server is back)",
                                    job_name));
  }
  const fs::path staging = data_.new_staging_dir();
  try {
    JobRecord job = new_record(sub, up, staging);
    std::string stored;
    if (up.board) {
      stage_board(sub, up.files, up.skip_other, up.zip, staging, &job, &stored);
    } else {
      stage_drawing(sub, up, staging, &job, &stored);
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
    r = refused(422, e.what());
  } catch (const PlanError& e) {
    r = refused(422, e.what());
  } catch (const StoreError& e) {
    r = refused(500, e.what());
  } catch (const WorkStopped&) {
    r = refused(503, fmt::format("{}: the server is stopping: not queued (send it again once "
                                 "the server is back)",
                                 job_name));
  } catch (const std::exception& e) {
    r = refused(500, fmt::format("{}: {}", job_name, e.what()));
  } catch (...) {
    // A reader threw something that is not an exception class.
    r = refused(422, fmt::format("{}: cannot be read as a drawing", job_name));
  }
  std::error_code ec;
  fs::remove_all(staging, ec);  // gone already when the job was queued
  return r;
}

}  // namespace host::server
