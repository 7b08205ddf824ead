// The 1 ms tick (the timer ISR on the target): follows the coordinate ring with the path
// controller, runs the zeroing jog, debounces the probe and latches the tick's alarms (limit
// switch, driver, supply, chip). The only user of the motion chip and the panel; it shares
// with the background loop only the SPSC channels it holds here (the coordinate ring,
// requests in, status snapshots out) and the probe result handed over through ProbeWatch.
#ifndef FIRMWARE_APP_MOTION_TICK_H
#define FIRMWARE_APP_MOTION_TICK_H

#include <stdint.h>  // int32_t, uint8_t, uint16_t

#include "firmware/app/axis_scaling.h"       // AxisScaling
#include "firmware/app/coordinate_ring.h"    // CoordinateRing
#include "firmware/app/jog_controller.h"     // JogController
#include "firmware/app/path_controller.h"    // PathController
#include "firmware/app/tick_link.h"          // RequestRing, StatusRing
#include "firmware/config/machine_config.h"  // kAxisCount
#include "hal/interfaces/motion_axes.h"
#include "hal/interfaces/operator_inputs.h"
#include "hal/interfaces/probe_input.h"

namespace app {

// The probe input as the tick sees it, and the end of each descent (#Y).
struct ProbeWatch {
  uint8_t hits;     // ticks the probe input has read closed in a row (saturates)
  int32_t first_z;  // Z (usteps) at the first of them
  uint8_t done;     // probe descents ended
  // The last descent's result (1 contact, 2 no contact) and Z (the first closed tick's, or
  // where it ended): written before the snapshot that carries the new `done`, read by the
  // background loop only once it saw that count; the next descent, which would write them
  // again, is the background's own to hand over. (Not in every snapshot: RAM.)
  volatile uint8_t result;
  volatile int32_t z_usteps;
};

class MotionTick {
 public:
  MotionTick();
  // probe: 0 on a machine without a probe input.
  void init(const AxisScaling& scaling, hal::MotionAxes* motion, hal::OperatorInputs* inputs,
            hal::ProbeInput* probe);
  // Timer ISR context on the target. Never waits.
  void tick_1ms();

  // For the background loop.
  CoordinateRing* ring() { return &ring_; }
  bool request(const TickRequest& r) { return requests_.push(r); }
  bool take_status(TickStatus* s) { return status_.pop(s); }
  uint16_t ms() const { return ms_; }
  const PathController& path() const { return path_; }
  bool has_probe() const { return probe_input_ != 0; }
  // The last descent's result and Z (usteps), once a snapshot carried its probes_done.
  uint8_t probe_result() const { return probe_.result; }
  int32_t probe_z_usteps() const { return probe_.z_usteps; }

 private:
  bool probe(const int32_t pos[config::kAxisCount]);
  void take_requests();
  void check_drivers();
  void latch_alarm(uint8_t alarm);
  void publish(const int32_t pos[config::kAxisCount], uint8_t limits);

  hal::MotionAxes* motion_;
  hal::OperatorInputs* inputs_;
  hal::ProbeInput* probe_input_;
  // Shared with the background loop (SPSC only).
  CoordinateRing ring_;
  RequestRing requests_;
  StatusRing status_;
  volatile uint16_t ms_;  // written by the tick only

  // The tick's own: the background loop sees them through the StatusRing snapshots.
  PathController path_;
  JogController jog_;
  // pos_ to probe_: zeroed as one block by the constructor (keep new members in it).
  int32_t pos_[config::kAxisCount];
  uint8_t mode_;  // TickMode
  uint8_t alarm_;
  uint8_t driver_check_ms_;  // ms since the last poll_driver_check() step
  uint8_t stops_done_;
  uint8_t jogs_done_;
  uint8_t jog_confirmed_;
  uint8_t requests_done_;
  uint8_t buttons_;          // panel state seen by the previous tick
  uint8_t confirm_presses_;  // confirm button presses (wraps), for #P
  bool stop_pending_;
  ProbeWatch probe_;
};

}  // namespace app

#endif  // FIRMWARE_APP_MOTION_TICK_H
