// The geometric isolation check of a planned board job, and its verdict: a job whose tool
// paths would cut copper is refused (CopperCutError), by `board`, `run`, `send` and the
// workshop server alike.
#ifndef HOST_LIB_PCB_BOARD_CHECK_H
#define HOST_LIB_PCB_BOARD_CHECK_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/lib/pcb/board_job.h"
#include "host/lib/pcb/isolation_check.h"
#include "host/lib/plan/job_plan.h"  // PlanError

namespace host::pcb {

// A job whose tool would remove copper: refused, never cut.
class CopperCutError : public PlanError {
 public:
  explicit CopperCutError(const std::string& msg) : PlanError(msg) {}
};

// The swept tool may reach into the copper by the fit tolerance and 1 um of rounding (the
// planned paths keep the clearance on top; simulated ones use it for the contour error).
double isolation_check_tolerance_mm(const BoardOptions& o);

// The check of the planned isolation paths against the job's copper (empty when the job has
// no copper).
IsolationCheck check_planned_isolation(const BoardJob& job, const BoardOptions& o);

// The same check of the points the controller will generate for the isolation curves at
// its chord tolerance (what `send` streams and the machine follows): chords sag toward the
// copper round a pad, by up to the tolerance.
IsolationCheck check_controller_isolation(const BoardJob& job, const BoardOptions& o,
                                          int chord_tolerance_um);

// Throws CopperCutError when the check found copper hits: `paths` says whose paths ("the
// planned isolation paths", "the simulated tool path"), the message the count and the first
// places.
void refuse_copper_hits(const IsolationCheck& c, const std::string& paths);

}  // namespace host::pcb

#endif  // HOST_LIB_PCB_BOARD_CHECK_H
