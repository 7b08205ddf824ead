// Height-map frames as they arrive (#A, then #E in order): what the stored frames said about
// the map so far, so each #E is checked before it is queued (its place in the sequence, and
// the span of the heights with the job's zero). Background loop only; the map itself is
// built when the items execute (ItemExecutor).
#ifndef FIRMWARE_APP_MAP_RECEPTION_H
#define FIRMWARE_APP_MAP_RECEPTION_H

#include <stdint.h>  // int16_t, uint16_t

#include "firmware/app/command_queue.h"    // MapHeightsArgs
#include "firmware/protocol/messages.h"    // HeightMapDataCmd
#include "firmware/protocol/wire_codes.h"  // ErrorCode

namespace app {

// The lowest and highest height received, with 0 (the job's zero height).
struct MapSpan {
  int16_t lowest;
  int16_t highest;
};

class MapReception {
 public:
  MapReception() : points_(0), expected_(0) { span_.lowest = span_.highest = 0; }
  // A #A was queued: its cols x rows heights follow from index 0 (0: a clear, nothing).
  void announced(uint16_t points);
  // Checks the #E against the map announced and copies its heights into *out and the span
  // with them into *span; an error (and *detail) when it is out of sequence, or completes a
  // map spanning more than 1 mm.
  proto::ErrorCode check(const proto::HeightMapDataCmd& c, MapHeightsArgs* out, MapSpan* span,
                         uint8_t* detail) const;
  // The #E checked into m (and span) was queued: the next one follows it.
  void accepted(const MapHeightsArgs& m, const MapSpan& span) {
    expected_ = (uint16_t)(m.index + m.n);
    span_ = span;
  }
  // The job was dropped (#E frames dropped or not): a new #A first.
  void drop() { points_ = 0; }

 private:
  uint16_t points_;    // cols x rows of the last #A (0: none, or no map)
  uint16_t expected_;  // the next #E index
  MapSpan span_;       // of the heights stored so far
};

}  // namespace app

#endif  // FIRMWARE_APP_MAP_RECEPTION_H
