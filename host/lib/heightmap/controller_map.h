// The height map and the probe through the controller's messages (docs/protocol.md): the
// map as #A/#E frames sent before a job, and one probe touch as #Z/#F/#Y then #T.
#ifndef HOST_LIB_HEIGHTMAP_CONTROLLER_MAP_H
#define HOST_LIB_HEIGHTMAP_CONTROLLER_MAP_H

#include <functional>  // std::function
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/probe_session.h"  // ProbeTouch
#include "host/lib/stream/job_encoder.h"       // QueuedCommand
#include "host/lib/stream/sender.h"

namespace host::heightmap {

// The map as the controller takes it: one #A header, then the heights (um, rounded) row by
// row, 8 to a #E frame. The map must be valid (validate()).
std::vector<QueuedCommand> height_map_commands(const HeightMap& map);
// The #A that clears the controller's map (compensation off).
QueuedCommand clear_height_map_command();
// What goes just before a job's first frame: the job's map (height_map_commands), or the
// clear when it has none (0), so that no map loaded earlier in the session compensates it.
std::vector<QueuedCommand> job_map_commands(const HeightMap* map);

// How the tool probes (machine Z, mm; Z 0 is the copper at the zero corner).
struct ProbeMotion {
  double travel_z_mm = 2.0;  // height of the first travel (from wherever the tool stands)
  double start_z_mm = 1.0;   // the probe starts down from here at each point
  double limit_z_mm = -1.0;  // no contact by here: refused (the controller's alarm)
  double feed_mm_s = 1.0;    // down, a micrometre a millisecond: the contact within 1 um
  double retract_mm = 0.5;   // above the contact after it
};

// A probe touch through the sender: travel to (x, y) at start_z, #Y, then the result from
// #T. Throws ProbeFailed with the controller's word (no contact, spindle on, probe closed).
// on_progress sees each status of the touch (the workshop shows the live position), the
// last one with the tool at rest after its retract.
class ProbeFailed : public std::runtime_error {
 public:
  explicit ProbeFailed(const std::string& what, bool link_lost = false)
      : std::runtime_error(what), link_lost_(link_lost) {}
  // The link went silent or closed: nothing is known about the blank.
  bool link_lost() const { return link_lost_; }

 private:
  bool link_lost_;
};
// before_descent, if given, runs between the travel to (x, y) and the descent: the travel
// is then sent and finished on its own, and the descent only after before_descent returns.
ProbeTouch controller_touch(Sender& sender, const ProbeMotion& motion,
                            std::function<void(const Progress&)> on_progress = nullptr,
                            std::function<void()> before_descent = nullptr);
// After an abort stopped a touch where it was (#X: mid-descent, or on the copper): a new
// session on the link ends the abort and the tool goes up to `z_mm` (nothing else moves; no
// zeroing). Returns what happened, for the operator; never throws.
std::string raise_tool_after_abort(Link& link, SenderOptions options, double z_mm);

}  // namespace host::heightmap

#endif  // HOST_LIB_HEIGHTMAP_CONTROLLER_MAP_H
