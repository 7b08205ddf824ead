// Jobs waiting for another job's height map (map_source.h).
#include "host/lib/server/map_source.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::find

#include "host/lib/server/board_height_map.h"  // kHeightMapFile, kHeightMapMachineFile
#include "host/lib/server/board_planning.h"    // is_board_job, read_board_settings

namespace host::server {

namespace fs = std::filesystem;

namespace {

// Queued jobs a machine looks at each time it looks for work (a workshop's queue is short).
constexpr size_t kQueuedLooked = 500;

// `job` cuts the other side of `from`'s blank: both sides known and different.
bool is_flipped_from(const DataFolder& data, const JobRecord& job, const JobRecord& from) {
  try {
    const std::string side = read_board_settings(data.job_dir(job.key)).side;
    const std::string from_side = read_board_settings(data.job_dir(from.key)).side;
    return !side.empty() && !from_side.empty() && side != from_side;
  } catch (const std::exception&) {
    return false;  // not in this archive (another server's upload): its run says
  }
}

// A flipped job's source that ended without its side completed (its map may be there).
std::string flipped_source_ended_text(const JobRecord& from) {
  return fmt::format(
      "job {} ended {} before its side was completed{}: the blank is not to be turned over "
      "(continue or requeue job {}, then requeue this job)",
      from.id, state_name(from.state), from.message.empty() ? "" : " (" + from.message + ")",
      from.id);
}

}  // namespace

std::string map_source_refusal(JobStore& store, const DataFolder& data, int64_t from) {
  const std::optional<JobRecord> job = store.get(from);
  if (!job || !is_board_job(*job)) {
    return fmt::format("height_map_from: no board job {} (the job whose height map to use)", from);
  }
  BoardSettings board;
  try {
    board = read_board_settings(data.job_dir(job->key));
  } catch (const std::exception&) {
    return "";  // not in this archive (another server's upload): its run says what is wrong
  }
  if (board.height_map_from != 0) {
    return fmt::format(
        "height_map_from: job {} probed no map, it cuts with the map of job {}: give "
        "height_map_from={} (a map is taken from the job that probed it)",
        from, board.height_map_from, board.height_map_from);
  }
  if (!board.probe_first) {
    return fmt::format(
        "height_map_from: job {} makes no height map (it was uploaded without probe_first=1)",
        from);
  }
  // Ended without its map (failed, aborted or cancelled before it probed): it will make none,
  // and the job would only fail in the queue. A job still to probe is taken: it waits.
  std::error_code ec;
  const std::string ended = source_ended_text(*job);
  if (!ended.empty() && !fs::exists(data.job_dir(job->key) / kHeightMapFile, ec)) {
    return fmt::format(
        "height_map_from: {}: it will make none (probe this job: upload it with "
        "probe_first=1)",
        ended);
  }
  return "";
}

MapSource map_source_of(JobStore& store, const DataFolder& data, const JobRecord& job) {
  MapSource s;
  if (!is_board_job(job)) return s;
  BoardSettings board;
  try {
    board = read_board_settings(data.job_dir(job.key));
  } catch (const std::exception&) {
    return s;  // not in this archive (another server's upload): its run says what is wrong
  }
  s.from = board.height_map_from;
  if (s.from == 0 && board.probe_first) {
    // A probe-first job probed in an earlier run (interrupted, continued): its blank is
    // clamped on the machine that probed it, which takes it again.
    const fs::path own = data.job_dir(job.key);
    std::error_code ec;
    if (fs::exists(own / kHeightMapFile, ec) && fs::exists(own / kHeightMapMachineFile, ec)) {
      s.from = job.id;
      s.own = true;
      s.has_map = true;
      s.machine = read_file(own / kHeightMapMachineFile);
    }
    return s;
  }
  if (s.from == 0) return s;
  const std::optional<JobRecord> from = store.get(s.from);
  if (!from) return s;
  const fs::path dir = data.job_dir(from->key);
  std::error_code ec;
  s.has_map = fs::exists(dir / kHeightMapFile, ec);
  if (s.has_map && fs::exists(dir / kHeightMapMachineFile, ec))
    s.machine = read_file(dir / kHeightMapMachineFile);
  s.source_completed = from->state == JobState::kCompleted;
  s.flipped = is_flipped_from(data, job, *from);
  s.source_ended = !s.has_map && is_final(from->state);
  if (s.source_ended) {
    s.ended_why = source_ended_text(*from);
  } else if (s.flipped && is_final(from->state) && !s.source_completed) {
    s.ended_why = flipped_source_ended_text(*from);
  }
  return s;
}

int64_t height_map_job_of(const DataFolder& data, const JobRecord& job) {
  if (!is_board_job(job)) return 0;
  try {
    const BoardSettings board = read_board_settings(data.job_dir(job.key));
    return board.probe_first ? job.id : board.height_map_from;
  } catch (const std::exception&) {
    return 0;  // not in this archive (another server's upload)
  }
}

namespace {

// Queued, its source's map not made yet but still to come.
bool waits_for_map(const JobRecord& job, const MapSource& source) {
  return job.state == JobState::kQueued && source.from != 0 && !source.has_map &&
         !source.source_ended;
}

// Queued, flipped, the map there but the source's side not cut yet (still to come: queued,
// running or interrupted).
bool waits_for_source(const JobRecord& job, const MapSource& source) {
  return job.state == JobState::kQueued && source.flipped && source.has_map &&
         !source.source_completed && source.ended_why.empty();
}

}  // namespace

std::string map_wait_text(const JobRecord& job, const MapSource& source,
                          const MachineAvailabilityOf& availability) {
  if (waits_for_map(job, source))
    return fmt::format("waiting for the height map of job {}", source.from);
  if (waits_for_source(job, source))
    return fmt::format(
        "waiting for job {} to be completed (the blank is turned over after its side is cut)",
        source.from);
  if (job.state != JobState::kQueued || !source.has_map || source.machine.empty()) return "";
  // Only that machine takes it (jobs_not_for_machine), however many others are idle.
  const std::string probed =
      source.own ? std::string(
                       "which probed this job's blank in an earlier run (the blank is "
                       "clamped there)")
                 : fmt::format("which probed the height map of job {}", source.from);
  switch (availability(source.machine)) {
    case MachineAvailability::kFree:
      return fmt::format("about to go to machine '{}' (free), {}", source.machine, probed);
    case MachineAvailability::kBusy:
      return fmt::format("waiting for machine '{}' (busy), {}", source.machine, probed);
    case MachineAvailability::kOffline:
      return fmt::format("waiting for machine '{}' (offline), {}", source.machine, probed);
    case MachineAvailability::kNotHere:
      break;
  }
  if (!source.own) return "";
  return fmt::format(
      "machine '{}', which probed this job's blank in an earlier run, is not one of this "
      "server's machines: the next free one here takes the job and probes the blank again",
      source.machine);
}

std::string map_wait_of(JobStore& store, const DataFolder& data, const JobRecord& job,
                        const MachineAvailabilityOf& availability) {
  if (job.state != JobState::kQueued) return "";
  return map_wait_text(job, map_source_of(store, data, job), availability);
}

int fail_jobs_without_map_source(JobStore& store, const DataFolder& data) {
  int failed = 0;
  for (const JobRecord& job : store.list(state_name(JobState::kQueued), kQueuedLooked)) {
    const MapSource s = map_source_of(store, data, job);
    // Completed without a map here (another server's archive may have it): its run says.
    if (s.ended_why.empty()) continue;
    if (store.fail_queued(job.id, fmt::format("height map: {}; nothing was cut", s.ended_why)))
      ++failed;
  }
  return failed;
}

std::vector<int64_t> jobs_not_for_machine(JobStore& store, const DataFolder& data,
                                          const std::string& machine,
                                          const std::vector<std::string>& machines) {
  std::vector<int64_t> out;
  for (const JobRecord& job : store.list(state_name(JobState::kQueued), kQueuedLooked)) {
    const MapSource s = map_source_of(store, data, job);
    if (s.from == 0) continue;
    const bool waiting = waits_for_map(job, s) || waits_for_source(job, s);
    const bool elsewhere = s.has_map && s.machine != machine &&
                           std::find(machines.begin(), machines.end(), s.machine) != machines.end();
    if (waiting || elsewhere || !s.ended_why.empty()) out.push_back(job.id);
  }
  return out;
}

}  // namespace host::server
