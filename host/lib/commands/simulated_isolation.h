// After `run` of a board: the simulated tool path checked against the board's copper, and a
// double-sided board's registration error (how far the cuts land from where they belong).
#ifndef HOST_LIB_COMMANDS_SIMULATED_ISOLATION_H
#define HOST_LIB_COMMANDS_SIMULATED_ISOLATION_H

#include <limits>    // std::numeric_limits
#include <memory>    // std::shared_ptr
#include <optional>  // std::optional
#include <string>    // std::string
#include <vector>    // std::vector

#include "host/lib/heightmap/surface_model.h"  // AreaMm
#include "host/lib/pcb/board_alignment.h"      // RigidTransform
#include "host/lib/pcb/board_job.h"
#include "host/lib/pcb/isolation_check.h"  // IsolationCheck

namespace host::commands {

// A planned board as `run` checks its simulated path: the job, its title, the planned paths'
// check tolerance and the machine Z of its isolation cuts.
struct PlannedBoard {
  std::shared_ptr<const pcb::BoardJob> job;  // none: not a board
  std::string title;
  double check_tolerance_mm = 0;
  double isolation_z_mm = 0;
  // Asked by the caller before planning (a probe comes): where it probes, made then
  // (pcb::board_probe_area: a double-sided top side plans its bottom side for it too).
  bool with_probe_area = false;
  std::optional<heightmap::AreaMm> probe_area;
  // The isolation cuts' Z when the board has copper and isolation cuts to check.
  std::optional<double> checked_isolation_z_mm() const {
    if (job == nullptr || job->copper_machine.empty() || job->isolation_curves == 0)
      return std::nullopt;
    return isolation_z_mm;
  }
};

// The isolation check of the planned paths applied to the simulated tool centres at the
// isolation depth, and their least clearance to copper.
struct SimulatedIsolation {
  pcb::IsolationCheck check;
  double tolerance_mm = 0;      // the same as the planned paths' check
  double min_clearance_um = 0;  // tool edge to copper, least over every cut sample
  Point2 min_clearance_at_mm{0, 0};
  double planned_min_clearance_um = 0;  // the same for the planned paths (every 5 um)
  size_t paths = 0, samples = 0;
  // With a clearing tool: its own edge's least clearance (NaN without one).
  double clearing_min_clearance_um = std::numeric_limits<double>::quiet_NaN();
};
// `tolerance_mm`: the planned paths' check tolerance (isolation_check_tolerance_mm()).
SimulatedIsolation check_simulated_isolation(const pcb::BoardJob& job, double tolerance_mm,
                                             const std::vector<std::vector<Point2>>& cut_paths_mm,
                                             size_t samples);

// How far the simulated cuts (machine frame) land on the board from where they belong: each
// sample taken back through the blank's placement error onto the board as planned without
// it, against the nominal job's isolation paths (max and mean, um).
struct Registration {
  double max_um = 0, mean_um = 0;
  size_t samples = 0;
};
Registration registration_error(const std::vector<std::vector<Point2>>& cut_paths_mm,
                                const pcb::RigidTransform& blank_error,
                                const std::vector<std::vector<Point2>>& nominal_paths_mm);

// A board job's isolation paths, the clearing tool's too (the nominal job of a flip).
std::vector<std::vector<Point2>> isolation_paths_mm(const pcb::BoardJob& job);

}  // namespace host::commands

#endif  // HOST_LIB_COMMANDS_SIMULATED_ISOLATION_H
