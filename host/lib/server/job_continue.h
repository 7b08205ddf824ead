// "continue" of an interrupted job on whatever machine claimed it: from where that machine
// stopped if it still holds the job's progress and is at or past the position saved for the
// job (nothing cut twice), else from the saved position (docs/protocol.md: a controller that
// does not hold the job; up to one save interval may be cut again), else from the first
// uncut curve through the resume hook.
#ifndef HOST_LIB_SERVER_JOB_CONTINUE_H
#define HOST_LIB_SERVER_JOB_CONTINUE_H

#include <functional>  // std::function
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/plan/job_plan.h"
#include "host/lib/server/job_record.h"
#include "host/lib/server/job_stream.h"
#include "host/lib/server/workshop.h"  // ResumeEncoder
#include "host/lib/stream/sender.h"

namespace host::server {

// Sets `stream` (the whole job's) to continue `job` on the machine behind `sender` (its
// session open): a resume's prefix and the plan's commands from the resume point on, none of
// them held whole (a custom hook's list instead when the hook is not continue_from_curve()'s).
// machine_ran_it: the last job this machine executed commands of is this job; else its
// position is never used (another job of the same file has the same wire job_id).
// `note` gets one line for the machine log saying which way. Throws PlanError when there is
// nothing to continue from, LinkError when the machine does not come to rest.
void continue_stream(const JobRecord& job, const JobPlan& plan, const EncodeOptions& enc,
                     Sender& sender, const ResumeEncoder& hook, bool machine_ran_it,
                     const std::function<void(const std::string&)>& note, JobStream* stream);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_JOB_CONTINUE_H
