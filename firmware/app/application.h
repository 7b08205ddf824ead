// The firmware application: wires the HAL (link, motion chip, display, panel) to the
// dispatcher, command queue, spline store, point generator, planner and the 1 ms path
// controller. tick_1ms() runs in the timer ISR and is the only user of board.motion;
// poll() is one pass of the background loop. They share only SPSC rings (tick_link.h and
// the coordinate ring). No heap, no floats.
#ifndef FIRMWARE_APP_APPLICATION_H
#define FIRMWARE_APP_APPLICATION_H

#include <stdint.h>  // int32_t, uint16_t

#include "firmware/app/axis_scaling.h"      // AxisScaling
#include "firmware/app/command_handlers.h"  // APP_DECLARE_COMMAND_HANDLERS
#include "firmware/app/command_queue.h"     // CommandQueue
#include "firmware/app/dispatcher.h"        // Dispatcher, CommandSink
#include "firmware/app/item_executor.h"     // ItemExecutor
#include "firmware/app/job_progress.h"      // JobProgress
#include "firmware/app/map_reception.h"     // MapReception
#include "firmware/app/motion_tick.h"       // MotionTick
#include "firmware/app/spline_store.h"      // SplineStore
#include "firmware/app/status_screen.h"     // StatusScreen
#include "firmware/app/stop_state.h"        // StopState
#include "firmware/app/tick_follower.h"     // TickFollower
#include "firmware/app/tick_link.h"         // TickStatus, RequestKind
#include "firmware/config/machine_config.h"
#include "hal/interfaces/link_clock.h"
#include "hal/interfaces/motion_axes.h"
#include "hal/interfaces/operator_inputs.h"
#include "hal/interfaces/probe_input.h"
#include "hal/interfaces/serial_port.h"
#include "hal/interfaces/spindle.h"
#include "hal/interfaces/text_display.h"

namespace app {

struct Board {
  hal::SerialPort* link;
  hal::MotionAxes* motion;
  hal::TextDisplay* display;
  hal::OperatorInputs* inputs;
  hal::Spindle* spindle;  // 0 on a machine without a switched spindle
  // What the link's time-outs count; 0 (the controller): the 1 ms tick (link_clock.h).
  hal::LinkClock* link_clock;
  hal::ProbeInput* probe;  // 0 on a machine without a probe input (#Y: alarm 11)
};

// The dispatcher's view of the application is the application itself (a private CommandSink:
// the dispatcher calls the public members below). Never deleted through a base pointer, so
// its non-virtual destructor is fine (the warning is silenced for it).
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
class Application : private CommandSink {
 public:
  Application();
  void init(const Board& board, const config::MachineConfig& cfg);
  // Timer ISR context on the target: the only caller of board.motion. Never waits.
  void tick_1ms();
  // One pass of the background loop: RX bytes -> parser -> dispatcher -> store; point
  // generation into the ring; replies; LCD.
  void poll();

  // Read-only views for tests and the simulator (background-loop side).
  proto::MachineState state() const;
  proto::Alarm alarm() const;
  bool zeroed() const { return zeroed_; }
  bool spindle_on() const { return executor_.spindle_on(); }
  // Actual position as last published by the tick, micrometres.
  void position_um(int32_t out[config::kAxisCount]) const;
  uint8_t last_executed_seq() const { return last_executed_seq_; }
  uint16_t items_stored() const { return items_stored_; }
  uint16_t items_done() const { return items_done_; }
  uint8_t queue_size() const { return queue_.size(); }
  uint16_t ms() const { return tick_.ms(); }
  const Dispatcher& dispatcher() const { return dispatcher_; }
  const StatusScreen& screen() const { return screen_; }
  const AxisScaling& scaling() const { return scaling_; }
  const PathController& path() const { return tick_.path(); }
  // The height map the planner follows (#A/#E), and the probe input as the tick debounced it.
  const core::HeightMap& height_map() const { return executor_.height_map(); }
  bool probe_closed() const { return follower_.latest().probe_closed != 0; }

  // What the dispatcher calls (as its CommandSink) from poll().
  proto::ErrorCode store(const proto::Frame& frame, uint8_t* detail);
  proto::ErrorCode realtime(const proto::Frame& frame);
  void reset_session();
  void fill_status(proto::StatusReply* reply);
  uint8_t queue_free();
  uint8_t spline_slots_free();
  void fill_session(proto::SessionReply* reply);
  void fill_probe_result(proto::ProbeResultReply* reply);

 private:
  bool request(RequestKind kind, uint8_t value);
  void take_snapshots();
  void follow_tick_events();
  void execute();
  bool standing_still() const;
  void set_origin_here();
  void finish_oldest();
  void drop_job();
  void begin_stop();
  void raise_alarm(proto::Alarm alarm);
  bool alarm_active() const;
  bool motion_allowed() const;
  bool inside_travel(uint8_t axis, int32_t um) const;
  uint16_t rapid_feed() const;

  // Command handlers (command_handlers.cpp), one per row of the message table.
  proto::ErrorCode handle(const proto::Frame& frame, uint8_t* detail);
  proto::ErrorCode enqueue_text(ItemKind kind, uint8_t seq, uint8_t row, const char* text,
                                uint8_t length);
  proto::ErrorCode enqueue_move(ItemKind kind, uint8_t seq, const int32_t* x_um,
                                const int32_t* y_um, uint16_t feed_um_s);
  proto::ErrorCode enqueue_args(ItemKind kind, uint8_t seq, const void* args, uint8_t size);
  proto::ErrorCode enqueue_inside(ItemKind kind, uint8_t seq, const void* args, uint8_t size,
                                  const int32_t* x_um, const int32_t* y_um, const int32_t* z_um);
  proto::ErrorCode motion_check(const int32_t* x_um, const int32_t* y_um,
                                const int32_t* z_um) const;
  // One per command of the message table with a handler (command_handlers.h).
  APP_DECLARE_COMMAND_HANDLERS()
  void watchdog();
  uint16_t link_ms() const;
  void update_screen();

  hal::LinkClock* link_clock_;  // 0: the tick counts the link's time-outs (Board)
  config::MachineConfig cfg_;
  AxisScaling scaling_;

  // The 1 ms tick (timer ISR on the target) and the channels it shares with the background
  // loop (SPSC only): tick_1ms() is its only caller.
  MotionTick tick_;

  // Owned by the background loop (poll() and everything it calls, the command handlers
  // included); the tick never reads these.
  Dispatcher dispatcher_;
  CommandQueue queue_;
  SplineStore store_;
  ItemExecutor executor_;  // queued items into ring points; the height map, the spindle
  MapReception map_rx_;    // #A/#E checked as they arrive
  StatusScreen screen_;
  TickFollower follower_;  // requests to the tick, its snapshots and events
  StopState stops_;        // stopping, holds, the background's alarm
  uint16_t items_stored_;
  uint16_t items_done_;
  uint8_t last_executed_seq_;
  uint8_t override_percent_;
  bool zeroed_;
  proto::ErrorCode shown_error_;

  // Job progress for the status (job_progress.h).
  JobProgress job_;
};
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif

}  // namespace app

#endif  // FIRMWARE_APP_APPLICATION_H
