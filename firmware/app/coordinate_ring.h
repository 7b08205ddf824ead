// The coordinate ring between the point generator (background loop, producer) and the 1 ms
// path controller (timer ISR, consumer): planned target points with their segment data.
#ifndef FIRMWARE_APP_COORDINATE_RING_H
#define FIRMWARE_APP_COORDINATE_RING_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/config/machine_config.h"  // kAxisCount
#include "firmware/core/spsc_ring.h"         // SpscRing

namespace app {

// Flags of a ring entry.
enum PointFlags {
  kPointRapid = 0x01,       // part of a rapid (#F) move
  kPointEndOfItem = 0x02,   // last point of a queued command (spline, move): progress count
  kPointCurvePoint = 0x04,  // a point of the curve walker (not a piece of a split chord)
  kPointProbe = 0x08        // a probe's descent (#Y): the tick stops it when the probe closes
};

// One target point and the straight segment that leads to it from the previous point.
// Written completely by the producer before it is published; afterwards the producer
// only raises entry_max_um_s and sets capture_um (16-bit stores, atomic on the target),
// which the consumer may read at any time: a stale value is always the safer one.
struct PlanEntry {
  int32_t target_usteps[config::kAxisCount];  // converted by the planner, not in the tick
  int16_t dir_q14[config::kAxisCount];        // unit vector of the segment, Q2.14
  uint32_t length_um;                         // segment length (saturated at 2^31)
  uint16_t feed_um_s;                         // commanded feed on this segment
  uint16_t cruise_max_um_s;                   // axis speed limits along this direction
  uint16_t accel_um_s_per_ms;                 // planned path acceleration on this segment
  uint16_t junction_max_um_s;                 // cap at the segment start (corner, feeds)
  volatile uint16_t entry_max_um_s;           // planned speed limit at the segment start
  volatile uint16_t capture_um;               // leave for the next target inside this distance
  uint16_t tag;                               // producer's item counter (progress)
  uint8_t flags;                              // PointFlags
};

// The SPSC ring of PlanEntry (core::SpscRing's contract); the planner's backward pass
// updates the entries not yet consumed through newest(k), the controller reads front().
template <uint16_t kCapacity>
class PlanRing : public core::SpscRing<PlanEntry, kCapacity> {
 public:
  // Consumer: the oldest entry without taking it, 0 when empty.
  const PlanEntry* front() const { return this->peek(0); }
};

// The ring the application uses: 32 points; at 10 mm/s even 50 um points buffer 160 ms,
// well beyond the 0.25 mm it takes to stop.
enum { kCoordinateRingCapacity = 32 };
typedef PlanRing<kCoordinateRingCapacity> CoordinateRing;

}  // namespace app

#endif  // FIRMWARE_APP_COORDINATE_RING_H
