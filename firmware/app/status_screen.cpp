// LCD status lines (see status_screen.h).
#include "firmware/app/status_screen.h"

#include <string.h>  // memcpy, memcmp, strlen

namespace app {

namespace {

// Appends s to out at *n, within kCols.
void put(char* out, uint8_t* n, const char* s) {
  while (*s && *n < StatusScreen::kCols) out[(*n)++] = *s++;
}

// By proto::MachineState (kIdle shows READY once zeroed).
const char* const kStateNames[] = {"IDLE", "RUN", "HOLDING", "HOLD", "ZEROING", "ALARM", "PAUSED"};

const char* state_name(proto::MachineState s, bool zeroed) {
  if (s == proto::MachineState::kIdle && zeroed) return "READY";
  const uint8_t i = (uint8_t)s;
  return i < sizeof kStateNames / sizeof kStateNames[0] ? kStateNames[i] : "?";
}

// By proto::Alarm, from kLimitSwitch (1) to kLastAlarm.
const char* const kAlarmNames[proto::kLastAlarm] = {
    "LIMIT SWITCH", "DRIVER FAULT",   "POWER LOST",    "FOLLOWING ERR",
    "MOTION CHIP",  "PATH FAULT",     "SOFT LIMIT",    "PROBE NO TOUCH",
    "PROBE CLOSED", "PROBE: SPINDLE", "NO PROBE INPUT"};

const char* alarm_name(proto::Alarm a) {
  const uint8_t i = (uint8_t)a;
  return i >= 1 && i <= proto::kLastAlarm ? kAlarmNames[i - 1] : "ALARM";
}

}  // namespace

uint8_t format_uint(uint32_t v, char* out) {
  char tmp[10];
  uint8_t n = 0;
  do {
    tmp[n++] = (char)('0' + v % 10U);
    v /= 10U;
  } while (v != 0 && n < sizeof tmp);
  for (uint8_t i = 0; i < n; ++i) out[i] = tmp[n - 1 - i];
  return n;
}

uint8_t format_mm(int32_t um, char* out) {
  uint8_t n = 0;
  uint32_t mag = (uint32_t)um;
  if (um < 0) {
    out[n++] = '-';
    mag = (uint32_t)0 - (uint32_t)um;
  }
  const uint32_t hundredths = (mag + 5U) / 10U;
  n = (uint8_t)(n + format_uint(hundredths / 100U, out + n));
  out[n++] = '.';
  out[n++] = (char)('0' + (hundredths / 10U) % 10U);
  out[n++] = (char)('0' + hundredths % 10U);
  return n;
}

StatusScreen::StatusScreen()
    : display_(0), last_draw_ms_(0), error_ms_(0), error_on_(false), drawn_once_(false) {
  for (uint8_t r = 0; r < 2; ++r) {
    text_ms_[r] = 0;
    text_on_[r] = false;
    text_[r][0] = 0;
    shown_[r][0] = 0;
  }
  error_[0] = 0;
  pause_[0] = 0;
}

void StatusScreen::init(hal::TextDisplay* display) {
  display_ = display;
  drawn_once_ = false;
}

void StatusScreen::show_text(uint8_t row, const char* text, uint8_t length, uint16_t now_ms) {
  if (row > 1) return;
  if (length > kCols) length = kCols;
  memcpy(text_[row], text, length);
  text_[row][length] = 0;
  text_on_[row] = true;
  text_ms_[row] = now_ms;
}

void StatusScreen::show_pause(const char* text, uint8_t length) {
  if (length > kCols) length = kCols;
  memcpy(pause_, text, length);
  pause_[length] = 0;
}

void StatusScreen::show_error(proto::ErrorCode code, uint8_t seq, uint16_t now_ms) {
  uint8_t n = 0;
  put(error_, &n, "ERR ");
  n = (uint8_t)(n + format_uint((uint8_t)code, error_ + n));
  put(error_, &n, " #");
  n = (uint8_t)(n + format_uint(seq, error_ + n));
  error_[n] = 0;
  error_on_ = true;
  error_ms_ = now_ms;
}

void StatusScreen::compose(const ScreenInfo& info, uint16_t now_ms, char out[2][kCols + 1]) {
  for (uint8_t r = 0; r < 2; ++r) {
    if (text_on_[r] && (uint16_t)(now_ms - text_ms_[r]) >= (uint16_t)kMessageMs)
      text_on_[r] = false;
  }
  if (error_on_ && (uint16_t)(now_ms - error_ms_) >= (uint16_t)kMessageMs) error_on_ = false;
  uint8_t n = 0;
  if (info.paused) {
    put(out[0], &n, pause_[0] != 0 ? pause_ : "PAUSED");
  } else if (text_on_[0]) {
    put(out[0], &n, text_[0]);
  } else {
    put(out[0], &n, state_name(info.state, info.zeroed));
    if (info.state == proto::MachineState::kZeroing) {
      put(out[0], &n, info.z_mode ? " Z" : " XY");
    } else if (info.items_stored != 0) {
      put(out[0], &n, " ");
      n = (uint8_t)(n + format_uint(info.items_done, out[0] + n));
      put(out[0], &n, "/");
      n = (uint8_t)(n + format_uint(info.items_stored, out[0] + n));
    }
  }
  out[0][n > (uint8_t)kCols ? (uint8_t)kCols : n] = 0;
  n = 0;
  if (info.state == proto::MachineState::kAlarm) {
    put(out[1], &n, alarm_name(info.alarm));
  } else if (error_on_) {
    put(out[1], &n, error_);
  } else if (info.paused) {
    put(out[1], &n, "CONFIRM TO GO ON");
  } else if (text_on_[1]) {
    put(out[1], &n, text_[1]);
  } else if (info.probing || info.probe_closed) {
    // "PROBE Z-0.14" while a #Y runs; "PROBE TOUCH Z.." whenever the input reads closed
    // (the operator sees the clip work before probing, or that it is shorted).
    char num[12];
    put(out[1], &n, info.probe_closed ? "PROBE TOUCH Z" : "PROBE Z");
    const uint8_t k = format_mm(info.pos_um[2], num);
    num[k] = 0;
    put(out[1], &n, num);
  } else {
    // "X12.34 Y-5.60" (Z while zeroing Z).
    char num[12];
    const bool z = info.state == proto::MachineState::kZeroing && info.z_mode;
    put(out[1], &n, z ? "Z" : "X");
    uint8_t k = format_mm(z ? info.pos_um[2] : info.pos_um[0], num);
    num[k] = 0;
    put(out[1], &n, num);
    if (!z) {
      put(out[1], &n, " Y");
      k = format_mm(info.pos_um[1], num);
      num[k] = 0;
      put(out[1], &n, num);
    }
  }
  out[1][n > (uint8_t)kCols ? (uint8_t)kCols : n] = 0;
}

void StatusScreen::update(const ScreenInfo& info, uint16_t now_ms) {
  if (display_ == 0) return;
  if (drawn_once_ && (uint16_t)(now_ms - last_draw_ms_) < (uint16_t)kRefreshMs) return;
  last_draw_ms_ = now_ms;
  char next[2][kCols + 1];
  compose(info, now_ms, next);
  for (uint8_t r = 0; r < 2; ++r) {
    if (drawn_once_ && strcmp(next[r], shown_[r]) == 0) continue;
    memcpy(shown_[r], next[r], kCols + 1);
    display_->write_line(r, shown_[r]);
  }
  drawn_once_ = true;
}

}  // namespace app
