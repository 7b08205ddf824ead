// The 1 ms tick (see motion_tick.h and docs/firmware.md).
#include "firmware/app/motion_tick.h"

#include <string.h>  // memcpy, memset

namespace app {

MotionTick::MotionTick() : motion_(0), inputs_(0), probe_input_(0), ms_(0) {
  // pos_ up to probe_ (declared in that order) start at zero (kFollow, kTickAlarmNone): one
  // memset of the block, less code than a store per member.
  uint8_t* const first = reinterpret_cast<uint8_t*>(pos_);
  memset(first, 0, (size_t)(reinterpret_cast<uint8_t*>(&probe_ + 1) - first));
}

void MotionTick::init(const AxisScaling& scaling, hal::MotionAxes* motion,
                      hal::OperatorInputs* inputs, hal::ProbeInput* probe) {
  motion_ = motion;
  inputs_ = inputs;
  probe_input_ = probe;
  path_.init(scaling);
  jog_.init(scaling);
}

void MotionTick::tick_1ms() {
  ms_ = (uint16_t)(ms_ + 1U);
  take_requests();
  int32_t pos[config::kAxisCount];
  uint8_t limits = 0;
  int16_t v[config::kAxisCount] = {0, 0, 0};
  if (!motion_->read_actual_usteps(pos) || !motion_->read_limits(&limits)) {
    memcpy(pos, pos_, sizeof pos);
    latch_alarm(kTickAlarmChip);
  }
  check_drivers();
  // Confirm presses for #P count in follow mode only (while zeroing, confirm sets the zero).
  const uint8_t buttons = inputs_->state();
  const bool confirm_pressed =
      (buttons & hal::kButtonConfirm) != 0 && (buttons_ & hal::kButtonConfirm) == 0;
  buttons_ = buttons;
  if (mode_ == (uint8_t)TickMode::kFollow) {
    if (confirm_pressed) confirm_presses_ = (uint8_t)(confirm_presses_ + 1U);
    const bool moving = !path_.finished() || !path_.at_rest() || !ring_.empty();
    if (limits != 0 && moving) {
      // A limit switch mid-job: zero velocities in this very tick, latch the alarm.
      latch_alarm(kTickAlarmLimit);
    } else {
      if (!probe(pos)) path_.tick(pos, &ring_, v);  // a touch: velocities stay 0
      if (stop_pending_ && path_.at_rest()) {
        path_.flush(&ring_);
        path_.set_hold(false);
        stop_pending_ = false;
        ++stops_done_;
      }
    }
  } else if (mode_ == (uint8_t)TickMode::kJog) {
    probe(pos);  // keeps the debounce current (no descent while jogging)
    const JogResult r = jog_.tick(buttons, limits, pos, v);
    if (r != JogResult::kRunning) {
      if (r == JogResult::kConfirmed) {
        motion_->set_actual_usteps(jog_.zero_usteps());
        memcpy(pos, jog_.zero_usteps(), sizeof pos);
      }
      jog_confirmed_ = r == JogResult::kConfirmed ? 1 : 0;
      ++jogs_done_;
      path_.flush(&ring_);  // the old target is meaningless in the new coordinates
      mode_ = (uint8_t)TickMode::kFollow;
    }
  }
  if (mode_ == (uint8_t)TickMode::kAlarm) {
    memset(v, 0, sizeof v);
  }
  motion_->write_velocity_units(v);
  memcpy(pos_, pos, sizeof pos_);
  publish(pos, limits);
}

// The probe input, debounced (kProbeDebounceTicks closed ticks in a row; the Z of the first is
// the contact height, so it is latched within one tick of the touch). While the path follows
// a probe descent (#Y): a contact drops the ring at once (the chip ramps Z to rest), reaching
// the descent's end without one is "no contact". True when the path was stopped.
bool MotionTick::probe(const int32_t pos[config::kAxisCount]) {
  const bool raw = probe_input_ != 0 && probe_input_->closed();
  if (!raw) {
    probe_.hits = 0;
  } else {
    if (probe_.hits == 0) probe_.first_z = pos[config::kAxisZ];
    if (probe_.hits < 255U) ++probe_.hits;
  }
  if (mode_ != (uint8_t)TickMode::kFollow || (path_.current_flags() & kPointProbe) == 0)
    return false;
  if (probe_.hits >= kProbeDebounceTicks) {
    probe_.result = 1;
    probe_.z_usteps = probe_.first_z;
  } else if (path_.finished() && path_.at_rest()) {
    probe_.result = 2;
    probe_.z_usteps = pos[config::kAxisZ];
  } else {
    return false;
  }
  probe_.done = (uint8_t)(probe_.done + 1U);
  path_.flush(&ring_);
  return true;
}

// One step of the power drivers' status check every kDriverCheckEveryMs (at most one SPI
// datagram; the blocking Tmc428::read_driver_status() can take ~70 ms and never runs here).
void MotionTick::check_drivers() {
  if (++driver_check_ms_ < kDriverCheckEveryMs) return;
  driver_check_ms_ = 0;
  const uint8_t c = motion_->poll_driver_check();
  if (c == hal::kDriverCheckFault) {
    latch_alarm(kTickAlarmDriver);
  } else if (c == hal::kDriverCheckUndervoltage) {
    latch_alarm(kTickAlarmPower);
  }
}

void MotionTick::latch_alarm(uint8_t alarm) {
  if (mode_ != (uint8_t)TickMode::kAlarm) alarm_ = alarm;
  mode_ = (uint8_t)TickMode::kAlarm;
  path_.stop_now();
}

void MotionTick::take_requests() {
  TickRequest r;
  while (requests_.pop(&r)) {
    ++requests_done_;
    switch (r.kind) {
      case RequestKind::kHold:
      case RequestKind::kLinkHold:
        path_.set_hold(true);
        break;
      case RequestKind::kResume:
        path_.set_hold(false);
        break;
      case RequestKind::kOverride:
        path_.set_override_percent(r.value);
        break;
      case RequestKind::kStop:
        if (mode_ == (uint8_t)TickMode::kJog) {
          jog_confirmed_ = 0;  // zeroing cancelled; the chip ramps the jog down
          ++jogs_done_;
          mode_ = (uint8_t)TickMode::kFollow;
        }
        if (mode_ == (uint8_t)TickMode::kAlarm) {
          path_.flush(&ring_);  // already standing: drop at once, stay in alarm
          ++stops_done_;
        } else {
          path_.set_hold(true);
          stop_pending_ = true;
        }
        break;
      case RequestKind::kStartJog:
        if (mode_ == (uint8_t)TickMode::kFollow) {
          path_.flush(&ring_);
          jog_.start(r.value, inputs_->state());
          mode_ = (uint8_t)TickMode::kJog;
        }
        break;
      case RequestKind::kClearAlarm:
        // Tick alarm or one raised by the background loop: either way start clean (the
        // chip ramps down whatever was still moving) and report it as a completed stop.
        if (mode_ == (uint8_t)TickMode::kAlarm) {
          mode_ = (uint8_t)TickMode::kFollow;
          alarm_ = kTickAlarmNone;
        }
        path_.flush(&ring_);
        path_.set_hold(false);
        stop_pending_ = false;
        ++stops_done_;
        break;
    }
  }
}

void MotionTick::publish(const int32_t pos[config::kAxisCount], uint8_t limits) {
  // Straight into the ring's next slot (no copy through this frame); full: the background
  // loop is behind, and the next status carries the counts.
  TickStatus* const slot = status_.reserve();
  if (slot == 0) return;
  TickStatus& s = *slot;
  memcpy(s.pos_usteps, pos, sizeof s.pos_usteps);
  s.ms = ms_;
  s.items_done = path_.items_done();
  s.item_points = path_.item_points();
  s.item_started = path_.item_started() ? 1 : 0;
  s.stopped_points = path_.stopped_points();
  s.stopped_started = path_.stopped_started() ? 1 : 0;
  s.speed_um_s = path_.speed_um_s();
  s.mode = mode_;
  s.alarm = alarm_;
  s.stops_done = stops_done_;
  s.jogs_done = jogs_done_;
  s.jog_confirmed = jog_confirmed_;
  s.requests_done = requests_done_;
  s.confirm_presses = confirm_presses_;
  s.z_mode = jog_.z_mode() ? 1 : 0;
  s.limits = limits;
  s.holding = path_.holding() ? 1 : 0;
  s.at_rest = path_.at_rest() ? 1 : 0;
  s.finished = path_.finished() && ring_.empty() ? 1 : 0;
  s.probes_done = probe_.done;
  s.probe_closed = probe_.hits >= kProbeDebounceTicks ? 1 : 0;
  status_.commit();
}

}  // namespace app
