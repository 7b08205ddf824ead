// What the background loop and the 1 ms tick tell each other: requests (poll -> tick) and
// status snapshots (tick -> poll), each through its own SPSC ring. Counters in the snapshot
// are cumulative, so a snapshot skipped because the ring was full loses nothing.
#ifndef FIRMWARE_APP_TICK_LINK_H
#define FIRMWARE_APP_TICK_LINK_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/config/machine_config.h"  // kAxisCount
#include "firmware/core/spsc_ring.h"         // SpscRing

namespace app {

enum class RequestKind : uint8_t {
  kHold = 1,        // decelerate along the path and stay
  kResume = 2,      // go on after a hold
  kStop = 3,        // decelerate, then drop the target and the ring (abort, session reset)
  kOverride = 4,    // value = percent
  kStartJog = 5,    // value = axes to zero (bit0 X, bit1 Y, bit2 Z)
  kClearAlarm = 6,  // leave the alarm latch (ring dropped, nothing moves by itself)
  kLinkHold = 7     // hold caused by the link watchdog (reported separately)
};

struct TickRequest {
  RequestKind kind;
  uint8_t value;
};

// Tick modes as published.
enum class TickMode : uint8_t { kFollow = 0, kJog = 1, kAlarm = 2 };

// Why the tick latched an alarm (values match proto::Alarm).
enum TickAlarm {
  kTickAlarmNone = 0,
  kTickAlarmLimit = 1,
  kTickAlarmDriver = 2,
  kTickAlarmPower = 3,
  kTickAlarmChip = 5,
  kTickAlarmPath = 6
};

// The tick advances the power drivers' status check (one short step) this often.
static const uint8_t kDriverCheckEveryMs = 10;

struct TickStatus {
  int32_t pos_usteps[config::kAxisCount];
  uint16_t ms;              // tick counter (wraps)
  uint16_t items_done;      // ring items whose last point was reached
  uint16_t item_points;     // curve points reached in the item being worked on
  uint16_t stopped_points;  // item_points when the ring was last dropped (a stop)
  uint16_t speed_um_s;      // commanded path speed
  uint8_t mode;             // TickMode
  uint8_t alarm;            // TickAlarm while mode is kAlarm
  uint8_t stops_done;       // kStop requests completed (at rest, ring dropped)
  uint8_t jogs_done;        // zeroing sessions ended
  uint8_t jog_confirmed;    // the last one set the zero (else it was cancelled)
  uint8_t requests_done;    // requests taken (all kinds)
  uint8_t confirm_presses;  // confirm button presses in follow mode (wraps)
  uint8_t limits;           // hal::LimitBits
  uint8_t holding;          // hold requested
  uint8_t at_rest;          // commanded speed zero
  uint8_t finished;         // nothing more to follow
  uint8_t z_mode;           // zeroing: the joystick drives Z
  uint8_t item_started;     // the item being worked on has a target (it began to move)
  uint8_t stopped_started;  // item_started when the ring was last dropped
  uint8_t probes_done;      // probe descents ended (contact or no contact, wraps)
  uint8_t probe_result;     // the last one's: 1 contact, 2 no contact
  uint8_t probe_closed;     // the probe input, debounced
  int32_t probe_z_usteps;   // the last one's Z: the first closed tick's, or where it ended
};

// Probe input debounce: closed this many ticks in a row counts (the first one's Z is kept).
static const uint8_t kProbeDebounceTicks = 2;

typedef core::SpscRing<TickRequest, 8> RequestRing;
typedef core::SpscRing<TickStatus, 4> StatusRing;

}  // namespace app

#endif  // FIRMWARE_APP_TICK_LINK_H
