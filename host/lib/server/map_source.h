// A job that cuts with another job's height map (height_map_from: the bottom side of a
// board whose top side probes) waits in the queue until that map exists, and then runs on
// the machine it was probed on (a map is that machine's table): which queued jobs a machine
// leaves alone, and what the job's record says while it waits.
#ifndef HOST_LIB_SERVER_MAP_SOURCE_H
#define HOST_LIB_SERVER_MAP_SOURCE_H

#include <cstdint>     // int64_t
#include <functional>  // std::function
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/server/data_folder.h"
#include "host/lib/server/job_record.h"
#include "host/lib/server/job_store.h"

namespace host::server {

// Why job `from` cannot be an upload's height_map_from ("" when it can): it must be a board
// job of this queue uploaded with probe_first=1 that has not ended without its map (failed,
// aborted or cancelled before it probed: named with its state). A job that itself cut with
// another job's map is refused, naming that job (a map is taken from the job that probed it, once:
// its flip would otherwise be applied twice). A job whose board.json is not in this archive
// (another server's upload) is taken: its run checks the map.
std::string map_source_refusal(JobStore& store, const DataFolder& data, int64_t from);

// Where a job's map source stands (a probe-first job probed in an earlier run: its own map).
struct MapSource {
  int64_t from = 0;  // the job whose map it takes; 0: none (or not a board job)
  // A probe-first job with the map of its own earlier run (from is its own id): only the
  // machine it was probed on takes it again.
  bool own = false;
  bool has_map = false;       // that job's map is in the archive
  std::string machine;        // the machine it was probed on ("" when no map)
  bool source_ended = false;  // no map, and the source job will not make one (it ended)
  // It ended failed, aborted or cancelled: source_ended_text (the job fails in the queue).
  std::string ended_why;
  // The job cuts the other side of the source's blank (its `side` differs): the blank is
  // turned over only once the source's side is cut, so it waits for the source to be
  // completed, not only for its map; a source that ends otherwise fails it (ended_why).
  bool flipped = false;
  bool source_completed = false;
};
MapSource map_source_of(JobStore& store, const DataFolder& data, const JobRecord& job);

// The job whose height map `job` cuts with: its own id (uploaded with probe_first=1), its
// height_map_from, 0 for none (a drawing, a board without a map, or a board whose board.json
// is not in this archive). Known from the upload on (the job's `height_map_job`).
int64_t height_map_job_of(const DataFolder& data, const JobRecord& job);

// Why a queued job with a map source waits: "waiting for the height map of job 4" while
// its source has no map and may still make one; a flipped job (MapSource::flipped) with
// the map there: "waiting for job 4 to be completed (the blank is turned over after its
// side is cut)" while job 4 is not; "waiting for machine 'left', which probed
// the height map of job 4" once it has (only that machine takes it); "" otherwise (not
// queued, no source, or it fails with the reason).
// The machine a map belongs to, as this server sees it: the `waiting` text says whether the
// job waits for it (busy, offline), is about to go to it (free), or is taken by another
// machine here, which probes the blank again (a probe-first job's own map, its machine not
// one of this server's: "" for a height_map_from job then, whose run says why it fails).
enum class MachineAvailability { kNotHere, kFree, kBusy, kOffline };
using MachineAvailabilityOf = std::function<MachineAvailability(const std::string& machine)>;
std::string map_wait_text(const JobRecord& job, const MapSource& source,
                          const MachineAvailabilityOf& availability);

// map_wait_text of a job, looking at its source only when it is queued.
std::string map_wait_of(JobStore& store, const DataFolder& data, const JobRecord& job,
                        const MachineAvailabilityOf& availability);

// Queued jobs whose map source ended without a map (failed, aborted or cancelled; a flipped
// job's: ended so at all, MapSource::flipped) fail in the queue, no machine claiming them
// (jobs_not_for_machine leaves them): their message "height map: job 4 ended failed without a
// height map (...); nothing was cut". Returns how many.
int fail_jobs_without_map_source(JobStore& store, const DataFolder& data);

// The queued jobs a machine leaves in the queue: those waiting for their map (a flipped
// one: for its source to be completed), those whose
// map was probed on another of `machines` (that one takes them), and those whose source
// ended without one (fail_jobs_without_map_source fails them).
std::vector<int64_t> jobs_not_for_machine(JobStore& store, const DataFolder& data,
                                          const std::string& machine,
                                          const std::vector<std::string>& machines);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_MAP_SOURCE_H
