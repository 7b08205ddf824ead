// The machines of the workshop: one worker per machine takes the best queued job that fits
// from the store, sends it with host::Sender over its link (tcp:// or serial:), reports live
// progress, takes hold/resume/abort/override for it, and archives how it ended.
#ifndef HOST_LIB_SERVER_WORKSHOP_H
#define HOST_LIB_SERVER_WORKSHOP_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <atomic>              // std::atomic
#include <chrono>              // std::chrono
#include <condition_variable>  // std::condition_variable
#include <cstdint>             // int64_t
#include <functional>          // std::function
#include <memory>              // std::unique_ptr
#include <mutex>               // std::mutex
#include <optional>            // std::optional
#include <string>              // std::string
#include <thread>              // std::thread
#include <vector>              // std::vector

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/probe_session.h"  // ProbeTouch
#include "host/lib/plan/job_plan.h"
#include "host/lib/server/board_planning.h"  // BoardSettings
#include "host/lib/server/data_folder.h"
#include "host/lib/server/job_store.h"
#include "host/lib/server/machine_spec.h"
#include "host/lib/server/map_source.h"  // MachineAvailability
#include "host/lib/server/progress_saver.h"
#include "host/lib/server/server_lease.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/sender.h"

namespace host::server {

// Commands that restart a job at `first_curve` (pen up, travel, pen down, then the rest).
// Without one an interrupted job can only be re-queued from the start (the API answers 501).
using ResumeEncoder = std::function<std::vector<QueuedCommand>(
    const JobPlan& plan, const EncodeOptions& options, int first_curve)>;
// The default: the job as encode_job() makes it, continued from the curve's first command
// with send --resume's machinery (host::resume_from_curve: pen up, travel to where the job
// stood before that curve, #J, the rest). The workshop streams it instead of calling it
// (continue_stream(): the same commands, the job never held whole).
struct ContinueFromCurve {
  std::vector<QueuedCommand> operator()(const JobPlan& plan, const EncodeOptions& options,
                                        int first_curve) const;
};
ResumeEncoder continue_from_curve();

struct WorkshopOptions {
  std::string owner = "local";                      // this server's name in the store
  std::chrono::milliseconds poll{200};              // idle machine: look at the queue
  std::chrono::milliseconds probe{2000};            // idle machine: check its link
  std::chrono::milliseconds connect_timeout{2000};  // TCP connect
  // Servers sharing a store: this one says it is alive every `heartbeat`; a server silent
  // for `stale_after` is taken for dead and its running jobs become interrupted.
  std::chrono::milliseconds heartbeat{1000};
  std::chrono::milliseconds stale_after{30000};
  // Who holds the name `owner` (host and data folder): JobStore::acquire_lease.
  std::string holder = "local";
  // A running job's position is saved at most this often (and at each change of machine
  // state), so "continue" works after a crash (ProgressSaver).
  std::chrono::milliseconds progress_interval{1000};
  // Messages for the operator (a lost lease); the CLI prints them.
  std::function<void(const std::string&)> say;
  SenderOptions sender;
  ResumeEncoder resume_encoder = continue_from_curve();  // "continue" (see above)
};

// kConfirmProbe: the operator has put the probe clip on the blank (a probe-first board job
// waits for it before it probes).
enum class JobControl { kHold, kResume, kAbort, kOverride, kConfirmProbe };

struct ControlResult {
  int status = 200;  // 200 done, 404 no such job, 409 not possible in its state
  std::string error;
};

class Workshop {
 public:
  Workshop(JobStore& store, const DataFolder& data, std::vector<MachineSpec> machines,
           WorkshopOptions options);
  ~Workshop();
  Workshop(const Workshop&) = delete;
  Workshop& operator=(const Workshop&) = delete;

  // Takes the lease on the owner's name (throws NameInUse when another live server has it),
  // marks jobs this owner left running as interrupted, then starts one worker per machine.
  void start();
  // Aborts running jobs (they become interrupted: the server stopped), joins the workers.
  void stop();

  // Hold, resume, abort or feed override (percent 10..200) of a running job.
  ControlResult control(int64_t job_id, JobControl control, int percent);
  bool can_continue() const { return static_cast<bool>(options_.resume_encoder); }
  const std::string& owner() const { return options_.owner; }  // this server's name

  // Machines (state, position, job) and the progress of running jobs: a job claimed and
  // still being planned is "planning"; a cutting one has its position along its path.
  nlohmann::json snapshot();
  // The tool path (JobPath::to_json) of a job running on a machine of this server, null
  // when none is (the page's live preview).
  std::shared_ptr<const std::string> live_path(int64_t job_id);
  // Something changed that the page shows (a job queued, a state, progress).
  void notify(bool jobs_changed);
  // Waits until the change counter differs from `seen` (or the timeout); returns it.
  uint64_t wait_change(uint64_t seen, std::chrono::milliseconds timeout);
  std::vector<MachineFit> fits() const;
  // Whether `machine` is one of this server's, and free, busy or offline (a job's `waiting`).
  MachineAvailability availability(const std::string& machine) const;
  // Why a queued job waits under serve --no-zero: every online machine here that fits it
  // is not zeroed ("waiting for machine 'm1', not zeroed: ..."); "" otherwise.
  std::string unzeroed_wait(const JobRecord& job) const;

 private:
  struct Slot;
  void machine_loop(Slot& slot);
  void run_job(Slot& slot, const JobRecord& job, Sender& sender, const proto::SessionReply& caps);
  // run_job's steps, in order (workshop.cpp).
  struct JobRun;
  void claim_slot(Slot& slot, const JobRun& run);
  void make_commands(Slot& slot, JobRun& run, Sender& sender, const proto::SessionReply& caps);
  void hand_to_sender(Slot& slot, JobRun& run, Sender& sender);
  void stream_commands(Slot& slot, JobRun& run, Sender& sender);
  void follow_status(Slot& slot, JobRun& run, Sender& sender, const Progress& p);
  void release_slot(Slot& slot, const JobRun& run, Sender& sender);
  void finish_run(Slot& slot, JobRun& run, Sender& sender);
  void sleep_for(std::chrono::milliseconds ms);
  void heartbeat_loop();
  void lease_lost(const std::string& why);
  void save_refused(int64_t job_id);
  // A board job's height map (probed here after the operator's confirm, or another job's),
  // kept in its archive folder; nullopt for a job without one. Throws what ends the job.
  std::optional<heightmap::HeightMap> board_height_map(
      Slot& slot, const JobRecord& job, const JobPlan& plan, Sender& sender,
      const std::function<void(const std::string&)>& note);
  // A touch of the probing grid that waits while the operator holds, ends on an abort;
  // the hold and the resume go to the run's log (`note`).
  heightmap::ProbeTouch probing_touch(Slot& slot, Sender& sender,
                                      const std::function<void(const std::string&)>& note);
  void wait_between_touches(Slot& slot, const std::function<void(const std::string&)>& note);
  // Asks for the probe clip and probes the blank over the board's probe area (board.json).
  heightmap::HeightMap probe_board_blank(Slot& slot, const JobRecord& job,
                                         const BoardSettings& board, const JobPlan& plan,
                                         Sender& sender,
                                         const std::function<void(const std::string&)>& note);
  // Until the operator confirms the clip (probe_ready); AbortedBeforeCutting on an abort.
  void wait_for_probe_clip(Slot& slot, Sender& sender,
                           const std::function<void(const std::string&)>& note);
  // The machine's fit, less the queued jobs it leaves for now (map_source.h).
  MachineFit fit_now(const Slot& slot);

  JobStore& store_;
  const DataFolder& data_;
  WorkshopOptions options_;
  ServerLease lease_;
  std::vector<std::unique_ptr<Slot>> slots_;
  ProgressSaver saver_;  // after slots_: its thread is gone before they are
  std::vector<std::thread> threads_;
  std::thread heartbeat_thread_;
  std::atomic<bool> stopping_{false};

  std::mutex change_mutex_;
  std::condition_variable change_cv_;
  uint64_t version_ = 0;
  uint64_t jobs_version_ = 0;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_WORKSHOP_H
