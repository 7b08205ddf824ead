// Machine workers: claim, send, report, archive.
#include "host/lib/server/workshop.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>   // std::clamp
#include <cctype>      // std::isalnum
#include <filesystem>  // std::filesystem::path
#include <fstream>     // std::ofstream
#include <memory>      // std::unique_ptr
#include <optional>    // std::optional

#include "host/lib/drawing/drawing.h"
#include "host/lib/heightmap/controller_map.h"  // height_map_commands, controller_touch
#include "host/lib/heightmap/job_area.h"        // refuse_job_outside_map
#include "host/lib/heightmap/probe_session.h"   // probe_blank
#include "host/lib/plot/height_map_plot.h"      // write_height_map_svg
#include "host/lib/server/board_height_map.h"
#include "host/lib/server/board_planning.h"
#include "host/lib/server/job_continue.h"
#include "host/lib/server/job_path.h"
#include "host/lib/server/job_planning.h"
#include "host/lib/server/job_stream.h"
#include "host/lib/server/map_source.h"
#include "host/lib/server/run_archive.h"
#include "host/lib/server/time_left.h"
#include "host/lib/stream/job_resume.h"  // resume_from_curve
#include "host/lib/stream/link.h"

namespace host::server {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

// The file naming the server job whose commands machine `name` last executed: the wire
// job_id is a CRC of the commands, the same for two jobs of one file, so a machine's
// status cannot tell which of them it ran.
fs::path last_job_file(const DataFolder& data, const std::string& name) {
  std::string safe;
  for (const char c : name) safe += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return data.root() / "machines" / (safe + ".last_job");
}

int64_t read_last_job(const fs::path& file) {
  try {
    return std::stoll(read_file(file));
  } catch (const std::exception&) {
    return -1;  // none recorded (or unreadable): the machine's position is not trusted
  }
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

ResumeEncoder continue_from_curve() {
  return ContinueFromCurve();
}

// One machine: its spec, what it is doing now, and the sender of the running job. Its parts
// each do one job; `mutex` guards all of them.
struct Workshop::Slot {
  // The link to the machine, as the page shows it.
  struct Connection {
    std::string state = "unknown";  // unknown, online, offline
    std::string message;
    bool unzeroed = false;  // serve --no-zero, and the machine is not zeroed: it gets no job
    Link* link = nullptr;   // the sender's link, from connect to the end of its job
  };
  // What the machine last reported, and what its controller still holds.
  struct MachineSeen {
    proto::StatusReply last_status{};
    bool have_last_status = false;
    // The controller may still hold the map of this machine's last job (#A: it stays
    // through #I): the next job without one clears it first.
    bool controller_has_map = false;
  };
  // What the operator asked for while the job was planning: done when its commands start.
  struct PendingAsks {
    bool hold = false;
    bool abort = false;
    int override_percent = 0;  // 0 = none
  };
  // The running job's progress along its path.
  struct CutProgress {
    std::shared_ptr<const std::string> path_json;  // JobPath of the running job
    double executed_mm = 0;                        // along that path
    double path_mm = 0;
    Progress progress;
    bool have_status = false;
  };
  // The running job's clock: its time left, and the operator's waits that do not count.
  struct CutClock {
    TimeLeft time_left;  // of the cut (remaining_s)
    Clock::time_point started;
    // When its commands went to the sender: the cut's time left counts from here.
    Clock::time_point cut_started;
    // Time the machine stood waiting for the operator (held, paused): not in the time left.
    Clock::duration waited{};
    bool waiting = false;
    Clock::time_point waiting_since;
    // Seconds the cut has worked at `now`: since its commands went to the sender, less the
    // operator's waits (the caller holds the slot's mutex).
    double working_s(Clock::time_point now) const {
      const Clock::duration waits = waited + (waiting ? now - waiting_since : Clock::duration{});
      return std::chrono::duration<double>(now - cut_started - waits).count();
    }
    // Starts or ends a wait for the operator (the caller holds the slot's mutex).
    void set_waiting(bool now_waiting) {
      const Clock::time_point now = Clock::now();
      if (now_waiting && !waiting) waiting_since = now;
      if (!now_waiting && waiting) waited += now - waiting_since;
      waiting = now_waiting;
    }
  };
  // A probe-first board job before it cuts.
  struct Probing {
    // "probe_clip" (waiting for the operator to put the probe clip on the blank and
    // confirm), then "probing"; "" otherwise.
    std::string stage;
    bool confirmed = false;
    Sender* sender = nullptr;  // while probing: an abort stops the touch
    size_t done = 0, total = 0;
  };

  MachineSpec spec;
  std::mutex mutex;  // guards everything below
  Connection connection;
  MachineSeen seen;
  Sender* sender = nullptr;  // while a job runs
  int64_t job_id = 0;        // from its claim until it ends
  std::string job_name;
  bool planning = false;    // claimed, its commands not made yet (no sender)
  int64_t lease_epoch = 0;  // the lease the running job was claimed under
  std::string fenced;       // why the running job was stopped for its lease ("" = it was not)
  PendingAsks asked;
  CutProgress cut;
  CutClock clock;
  Probing probe;
};

namespace {

// Why a machine gets no job under serve --no-zero (on the page as the machine's message).
constexpr const char* kUnzeroedMachine =
    "not zeroed: with serve --no-zero it gets no job until it is zeroed (a server without "
    "--no-zero, or engraver send, starts manual zeroing on it)";

// The operator aborted a job before it cut (waiting for the probe clip, or probing), or the
// server stopped then. what() is the stage ("probing", "waiting for the probe clip").
class AbortedBeforeCutting : public std::runtime_error {
 public:
  explicit AbortedBeforeCutting(const std::string& while_doing, std::string detail = "")
      : std::runtime_error(while_doing), detail(std::move(detail)) {}
  std::string detail;  // e.g. whether the tool was raised; "" = nothing to add
};

// A continued job: its earlier runs cut, and it resumes where they stopped.
bool continued_run(const JobRecord& job) {
  return job.resume_index >= 0 || job.start_curve >= 0;
}

// Where a continued job's earlier runs stopped, over the whole job.
// (job_commands 0: not known, the run ended before its commands were made.)
std::string whole_job_point(const JobRecord& job, size_t job_commands) {
  if (job.resume_index < 0) return fmt::format("curve {}", job.start_curve);
  return job_commands > 0 ? fmt::format("job command {} of {}", job.resume_index, job_commands)
                          : fmt::format("job command {}", job.resume_index);
}

// Why a run ended before it cut. A continued job's earlier runs did cut, so its message
// says where the whole job stands, not "nothing was cut" (issue 25's outside tester).
std::string before_cutting_message(const JobRecord& job, size_t job_commands, bool server_stopping,
                                   const AbortedBeforeCutting& e) {
  const std::string cut =
      continued_run(job)
          ? fmt::format(
                "nothing more was cut in this run (the job's earlier runs cut up to {}; "
                "it continues there)",
                whole_job_point(job, job_commands))
          : std::string("nothing was cut");
  std::string message =
      fmt::format("{} while {}; {}",
                  server_stopping ? "the server stopped (interrupted)" : "aborted", e.what(), cut);
  if (!e.detail.empty()) message += " (" + e.detail + ")";
  return message;
}

// An interrupted run's message (link lost, stalled, the server stopped): the sender counted
// this run's stream; where the whole job stands, where continue resumes ("" before its first
// job command).
std::string whole_job_position(int64_t resume_index, size_t job_commands) {
  return resume_index >= 0 ? fmt::format(
                                 " (counts of this run; the job is at job command {} of "
                                 "{}, where continue resumes)",
                                 resume_index, job_commands)
                           : "";
}

// The action as the API names it.
const char* control_name(JobControl control) {
  switch (control) {
    case JobControl::kHold:
      return "hold";
    case JobControl::kResume:
      return "resume";
    case JobControl::kAbort:
      return "abort";
    case JobControl::kOverride:
      return "override";
    case JobControl::kConfirmProbe:
      break;
  }
  return "probe_ready";
}

// A board job whose board.json this archive holds (not another server's upload): what it
// probes is known here.
bool board_in_archive(const DataFolder& data, const JobRecord& job) {
  try {
    read_board_settings(data.job_dir(job.key));
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

// Why no machine waits for a job's probe clip.
enum class NoClipWait {
  kProbing,    // the clip was confirmed: it is probing
  kCutting,    // the clip was confirmed: it is cutting
  kPlanning,   // its machine is still planning it
  kUnclaimed,  // queued: no machine has claimed it yet
  kElsewhere,  // running on another server's machine
  kNotRunning  // stopped: continue or requeue it first
};

const char* no_clip_why(NoClipWait why) {
  switch (why) {
    case NoClipWait::kProbing:
      return "it is probing already";
    case NoClipWait::kCutting:
      return "it is cutting";
    case NoClipWait::kPlanning:
      return "its machine is still planning it";
    case NoClipWait::kUnclaimed:
      return "no machine has claimed it yet";
    case NoClipWait::kElsewhere:
      return "it runs on another server's machine";
    case NoClipWait::kNotRunning:
      break;
  }
  return "it is not running (continue or requeue it first)";
}

// The 409 to probe_ready when no machine waits for the clip: the job and its state first
// (the actions' one rule), why, and when to send it (never, for a job that has ended).
std::string no_clip_wait(int64_t job_id, JobState state, NoClipWait why) {
  if (is_final(state)) {
    return fmt::format("job {} is {}: no machine is waiting for its probe clip: the job has ended",
                       job_id, state_name(state));
  }
  // Probing already or cutting: the clip was confirmed, nothing to wait for.
  const bool later = why != NoClipWait::kProbing && why != NoClipWait::kCutting;
  return fmt::format("job {} is {}: no machine is waiting for its probe clip: {}{}", job_id,
                     state_name(state), no_clip_why(why),
                     later ? " (send probe_ready once the job's machine_state in /api/status is "
                             "probe_clip)"
                           : "");
}

}  // namespace

Workshop::Workshop(JobStore& store, const DataFolder& data, std::vector<MachineSpec> machines,
                   WorkshopOptions options)
    : store_(store),
      data_(data),
      options_(std::move(options)),
      lease_(store, options_.owner, options_.holder, options_.stale_after),
      saver_(store, options_.progress_interval, [this](int64_t id) { save_refused(id); }) {
  for (MachineSpec& m : machines) {
    auto slot = std::make_unique<Slot>();
    slot->spec = std::move(m);
    slots_.push_back(std::move(slot));
  }
}

Workshop::~Workshop() {
  stop();
}

std::vector<MachineFit> Workshop::fits() const {
  std::vector<MachineFit> out;
  for (const auto& s : slots_) out.push_back(s->spec.fit);
  return out;
}

MachineAvailability Workshop::availability(const std::string& machine) const {
  for (const auto& s : slots_) {
    if (s->spec.name != machine) continue;
    std::lock_guard<std::mutex> lock(s->mutex);
    if (s->connection.state != "online") return MachineAvailability::kOffline;
    return s->job_id != 0 ? MachineAvailability::kBusy : MachineAvailability::kFree;
  }
  return MachineAvailability::kNotHere;
}

std::string Workshop::unzeroed_wait(const JobRecord& job) const {
  if (job.state != JobState::kQueued) return "";
  std::vector<std::string> unzeroed;
  for (const auto& s : slots_) {
    if (!job_fits(job, s->spec.fit)) continue;
    std::lock_guard<std::mutex> lock(s->mutex);
    if (s->connection.state != "online") continue;
    if (!s->connection.unzeroed) return "";  // a machine that takes it (once free)
    unzeroed.push_back(fmt::format("'{}'", s->spec.name));
  }
  if (unzeroed.empty()) return "";
  std::string names;
  for (const std::string& n : unzeroed) names += (names.empty() ? "" : ", ") + n;
  // The machine's own message after its name, as /api/status gives it.
  return fmt::format("waiting for machine{} {}, {}", unzeroed.size() > 1 ? "s" : "", names,
                     kUnzeroedMachine);
}

void Workshop::start() {
  lease_.acquire();
  store_.interrupt_running(options_.owner, "the server stopped while the job was running");
  stopping_ = false;
  heartbeat_thread_ = std::thread([this] { heartbeat_loop(); });
  for (auto& slot : slots_) {
    Slot* s = slot.get();
    threads_.emplace_back([this, s] { machine_loop(*s); });
  }
}

void Workshop::stop() {
  if (threads_.empty() && !heartbeat_thread_.joinable()) return;
  stopping_ = true;
  for (auto& slot : slots_) {
    std::lock_guard<std::mutex> lock(slot->mutex);
    if (slot->sender != nullptr) slot->sender->request_abort();
    // Probing stops at once too (the touch under way: #X), not after the grid.
    if (slot->probe.sender != nullptr) slot->probe.sender->request_abort();
  }
  change_cv_.notify_all();
  for (std::thread& t : threads_) t.join();
  threads_.clear();
  if (heartbeat_thread_.joinable()) heartbeat_thread_.join();
}

void Workshop::heartbeat_loop() {
  while (!stopping_) {
    try {
      const int64_t epoch = lease_.current().epoch;
      if (lease_.renew() == ServerLease::Renewal::kLost) {
        if (epoch != 0) lease_lost(lease_.why_not(epoch));  // once per lease
        lease_.acquire();  // a fresh epoch for new jobs; the old ones stay interrupted
        if (options_.say) options_.say(fmt::format("took a new lease as '{}'", options_.owner));
      }
      if (store_.interrupt_stale(options_.stale_after.count(),
                                 "the server running the job stopped answering") > 0) {
        notify(true);
      }
    } catch (const StoreError&) {
      // The database is away; the next beat tries again.
    }
    std::unique_lock<std::mutex> lock(change_mutex_);
    change_cv_.wait_for(lock, options_.heartbeat, [&] { return stopping_.load(); });
  }
}

// The store revoked our lease (we were taken for dead): every machine still running a job
// under it is stopped (#X: the controller keeps the job's position for "continue").
void Workshop::lease_lost(const std::string& why) {
  if (options_.say) options_.say(why);
  for (auto& slot : slots_) {
    std::lock_guard<std::mutex> lock(slot->mutex);
    if (slot->sender == nullptr) continue;
    slot->fenced = why;
    slot->sender->request_abort();
    slot->connection.message = why;
  }
  notify(true);
}

// The store refused a running job's progress: it no longer runs under our lease.
void Workshop::save_refused(int64_t job_id) {
  for (auto& slot : slots_) {
    std::lock_guard<std::mutex> lock(slot->mutex);
    if (slot->job_id != job_id || slot->sender == nullptr) continue;
    slot->fenced = fmt::format(
        "the store refused job {}'s progress: it no longer runs under "
        "this server's lease; stopped",
        job_id);
    slot->sender->request_abort();
    slot->connection.message = slot->fenced;
  }
}

void Workshop::sleep_for(std::chrono::milliseconds ms) {
  std::unique_lock<std::mutex> lock(change_mutex_);
  const uint64_t jobs_seen = jobs_version_;
  // A new job wakes idle machines at once.
  change_cv_.wait_for(lock, ms, [&] { return stopping_ || jobs_version_ != jobs_seen; });
}

void Workshop::notify(bool jobs_changed) {
  {
    std::lock_guard<std::mutex> lock(change_mutex_);
    ++version_;
    if (jobs_changed) ++jobs_version_;
  }
  change_cv_.notify_all();
}

uint64_t Workshop::wait_change(uint64_t seen, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(change_mutex_);
  change_cv_.wait_for(lock, timeout, [&] { return stopping_ || version_ != seen; });
  return version_;
}

ControlResult Workshop::control(int64_t job_id, JobControl control, int percent) {
  if (control == JobControl::kConfirmProbe) {
    // A job that probes nothing never asks for the clip: say so, not "wait for probe_clip".
    const std::optional<JobRecord> job = store_.get(job_id);
    if (!job) return {404, fmt::format("no job {}", job_id)};
    const int64_t map_job = height_map_job_of(data_, *job);
    if (map_job != job_id &&
        (map_job != 0 || !is_board_job(*job) || board_in_archive(data_, *job))) {
      const std::string what =
          map_job != 0 ? fmt::format("it cuts with job {}'s height map and probes nothing", map_job)
          : is_board_job(*job)
              ? std::string("a board uploaded without probe_first=1 probes nothing")
              : std::string("a drawing probes nothing");
      return {409, fmt::format("job {} is {}: {}: no machine asks for the probe clip, send no "
                               "probe_ready",
                               job_id, state_name(job->state), what)};
    }
  }
  for (auto& slot : slots_) {
    std::lock_guard<std::mutex> lock(slot->mutex);
    if (slot->job_id != job_id || (slot->sender == nullptr && !slot->planning)) continue;
    if (control == JobControl::kConfirmProbe) {
      if (slot->probe.stage != "probe_clip") {
        return {409, no_clip_wait(job_id, JobState::kRunning,
                                  slot->probe.stage == "probing" ? NoClipWait::kProbing
                                  : slot->planning               ? NoClipWait::kPlanning
                                                                 : NoClipWait::kCutting)};
      }
      slot->probe.confirmed = true;
      notify(false);
      return {};
    }
    if (slot->sender == nullptr) {  // still planning: kept for when its commands start
      if (control == JobControl::kAbort && slot->probe.sender != nullptr) {
        slot->probe.sender->request_abort();
      }
      // A hold while probing stops it between touches (probing_touch); wake its wait.
      if (control != JobControl::kOverride) notify(false);
      switch (control) {
        case JobControl::kConfirmProbe:
          break;
        case JobControl::kHold:
          slot->asked.hold = true;
          break;
        case JobControl::kResume:
          slot->asked.hold = false;
          break;
        case JobControl::kAbort:
          slot->asked.abort = true;
          break;
        case JobControl::kOverride:
          if (percent < 10 || percent > 200) return {400, "override must be 10 .. 200 percent"};
          slot->asked.override_percent = percent;
          break;
      }
      return {};
    }
    switch (control) {
      case JobControl::kHold:
        slot->sender->request_hold();
        break;
      case JobControl::kResume:
        // Resuming under a lapsed lease could cut what another machine now cuts.
        if (!lease_.valid(slot->lease_epoch)) {
          return {409,
                  fmt::format("job {} is running: {}", job_id, lease_.why_not(slot->lease_epoch))};
        }
        slot->sender->request_resume();
        break;
      case JobControl::kAbort:
        slot->sender->request_abort();
        break;
      case JobControl::kOverride:
        if (percent < 10 || percent > 200) return {400, "override must be 10 .. 200 percent"};
        slot->sender->request_override(percent);
        break;
      case JobControl::kConfirmProbe:
        break;
    }
    return {};
  }
  const std::optional<JobRecord> job = store_.get(job_id);
  if (!job) return {404, fmt::format("no job {}", job_id)};
  if (control == JobControl::kConfirmProbe) {
    return {409, no_clip_wait(job_id, job->state,
                              job->state == JobState::kQueued    ? NoClipWait::kUnclaimed
                              : job->state == JobState::kRunning ? NoClipWait::kElsewhere
                                                                 : NoClipWait::kNotRunning)};
  }
  // One rule: the machine's actions go to a job running on a machine of this server; in any
  // other state they are refused, the state named.
  const char* action = control_name(control);
  if (job->state != JobState::kRunning) {
    return {409, fmt::format("job {} is {}: {} applies to a running job only", job_id,
                             state_name(job->state), action)};
  }
  if (job->owner != options_.owner) {
    return {409, fmt::format("job {} is running on server '{}' (machine '{}'): send {} to that "
                             "server",
                             job_id, job->owner, job->machine, action)};
  }
  return {409, fmt::format("job {} is running: its machine '{}' is starting or ending it, "
                           "try {} again",
                           job_id, job->machine, action)};
}

nlohmann::json Workshop::snapshot() {
  nlohmann::json machines = nlohmann::json::array();
  nlohmann::json running = nlohmann::json::array();
  for (auto& slot : slots_) {
    std::lock_guard<std::mutex> lock(slot->mutex);
    nlohmann::json m;
    m["name"] = slot->spec.name;
    m["address"] = slot->spec.address;
    m["work_mm"] = {slot->spec.fit.work_width_mm, slot->spec.fit.work_height_mm};
    m["tags"] = slot->spec.fit.tags;
    m["link"] = slot->connection.state;
    m["message"] = slot->connection.message;
    m["job"] = slot->job_id != 0 ? nlohmann::json(slot->job_id) : nlohmann::json();
    const bool probing = !slot->probe.stage.empty();
    // The hold the server has accepted, shown at once in every field: no touch starts until
    // resume (the one under way finishes and retracts first; its position stays live).
    const bool probe_held = probing && slot->asked.hold && !slot->asked.abort;
    // An abort taken: the touch stops and the tool goes up before the job ends; never shown
    // as probing again (a held job goes held -> aborting -> aborted).
    const bool probe_aborting = probing && slot->asked.abort;
    // A hold taken for a job not probing, shown at once: while planning, after the last
    // touch and in the cut's first statuses the controller has not been told yet (it is,
    // before the first command), so its idle or running must not show.
    const bool hold_taken = slot->job_id != 0 && !probing && slot->asked.hold && !slot->asked.abort;
    const auto state_shown = [hold_taken](const proto::StatusReply& st) -> const char* {
      const proto::MachineState s = st.state;
      const bool moving_or_free =
          s == proto::MachineState::kIdle || s == proto::MachineState::kRunning;
      return hold_taken && moving_or_free ? "held" : machine_state_name(s);
    };
    // Waiting for the clip and probing are the workshop's: the machine's own state then is
    // idle, which the operator must not read as "free".
    const char* probe_state = probe_aborting                      ? "aborting"
                              : probe_held                        ? "held"
                              : slot->probe.stage == "probe_clip" ? "probe_clip"
                                                                  : "probing";
    // A machine that has claimed a job is never shown idle (free): until the cut's first
    // status it is the job's (planning, starting, or held as asked).
    // An idle controller before the run's first command has executed is still starting.
    const bool cut_reported =
        slot->cut.have_status && (slot->cut.progress.executed > 0 ||
                                  slot->cut.progress.status.state != proto::MachineState::kIdle);
    const char* claimed = slot->job_id == 0 || probing || cut_reported ? nullptr
                          : hold_taken                                 ? "held"
                          : slot->planning                             ? "planning"
                                                                       : "starting";
    if (slot->seen.have_last_status) {
      const proto::StatusReply& st = slot->seen.last_status;
      m["state"] = probing ? probe_state : claimed != nullptr ? claimed : state_shown(st);
      m["position_mm"] = {st.x_um / 1000.0, st.y_um / 1000.0, st.z_um / 1000.0};
    } else if (probing || claimed != nullptr) {
      m["state"] = probing ? probe_state : claimed;
    } else {
      m["state"] = slot->connection.state == "online" ? "idle" : "unknown";
    }
    machines.push_back(m);
    if (slot->job_id == 0) continue;
    const Progress& p = slot->cut.progress;
    const double elapsed = seconds_since(slot->clock.started);
    const double f = p.total > 0 ? double(p.executed) / double(p.total) : 0.0;
    // The cut's time left (TimeLeft): before its commands run (planning, the probe clip,
    // probing: the probe object counts the touches) the planned time, standing still; then
    // the plan's time from the step the machine is at, at the pace it has kept. Time spent
    // waiting for the operator is not work: it stands still then.
    const double remaining = slot->clock.time_left.remaining(
        slot->sender != nullptr ? slot->clock.working_s(Clock::now()) : 0.0);
    nlohmann::json j;
    j["id"] = slot->job_id;
    j["name"] = slot->job_name;
    j["machine"] = slot->spec.name;
    j["executed"] = p.executed;
    j["total"] = p.total;
    j["fraction"] = f;
    j["elapsed_s"] = elapsed;
    j["remaining_s"] = remaining;
    j["machine_state"] = probing ? probe_state : claimed ? claimed : state_shown(p.status);
    if (!slot->probe.stage.empty()) {
      j["probe"] = {{"stage", slot->probe.stage},
                    {"touches", slot->probe.done},
                    {"planned", slot->probe.total},
                    {"held", probe_held},
                    {"ask", probe_aborting ? "aborted: the tool goes up, nothing is cut"
                            : slot->probe.stage == "probe_clip"
                                ? "put the probe clip on the blank, the spindle off, then "
                                  "confirm (action probe_ready)"
                                : "probing the blank"}};
    }
    j["override_percent"] = slot->cut.have_status ? p.status.override_percent : 100;
    // The machine's reported position and how far along the job's path it has got.
    j["position_mm"] = nlohmann::json();
    if (slot->cut.have_status) {
      j["position_mm"] = {p.status.x_um / 1000.0, p.status.y_um / 1000.0, p.status.z_um / 1000.0};
    } else if ((probing || hold_taken) && slot->seen.have_last_status) {
      const proto::StatusReply& st = slot->seen.last_status;
      j["position_mm"] = {st.x_um / 1000.0, st.y_um / 1000.0, st.z_um / 1000.0};
    }
    j["executed_mm"] = slot->cut.executed_mm;
    j["path_mm"] = slot->cut.path_mm;
    running.push_back(j);
  }
  uint64_t version = 0, jobs_version = 0;
  {
    std::lock_guard<std::mutex> lock(change_mutex_);
    version = version_;
    jobs_version = jobs_version_;
  }
  return {{"machines", machines},
          {"running", running},
          {"version", version},
          {"jobs_version", jobs_version},
          {"can_continue", can_continue()}};
}

std::shared_ptr<const std::string> Workshop::live_path(int64_t job_id) {
  for (auto& slot : slots_) {
    std::lock_guard<std::mutex> lock(slot->mutex);
    if (slot->job_id == job_id && slot->cut.path_json) return slot->cut.path_json;
  }
  return nullptr;
}

MachineFit Workshop::fit_now(const Slot& slot) {
  std::vector<std::string> machines;
  for (const auto& other : slots_) machines.push_back(other->spec.name);
  MachineFit fit = slot.spec.fit;
  fit.not_now_ids = jobs_not_for_machine(store_, data_, slot.spec.name, machines);
  return fit;
}

void Workshop::machine_loop(Slot& slot) {
  Clock::time_point next_probe = Clock::now();
  while (!stopping_) {
    bool work = false;
    try {
      // A bottom side whose top side ended without a map fails here, never claimed.
      if (fail_jobs_without_map_source(store_, data_) > 0) notify(true);
      work = store_.has_claimable(fit_now(slot));
    } catch (const StoreError& e) {
      std::lock_guard<std::mutex> lock(slot.mutex);
      slot.connection.message = e.what();
    }
    if (!work && Clock::now() < next_probe) {
      sleep_for(options_.poll);
      continue;
    }
    next_probe = Clock::now() + options_.probe;
    // Connect and open a session before claiming: a job only leaves the queue for a machine
    // that answers.
    std::unique_ptr<Link> link;
    std::unique_ptr<Sender> sender;
    proto::SessionReply caps{};
    proto::StatusReply idle_status{};  // the machine between jobs, as the page shows it
    try {
      link = open_link(parse_link_spec(slot.spec.address), options_.connect_timeout);
      SenderOptions so = options_.sender;
      // Each batch of commands goes out only under the lease its job was claimed with.
      // A veto is kept as the slot's reason: the job ends interrupted (continuable), not
      // aborted.
      so.send_veto = [this, &slot] {
        std::lock_guard<std::mutex> lock(slot.mutex);
        if (slot.fenced.empty()) slot.fenced = lease_.why_not(slot.lease_epoch);
        return slot.fenced;
      };
      sender = std::make_unique<Sender>(*link, so);
      caps = sender->open_session();
      idle_status = sender->read_status();
    } catch (const std::exception& e) {
      bool changed = false;
      {
        std::lock_guard<std::mutex> lock(slot.mutex);
        changed = slot.connection.state != "offline";
        slot.connection.state = "offline";
        slot.connection.message = e.what();
        slot.connection.unzeroed = false;
        slot.seen.have_last_status = false;
      }
      if (changed) notify(false);
      sleep_for(std::min(options_.probe, std::chrono::milliseconds(1000)));
      continue;
    }
    // --no-zero: a machine that is not zeroed gets no job (it would cut where it stands, not
    // where the job is drawn); it waits, saying so on the page, until zeroed at the machine.
    const bool unzeroed =
        !options_.sender.zero_first && !(idle_status.flags & proto::kStatusZeroed);
    const std::string message = unzeroed ? std::string(kUnzeroedMachine) : std::string();
    bool changed = false;
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      changed = slot.connection.state != "online" || !slot.seen.have_last_status ||
                slot.seen.last_status.state != idle_status.state ||
                slot.connection.message != message;
      slot.connection.state = "online";
      slot.connection.message = message;
      slot.connection.unzeroed = unzeroed;
      slot.seen.last_status = idle_status;
      slot.seen.have_last_status = true;
    }
    if (changed) notify(false);
    const Lease lease = lease_.current();
    if (!work || stopping_) continue;
    if (unzeroed) {
      sleep_for(std::min(options_.probe, std::chrono::milliseconds(1000)));
      continue;
    }
    if (!lease_.valid(lease.epoch)) {  // the heartbeat renews it or takes a new one
      sleep_for(options_.poll);
      continue;
    }
    std::optional<JobRecord> job;
    try {
      job = store_.claim(fit_now(slot), slot.spec.name, lease);
    } catch (const StoreError& e) {
      std::lock_guard<std::mutex> lock(slot.mutex);
      slot.connection.message = e.what();
      continue;
    }
    if (!job) continue;
    notify(true);
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      slot.connection.link = link.get();
    }
    run_job(slot, *job, *sender, caps);
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      slot.connection.link = nullptr;
    }
    notify(true);
  }
}

// One run of a job on a machine: what its steps share, and how it ended (report.json).
struct Workshop::JobRun {
  JobRun(const JobRecord& record, const fs::path& job_dir)
      : job(record), dir(job_dir), lease{record.owner, record.lease_epoch} {
    progress.resume_curve = job.resume_curve;
    progress.resume_index = job.resume_index;
    progress.resume_point = job.resume_point;
    progress.resume_job_id = job.resume_job_id;
    try {
      archive = std::make_unique<RunArchive>(dir);
    } catch (const std::exception& e) {
      archive_error = e.what();
    }
  }
  // A line of this run's machine.log; a log that cannot be written ends nothing (the
  // job's message says the log is incomplete).
  void note(const std::string& line) {
    if (!archive || !archive_error.empty()) return;
    try {
      archive->log(fmt::format("{:9.3f} {}", seconds_since(started), line));
    } catch (const std::exception& e) {
      archive_error = e.what();
    }
  }
  std::function<void(const std::string&)> noter() {
    return [this](const std::string& line) { note(line); };
  }

  const JobRecord& job;
  const fs::path dir;
  const Clock::time_point started = Clock::now();
  const Lease lease;
  std::unique_ptr<RunArchive> archive;  // this run's folder in the archive
  std::string archive_error;
  JobState state = JobState::kFailed;
  const char* outcome = "not started";
  std::string message;
  // The plan and its stream live past the try: an interrupted job's first uncut curve.
  std::shared_ptr<const JobPlan> planned;  // shared with the time left while it runs
  std::optional<JobStream> commands;
  size_t executed = 0;
  // The feed override as the machine reported it: when it changed and to what.
  nlohmann::json overrides = nlohmann::json::array();
  uint16_t job_id = 0;          // the controller's id of the whole job (#J)
  size_t setup_frames = 0;      // sent before the job's own #J (its height map)
  size_t first_step_index = 0;  // the first command along the path: executed_mm 0 before it
  bool before_cutting = false;  // ended waiting for the clip or probing: nothing of it ran
  bool streaming = false;       // its commands went to the sender (executed counts them)
  bool machine_marked = false;  // the machine's last job file names this job
  // Where it stands; a continued job keeps its saved position until the machine reports.
  JobProgress progress;
  nlohmann::json height_map;    // the map the job was cut with (report.json), null: none
  std::optional<JobPath> path;  // the tool path, for the live position along it
  // What the progress callback has reported so far.
  proto::MachineState last_state = proto::MachineState::kIdle;
  int last_override = -1;  // none reported yet
  Clock::time_point last_notify = started;
};

void Workshop::run_job(Slot& slot, const JobRecord& job, Sender& sender,
                       const proto::SessionReply& caps) {
  JobRun r(job, data_.job_dir(job.key));
  r.note(fmt::format("job {} '{}' on {} ({}), server {}", job.id, job.name, slot.spec.name,
                     slot.spec.address, options_.owner));
  r.note(fmt::format("session: protocol v{}, max payload {}, window {}", int(caps.protocol_version),
                     int(caps.max_payload), int(caps.window_frames)));
  claim_slot(slot, r);
  // The zeroing the sender starts itself (#M) goes to this run's log; the sender outlives
  // the run.
  sender.set_note(r.noter());
  struct NoteOff {
    Sender& sender;
    ~NoteOff() { sender.set_note(nullptr); }
  } note_off{sender};
  try {
    make_commands(slot, r, sender, caps);
    hand_to_sender(slot, r, sender);
    stream_commands(slot, r, sender);
  } catch (const LinkError& e) {
    r.state = JobState::kInterrupted;
    r.outcome = "link lost";
    r.message = e.what();
    // Lost while streaming (a machine killed, its socket closed): the same counts as a
    // silent link's message.
    if (r.streaming) {
      r.message += fmt::format(" after {} of {} commands executed", r.executed, r.commands->size());
      r.message += whole_job_position(r.progress.resume_index, r.commands->job_commands());
    }
  } catch (const AbortedBeforeCutting& e) {
    r.state = stopping_ ? JobState::kInterrupted : JobState::kAborted;
    r.outcome = stopping_ ? "server stopped before cutting" : "aborted before cutting";
    r.message =
        before_cutting_message(job, r.commands ? r.commands->job_commands() : 0, stopping_, e);
    r.before_cutting = true;
  } catch (const std::exception& e) {
    r.state = JobState::kFailed;
    r.outcome = "not sent";
    r.message = e.what();
  }
  release_slot(slot, r, sender);
  finish_run(slot, r, sender);
  r.path.reset();
  r.commands.reset();
  r.planned.reset();
  release_freed_memory();  // the plan: an idle machine holds none of it
}

// Claimed: on the page (planning) and steerable before its commands exist.
void Workshop::claim_slot(Slot& slot, const JobRun& r) {
  {
    std::lock_guard<std::mutex> lock(slot.mutex);
    slot.job_id = r.job.id;
    slot.job_name = r.job.name;
    slot.planning = true;
    slot.probe.stage.clear();
    slot.probe.confirmed = false;
    slot.lease_epoch = r.job.lease_epoch;  // probing sends before the job's commands do
    slot.fenced.clear();
    slot.probe.done = slot.probe.total = 0;
    slot.asked.hold = slot.asked.abort = false;
    slot.asked.override_percent = 0;
    slot.cut.path_json.reset();
    slot.cut.executed_mm = slot.cut.path_mm = 0;
    slot.cut.progress = Progress{};
    slot.cut.have_status = false;
    slot.clock.time_left.plan(nullptr, r.job.planned_s);
    slot.clock.started = r.started;
    slot.clock.waited = Clock::duration{};
    slot.clock.waiting = false;
  }
  notify(false);
}

// The job's plan and commands (continued where it stopped), its height map first.
void Workshop::make_commands(Slot& slot, JobRun& r, Sender& sender,
                             const proto::SessionReply& caps) {
  const JobRecord& job = r.job;
  // Uploaded to another server sharing the queue: the input comes from the store.
  const bool fetched = !fs::exists(r.dir / job.input_file);
  if (fetched) {
    const std::optional<std::string> bytes = store_.input(job.id);
    if (!bytes) throw std::runtime_error((r.dir / job.input_file).string() + ": missing");
    restore_job_input(r.dir, job, *bytes);
  }
  // A server that stops, or an abort, ends the planning of a large job at once.
  const StopAsked stop = [this, &slot] {
    std::lock_guard<std::mutex> lock(slot.mutex);
    return stopping_ || slot.asked.abort;
  };
  try {
    r.planned = std::make_shared<const JobPlan>(plan_archived_job(
        r.dir, job, slot.spec.fit.work_width_mm, slot.spec.fit.work_height_mm, fetched, stop));
  } catch (const WorkStopped&) {
    throw AbortedBeforeCutting("planning");
  }
  const JobPlan& plan = *r.planned;
  EncodeOptions enc = encode_options(job);
  use_session(caps, &enc);
  // Encoded as the sender goes (and again for the progress): never held whole.
  r.commands.emplace(plan, enc);
  r.job_id = r.commands->job_id();
  if (job.start_curve >= 0 || job.resume_index >= 0) {
    const bool machine_ran_it = read_last_job(last_job_file(data_, slot.spec.name)) == job.id;
    continue_stream(job, plan, enc, sender, options_.resume_encoder, machine_ran_it, r.noter(),
                    &*r.commands);
  }
  // The height map goes first (a continued job sends it again: a restarted controller
  // has lost it); a job without one clears the last job's.
  const std::optional<heightmap::HeightMap> map =
      board_height_map(slot, job, plan, sender, r.noter());
  bool clear_map = false;
  {
    std::lock_guard<std::mutex> lock(slot.mutex);
    clear_map = !map && slot.seen.controller_has_map;
    slot.seen.controller_has_map = static_cast<bool>(map);
  }
  if (map) {
    const std::vector<QueuedCommand> frames = heightmap::height_map_commands(*map);
    r.setup_frames = frames.size();
    r.commands->set_setup(frames);
    r.height_map = nlohmann::json{{"file", std::string(kHeightMapFile)},
                                  {"rows", map->rows},
                                  {"cols", map->cols},
                                  {"min_um", map->min_um()},
                                  {"max_um", map->max_um()},
                                  {"probed_at", map->probed_at}};
  } else if (clear_map) {
    r.commands->set_setup({heightmap::clear_height_map_command()});
    r.setup_frames = 1;
    r.note("the last job's height map cleared on the controller");
  }
  r.note(fmt::format("planned: {} curves, {} commands, {} bytes, about {:.1f} s",
                     plan.curves.size(), r.commands->size(), r.commands->wire_bytes(),
                     job.planned_s));
  r.path.emplace(plan);
  release_freed_memory();  // the drawing and the planner's temporaries
}

// The commands exist: the slot takes the sender and what the operator asked for meanwhile.
void Workshop::hand_to_sender(Slot& slot, JobRun& r, Sender& sender) {
  auto path_json = std::make_shared<const std::string>(r.path->to_json().dump());
  r.first_step_index = r.commands->first_step_index();
  // A continued run's time left counts from where it resumes (its prefix's way back may
  // carry earlier steps).
  const int first_step =
      r.commands->resumed_step() >= 0 ? r.commands->resumed_step() : r.commands->step_from(0);
  auto step_ends = std::make_shared<const PlannedTimes>(r.planned);
  // Its size and first curve are known now: not "0 of 0" in the store while the first
  // status is awaited, and continuable from that curve whatever stops it next.
  r.progress = progress_of(r.progress, r.commands->size(), 0, r.commands->first_uncut_curve(0),
                           proto::StatusReply{}, r.job_id);
  saver_.post(r.job.id, r.lease, r.progress, true);
  {
    std::lock_guard<std::mutex> lock(slot.mutex);
    slot.sender = &sender;
    slot.planning = false;
    slot.clock.cut_started = Clock::now();
    slot.clock.waited = Clock::duration{};
    slot.clock.waiting = false;
    slot.clock.time_left.plan(std::move(step_ends), r.job.planned_s);
    slot.clock.time_left.start_at(first_step);
    slot.cut.progress = Progress{};
    slot.cut.progress.total = r.commands->size();
    slot.cut.path_json = std::move(path_json);
    slot.cut.path_mm = r.path->length_mm();
    slot.lease_epoch = r.job.lease_epoch;
    slot.fenced.clear();
    if (stopping_) sender.request_abort();  // claimed just as stop() looked at the slots
    // Asked for while it was planning; run() sends them before its first command (the
    // override after this run's reset to 100 %).
    if (slot.asked.abort) sender.request_abort();
    if (slot.asked.hold) sender.request_hold();
    if (slot.asked.override_percent != 0) sender.request_override(slot.asked.override_percent);
    if (slot.asked.hold || slot.asked.abort || slot.asked.override_percent != 0) {
      r.note(fmt::format("asked for while planning:{}{}{}", slot.asked.hold ? " hold" : "",
                         slot.asked.abort ? " abort" : "",
                         slot.asked.override_percent != 0
                             ? fmt::format(" override {}%", slot.asked.override_percent)
                             : ""));
    }
  }
  notify(false);
}

// Sends the commands, following each status, and judges how the run ended.
void Workshop::stream_commands(Slot& slot, JobRun& r, Sender& sender) {
  // A feed override belongs to the job that set it: every run starts at 100 %, whatever
  // the machine's last job left.
  if (!sender.set_override(100)) throw LinkError("the machine did not take feed override 100%");
  r.note("feed override set to 100% for this run");
  r.streaming = true;
  const JobOutcome result = sender.run(
      r.commands->source(), [&](const Progress& p) { follow_status(slot, r, sender, p); });
  r.outcome = outcome_name(result);
  r.message = sender.message();
  std::string fenced;
  {
    std::lock_guard<std::mutex> lock(slot.mutex);
    fenced = slot.fenced;
  }
  switch (fenced.empty() || result == JobOutcome::kCompleted ? result : JobOutcome::kLinkLost) {
    case JobOutcome::kCompleted:
      r.state = JobState::kCompleted;
      r.executed = r.commands->size();
      break;
    case JobOutcome::kAborted: {
      r.state = stopping_ ? JobState::kInterrupted : JobState::kAborted;
      if (stopping_) {
        // The sender's abort came from stop(), not from an operator.
        r.outcome = "server stopped";
        r.message =
            fmt::format("the server stopped while the job was running, after {} of {} commands{}",
                        r.executed, r.commands->size(),
                        whole_job_position(r.progress.resume_index, r.commands->job_commands()));
      }
      // #X stopped the tool where it was, maybe in the copper: up to the travel height before
      // the machine is free (the next job may ask for the probe clip), as `send` does.
      Link* link = nullptr;
      {
        std::lock_guard<std::mutex> lock(slot.mutex);
        link = slot.connection.link;
      }
      if (link != nullptr) {
        r.message += "; " + heightmap::raise_tool_after_abort(*link, options_.sender,
                                                              heightmap::ProbeMotion{}.travel_z_mm);
      }
      break;
    }
    case JobOutcome::kAlarm:
    case JobOutcome::kRejected:
      r.state = JobState::kFailed;
      break;
    case JobOutcome::kLinkLost:
    case JobOutcome::kStalled:  // the sender's watchdog: answered, but no progress
      r.state = JobState::kInterrupted;
      // The sender counts this run's stream; continue resumes where the whole job stands.
      r.message += whole_job_position(r.progress.resume_index, r.commands->job_commands());
      break;
  }
  if (!fenced.empty() && result != JobOutcome::kCompleted) {
    r.outcome = "stopped: lease lost";
    r.message = fenced;
  }
}

// One status of the running job: the page, the saved progress, the lease, the log.
void Workshop::follow_status(Slot& slot, JobRun& r, Sender& sender, const Progress& p) {
  // The plan step running (or next): that of the first command not done yet.
  const int step = r.commands->step_from(p.executed);
  // Nothing along the path has run (a hold from probing stands at the last touch, the map's
  // frames taken): the nearest path point to where the tool stands is not how far it got.
  const double executed_mm =
      p.executed <= r.first_step_index
          ? 0.0
          : r.path->advance(step, Point2(p.status.x_um / 1000.0, p.status.y_um / 1000.0));
  {
    std::lock_guard<std::mutex> lock(slot.mutex);
    slot.cut.executed_mm = executed_mm;
    // The sender's reports while it checks the zeroing come before its stream: no total. The
    // stream's counts stay (an outside tester saw "0 of 0" and `idle` for a moment), and an
    // idle controller then is not yet the cut's first status.
    if (p.total == 0 && p.status.state == proto::MachineState::kIdle) {
      slot.seen.last_status = p.status;
      slot.seen.have_last_status = true;
      return;
    }
    slot.cut.progress = p;
    slot.clock.set_waiting(machine_waits_for_operator(p.status.state));
    slot.clock.time_left.at_step(step, slot.clock.working_s(Clock::now()));
    slot.cut.have_status = true;
    slot.seen.last_status = p.status;
    slot.seen.have_last_status = true;
  }
  r.executed = p.executed;
  if (!r.machine_marked && p.executed > r.setup_frames) {
    // The machine has this job's numbering now: its position is this job's.
    r.machine_marked = true;
    try {
      const fs::path file = last_job_file(data_, slot.spec.name);
      fs::create_directories(file.parent_path());
      write_file(file, std::to_string(r.job.id));
    } catch (const std::exception& e) {
      r.note(fmt::format("the machine's last job not recorded: {}", e.what()));
    }
  }
  const bool state_changed = p.status.state != r.last_state;
  r.progress = progress_of(r.progress, p.total, p.executed,
                           r.commands->first_uncut_curve(p.executed), p.status, r.job_id);
  saver_.post(r.job.id, r.lease, r.progress, state_changed);
  // A lapsed lease stops the machine even when every command has been sent already.
  const std::string lapsed = lease_.why_not(r.job.lease_epoch);
  if (!lapsed.empty()) {
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      if (slot.fenced.empty()) slot.fenced = lapsed;
    }
    sender.request_abort();
  }
  if (p.status.override_percent != r.last_override) {
    r.overrides.push_back({{"elapsed_s", seconds_since(r.started)},
                           {"percent", int(p.status.override_percent)},
                           {"executed", p.executed}});
  }
  if (state_changed || p.status.override_percent != r.last_override) {
    // A hold by the link watchdog: the link was cut for 2 s; the sender resumes it once a
    // status comes through again.
    const bool link_hold = (p.status.flags & proto::kStatusLinkHold) != 0;
    r.note(fmt::format("machine {} override {}% at {}/{} x {:.3f} y {:.3f} z {:.3f}{}",
                       machine_state_name(p.status.state), int(p.status.override_percent),
                       p.executed, p.total, p.status.x_um / 1000.0, p.status.y_um / 1000.0,
                       p.status.z_um / 1000.0,
                       link_hold ? " (link watchdog: the controller heard nothing for 2 s; "
                                   "resumed now that the link answers)"
                                 : ""));
    r.last_state = p.status.state;
    r.last_override = p.status.override_percent;
  }
  // The page needs a few updates a second, not one per status reply.
  if (state_changed || Clock::now() - r.last_notify > std::chrono::milliseconds(100)) {
    r.last_notify = Clock::now();
    notify(false);
  }
}

// The job has ended on the machine: the slot is free, showing the machine as it is now.
void Workshop::release_slot(Slot& slot, const JobRun& r, Sender& sender) {
  // Asked (an abort's last status during the run still said running); unknown when the
  // link went away or does not answer. No lock held meanwhile.
  std::optional<proto::StatusReply> at_rest;
  if (r.state != JobState::kInterrupted) {
    try {
      at_rest = sender.read_status_at_rest(std::chrono::milliseconds(2000));
    } catch (const std::exception&) {
      at_rest.reset();
    }
  }
  {
    std::lock_guard<std::mutex> lock(slot.mutex);
    slot.sender = nullptr;
    slot.job_id = 0;
    slot.planning = false;
    slot.probe.stage.clear();
    slot.probe.sender = nullptr;
    slot.cut.path_json.reset();
    slot.seen.have_last_status = at_rest.has_value();
    if (at_rest) slot.seen.last_status = *at_rest;
  }
  notify(false);
  saver_.forget(r.job.id);
}

// The run's report in its archive and the job's record in the store.
void Workshop::finish_run(Slot& slot, JobRun& r, Sender& sender) {
  const JobRecord& job = r.job;
  JobProgress& progress = r.progress;
  progress.executed = static_cast<int64_t>(r.executed);
  const size_t total = r.commands ? r.commands->size() : 0;
  progress.total = static_cast<int64_t>(total);
  progress.resume_curve = r.state == JobState::kInterrupted && r.commands
                              ? r.commands->first_uncut_curve(r.executed)
                              : -1;
  if (r.before_cutting && continued_run(job) && r.state == JobState::kInterrupted) {
    // Nothing of this run's stream ran: the job continues where its earlier runs stopped
    // (the saved position is never lowered by such a run).
    progress.resume_curve = job.resume_curve >= 0 ? job.resume_curve : job.start_curve;
  }
  r.note(fmt::format("ended: {} ({}): {}", state_name(r.state), r.outcome, r.message));
  const SenderStats& st = sender.stats();
  nlohmann::json report;
  report["id"] = job.id;
  report["name"] = job.name;
  report["machine"] = slot.spec.name;
  report["server"] = options_.owner;
  report["state"] = state_name(r.state);
  report["outcome"] = r.outcome;
  report["message"] = r.message;
  report["commands"] = total;
  report["executed"] = r.executed;
  report["resume_curve"] = progress.resume_curve;
  report["resume_at"] = {{"job_command", progress.resume_index},
                         {"curve_point", progress.resume_point}};
  report["planned_s"] = job.planned_s;
  report["elapsed_s"] = seconds_since(r.started);
  report["frames_sent"] = st.frames_sent;
  report["bytes_sent"] = st.bytes_sent;
  report["retransmits"] = st.retransmits;
  report["status_queries"] = st.status_queries;
  report["error_replies"] = st.error_replies;
  report["feed_overrides"] = r.overrides;
  report["height_map"] = r.height_map;
  report["settings"] = {{"feed_mm_s", job.settings.feed_mm_s},
                        {"tol_mm", job.settings.tol_mm},
                        {"scale", job.settings.scale},
                        {"margin_mm", job.settings.margin_mm}};
  try {
    if (r.archive) {
      report["run"] = r.archive->number();
      r.archive->write_report(report);
    }
  } catch (const std::exception& e) {
    r.archive_error = e.what();
  }
  std::string message = r.message;
  if (!r.archive_error.empty()) message += fmt::format(" (archive: {})", r.archive_error);
  try {
    if (!store_.finish(job.id, r.lease, r.state, message, progress) && options_.say) {
      options_.say(
          fmt::format("job {} ended {} here, but the store no longer had it running "
                      "under this server's lease: its record was left as it is",
                      job.id, state_name(r.state)));
    }
  } catch (const StoreError&) {
    // The record stays 'running'; the next start of this server marks it interrupted.
  }
}

// One touch of a board job's probing grid. Before it, the operator's hold waits (the touch
// before has finished: the tool stands retracted above its contact) and an abort or the
// server stopping ends the probing; each status of the touch is the machine's on the page.
heightmap::ProbeTouch Workshop::probing_touch(Slot& slot, Sender& sender,
                                              const std::function<void(const std::string&)>& note) {
  auto last_notify = std::make_shared<Clock::time_point>();
  const auto show = [this, &slot, last_notify](const Progress& p) {
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      slot.seen.last_status = p.status;
      slot.seen.have_last_status = true;
    }
    if (Clock::now() - *last_notify > std::chrono::milliseconds(100)) {
      *last_notify = Clock::now();
      notify(false);
    }
  };
  // A hold that came during the travel to the point: the tool stops above it, at rest,
  // and goes down only after resume (the guide: no touch while held).
  const auto before_descent = [this, &slot, &sender, note, show] {
    bool held = false;
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      held = slot.asked.hold && !slot.asked.abort && !stopping_;
    }
    if (held) {
      Progress rest;
      rest.status = sender.read_status_at_rest(std::chrono::seconds(60));
      show(rest);
    }
    wait_between_touches(slot, note);
  };
  heightmap::ProbeTouch touch =
      heightmap::controller_touch(sender, heightmap::ProbeMotion{}, show, before_descent);
  return [this, &slot, touch, note](double x_mm, double y_mm) {
    wait_between_touches(slot, note);
    try {
      return touch(x_mm, y_mm);
    } catch (const heightmap::ProbeFailed& e) {
      // A silent or closed link ends the job interrupted, as when cutting: not the map's fault.
      if (e.link_lost()) throw LinkError(e.what());
      throw;
    }
  };
}

void Workshop::wait_between_touches(Slot& slot,
                                    const std::function<void(const std::string&)>& note) {
  bool waited = false;
  std::string where;  // the touches done, for the log
  while (true) {
    std::string held;
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      if (slot.asked.abort || stopping_) throw AbortedBeforeCutting("probing");
      if (!slot.asked.hold) break;
      if (!waited) {
        where = slot.probe.done == 0
                    ? std::string("before the first touch")
                    : fmt::format("after touch {} of {}", slot.probe.done, slot.probe.total);
        const proto::StatusReply& st = slot.seen.last_status;
        held = fmt::format("probing held by the operator {}", where);
        if (slot.seen.have_last_status) {
          held += fmt::format(": the tool at rest at x {:.3f} y {:.3f} z {:.3f}", st.x_um / 1000.0,
                              st.y_um / 1000.0, st.z_um / 1000.0);
        }
      }
    }
    if (!held.empty()) note(held);
    waited = true;
    std::unique_lock<std::mutex> lock(change_mutex_);
    change_cv_.wait_for(lock, std::chrono::milliseconds(100));
  }
  if (waited) note("probing resumed " + where);
}

std::optional<heightmap::HeightMap> Workshop::board_height_map(
    Slot& slot, const JobRecord& job, const JobPlan& plan, Sender& sender,
    const std::function<void(const std::string&)>& note) {
  if (!is_board_job(job)) return std::nullopt;
  const fs::path dir = data_.job_dir(job.key);
  const BoardSettings board = read_board_settings(dir);
  if (!board.probe_first && board.height_map_from == 0) return std::nullopt;
  heightmap::HeightMap map;
  try {
    if (board.height_map_from != 0) {
      // The top side's map, the blank flipped on its pins since.
      return map_from_source_job(store_, data_, dir, job.name, board, slot.spec.name, plan, note);
    }
    if (fs::exists(dir / kHeightMapFile) && map_probed_on(dir) == slot.spec.name) {
      // Probed in an earlier run of this job on this machine (interrupted, continued): the
      // blank has not moved, or the job would have been uploaded again. On another machine
      // the blank lies on another table: probed again below. A map belongs to the machine
      // whose table it was probed on, never another's.
      map = heightmap::read_height_map_file((dir / kHeightMapFile).string());
      note("height map probed in an earlier run of this job");
    } else {
      map = probe_board_blank(slot, job, board, plan, sender, note);
      keep_height_map(dir, map, job.name, slot.spec.name);
    }
    heightmap::refuse_job_outside_map(plan, map, kHeightMapFile);
  } catch (const AbortedBeforeCutting&) {
    throw;
  } catch (const LinkError&) {
    throw;
  } catch (const std::exception& e) {
    // No contact, the spindle on, an outlier, a map out of range: nothing was cut.
    throw std::runtime_error(
        fmt::format("height map: {}; nothing was cut", server_map_words(e.what())));
  }
  return map;
}

heightmap::HeightMap Workshop::probe_board_blank(
    Slot& slot, const JobRecord& job, const BoardSettings& board, const JobPlan& plan,
    Sender& sender, const std::function<void(const std::string&)>& note) {
  const fs::path dir = data_.job_dir(job.key);
  const nlohmann::json m = nlohmann::json::parse(read_file(dir / kBoardManifest));
  std::optional<heightmap::AreaMm> area;
  if (m.contains("probe_area_mm")) area = area_of_json(m["probe_area_mm"]);
  if (!area) area = heightmap::cutting_area(plan);
  if (!area) throw std::runtime_error("the job cuts nothing: there is nothing to probe");
  wait_for_probe_clip(slot, sender, note);
  note("probe clip confirmed: probing");
  heightmap::ProbeOptions o;
  o.blank = job.name;
  o.grid.spacing_mm = board.probe_spacing_mm;
  heightmap::ProbeRun probed;
  try {
    probed = heightmap::probe_blank(*area, o, probing_touch(slot, sender, note),
                                    [&](size_t done, size_t planned) {
                                      {
                                        std::lock_guard<std::mutex> lock(slot.mutex);
                                        slot.probe.done = done;
                                        slot.probe.total = planned;
                                      }
                                      notify(false);
                                    });
  } catch (const std::exception& e) {
    bool aborted = false;
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      slot.probe.sender = nullptr;
      aborted = slot.asked.abort || stopping_;
    }
    if (!aborted) throw;
    // The touch under way stopped where it was (#X), maybe on the copper: the tool up to
    // the travel height before the machine is free, as `engraver probe` does on Ctrl-C.
    Link* link = nullptr;
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      link = slot.connection.link;
    }
    const std::string lifted =
        link != nullptr ? heightmap::raise_tool_after_abort(*link, options_.sender,
                                                            heightmap::ProbeMotion{}.travel_z_mm)
                        : std::string("the tool was not raised: no link");
    note("probing stopped: " + lifted);
    throw AbortedBeforeCutting("probing", lifted);
  }
  bool held = false;
  size_t done = 0, planned = 0;
  {
    std::lock_guard<std::mutex> lock(slot.mutex);
    slot.probe.sender = nullptr;
    slot.probe.stage.clear();
    held = slot.asked.hold && !slot.asked.abort;
    done = slot.probe.done;
    planned = slot.probe.total;
  }
  if (held) {
    // Held during the last touch: it finished; the cut waits held before its first command.
    const proto::StatusReply st = sender.read_status_at_rest(std::chrono::seconds(60));
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      slot.seen.last_status = st;
      slot.seen.have_last_status = true;
    }
    note(
        fmt::format("probing held by the operator after touch {} of {} (the last): the tool at "
                    "rest at x {:.3f} y {:.3f} z {:.3f}; the cut waits held before its first "
                    "command",
                    done, planned, st.x_um / 1000.0, st.y_um / 1000.0, st.z_um / 1000.0));
  }
  for (const std::string& r : probed.reprobed) note("probed again: " + r);
  const heightmap::HeightMap& map = probed.map;
  note(fmt::format("probed {} x {} points ({} touches), heights {:.1f} .. {:.1f} um", map.rows,
                   map.cols, probed.touches, map.min_um(), map.max_um()));
  return map;
}

void Workshop::wait_for_probe_clip(Slot& slot, Sender& sender,
                                   const std::function<void(const std::string&)>& note) {
  {
    std::lock_guard<std::mutex> lock(slot.mutex);
    slot.probe.stage = "probe_clip";
  }
  notify(false);
  note("waiting for the probe clip on the blank (action probe_ready)");
  // The operator's confirm, an abort, or the server stopping.
  while (true) {
    {
      std::lock_guard<std::mutex> lock(slot.mutex);
      if (slot.asked.abort || stopping_) {
        throw AbortedBeforeCutting("waiting for the probe clip");
      }
      if (slot.probe.confirmed) {
        slot.probe.stage = "probing";
        slot.probe.sender = &sender;
        break;
      }
    }
    std::unique_lock<std::mutex> lock(change_mutex_);
    change_cv_.wait_for(lock, std::chrono::milliseconds(100));
  }
  notify(false);
}

}  // namespace host::server
