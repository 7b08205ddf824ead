// The clock the host link's time-outs count (the 200 ms inter-byte frame time-out, the 2 s
// link watchdog): milliseconds, wrapping at 65536.
//
// The controller has none (Board::link_clock = 0): its 1 ms tick is wall-clock time, so the
// application counts its ticks. The simulator serving another program runs machine time
// faster than the wall clock between the bytes; it gives the link's wall clock here, so the
// time-outs see what the real controller would see on the same link.
#ifndef HAL_INTERFACES_LINK_CLOCK_H
#define HAL_INTERFACES_LINK_CLOCK_H

#include <stdint.h>  // uint16_t

namespace hal {

class LinkClock {
 public:
  // Milliseconds now; only differences are used. Called from the background loop only.
  virtual uint16_t link_ms() = 0;

 protected:
  ~LinkClock() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_LINK_CLOCK_H
