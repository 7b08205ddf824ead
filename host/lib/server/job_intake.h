// Turns an upload (web page, API, inbox) into a queued job: checks the name and settings,
// plans it at once (a job that cannot run is refused with the planner's message), writes
// its archive folder and queues it. A refused upload leaves nothing behind.
#ifndef HOST_LIB_SERVER_JOB_INTAKE_H
#define HOST_LIB_SERVER_JOB_INTAKE_H

#include <atomic>      // std::atomic
#include <cstdint>     // int64_t
#include <filesystem>  // std::filesystem::path
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/server/board_planning.h"
#include "host/lib/server/data_folder.h"
#include "host/lib/server/job_record.h"
#include "host/lib/server/job_store.h"

namespace host::server {

// One upload. A drawing is one file (name, content). A board is its Gerber/Excellon files
// (copper, drill, outline): one such file in name/content, or one zip file holding them in
// name/content, or several in `files` (then `name` is the board's name, "" to take it from
// the files' names, and content is unused).
struct Submission {
  std::string name;     // the file name the sender gave (display only)
  std::string content;  // the file's bytes, unless content_file is given
  // Or the file holding them (an HTTP upload received to disk, an inbox file): a drawing is
  // copied from it into the archive and planned from there, never read whole into memory
  // here (a 72 MB drawing was held four times at once); a board or zip is read (small).
  std::filesystem::path content_file;
  // What `name` is when it names a board of several files (refusals say so): the HTTP
  // form's field, an inbox folder's name.
  std::string name_source = "field 'name'";
  std::vector<UploadFile> files;
  bool skip_other_files = false;  // board from a folder: leave out its read-me and such
  int priority = 0;
  std::string tag;
  JobPlanSettings settings;
  bool margin_given = false;  // settings.margin_mm is the sender's; else a board gets board's 5 mm
  bool feed_given = false;    // a board refuses feed_mm_s (its feeds are the board planner's)
  bool tol_given = false;     // a board is sent with 1 um chords: tol_mm other than 0.001 refused
  BoardSettings board;
  std::vector<std::string> board_fields;  // the board's fields the sender gave (a drawing: none)
};

struct IntakeResult {
  int status = 0;     // HTTP-style: 201 queued, 400 bad request, 413 too large, 422 refused
  std::string error;  // why it was refused
  int64_t id = 0;     // the new job
};

class JobIntake {
 public:
  // machines: what the workshop's machines offer (a job must fit at least one).
  JobIntake(JobStore& store, const DataFolder& data, std::vector<MachineFit> machines,
            size_t max_bytes);
  IntakeResult submit(const Submission& submission);
  size_t max_bytes() const { return max_bytes_; }
  // The server stops: an upload being planned ends at once, answered 503 and not queued (the
  // inbox leaves its file where it is, for the next start); later ones get the same.
  void stop() { stopping_ = true; }
  static constexpr size_t kMaxFiles = 32;  // files of one board (a CAM folder with masks, silk)
  struct UploadedFiles;                    // the upload's files as checked (job_intake.cpp)

 private:
  // Plans the checked upload in a staging folder and queues it (the folder becomes the
  // job's archive folder); nothing is left behind when it is refused.
  IntakeResult plan_and_queue(const Submission& sub, const UploadedFiles& up);
  JobRecord new_record(const Submission& sub, const UploadedFiles& up,
                       const std::filesystem::path& staging) const;
  // Plans the upload into the staging folder; fills the job's plan-derived fields and the
  // bytes the store keeps. Throws ImportError / PlanError with the message for the sender.
  void stage_drawing(const Submission& sub, const UploadedFiles& up,
                     const std::filesystem::path& staging, JobRecord* job,
                     std::string* stored) const;
  // zip: the upload as it came when it was one zip file (kept as input.zip), else null. Planned
  // with job->settings (the board's margin resolved), sub.board.
  void stage_board(const Submission& sub, const std::vector<UploadFile>& files, bool skip_other,
                   const std::string* zip, const std::filesystem::path& staging, JobRecord* job,
                   std::string* stored) const;
  void work_area(double* w_mm, double* h_mm) const;

  JobStore& store_;
  const DataFolder& data_;
  std::vector<MachineFit> machines_;
  size_t max_bytes_;
  std::atomic<bool> stopping_{false};
};

// Why a file name from outside is refused ("" when it is acceptable): no folders, no "..",
// no control characters, no leading dot, 1..200 bytes. `what` begins the reason: what the
// name is to the sender ("field 'name' contains '..'").
constexpr const char* kFileName = "the file name";
std::string check_upload_name(const std::string& name, const std::string& what = kFileName);
// Why a tag is refused ("" when fine): [A-Za-z0-9_-], at most 32.
std::string check_tag(const std::string& tag);
// Why settings are refused ("" when fine): the same ranges as `engraver send`.
std::string check_settings(const JobPlanSettings& s);
// "input.dxf" for "Board.DXF"; "input" when the extension is not a known drawing format.
std::string archive_input_name(const std::string& upload_name);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_INTAKE_H
