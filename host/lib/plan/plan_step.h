// One machine action of a job plan (pen up/down, rapid, feed, spline, pause, dwell,
// spindle, drill), in the machine frame: micrometres from the zero corner.
#ifndef HOST_LIB_PLAN_PLAN_STEP_H
#define HOST_LIB_PLAN_PLAN_STEP_H

#include <stdint.h>  // int32_t, uint32_t, uint8_t

#include <string>   // std::string
#include <utility>  // std::swap

#include "firmware/core/spline.h"  // core::PointUm
#include "host/lib/plan/step_spline.h"

namespace host {

// One machine action. Which fields mean something depends on kind.
struct PlanStep {
  // One byte: a million-line job holds four million steps.
  enum Kind : uint8_t {
    kPenUp,    // Z to z_um (travel height), at the rapid rate
    kPenDown,  // Z to z_um (cutting depth), at feed_um_per_s (plunge feed)
    kRapid,    // X/Y straight to `to` with the pen up, at the rapid rate
    kFeed,     // X/Y straight to `to` with the pen down, at feed_um_per_s
    kSpline,   // trace `spline` from its start (== current position) at feed_um_per_s
    // Machine actions that CAM programs and PCB jobs need (G-code M0/M6/G4/M3/G81, drilling):
    kPause,    // stop until the operator confirms on the panel; `text` shown on the LCD
    kDwell,    // wait dwell_ms with every axis still
    kSpindle,  // spindle on (spindle_on) or off
    kDrill     // one hole at `to`: travel height, Z to z_start_um, plunge to z_um at
               // feed_um_per_s, back to z_start_um
  };
  Kind kind = kRapid;
  bool spindle_on = false;     // kSpindle
  core::PointUm to = {0, 0};   // kRapid, kFeed: target; kSpline: the spline's end point
  int32_t z_um = 0;            // kPenUp, kPenDown
  int32_t feed_um_per_s = 0;   // kPenDown, kFeed, kSpline
  int32_t tool_offset_um = 0;  // kSpline, kFeed: signed offset, > 0 left of travel, < 0 right
  // Only one kind reads each of these, so they share their bytes (32 bytes of fields).
  union {
    uint32_t dwell_ms = 0;  // kDwell
    int32_t z_start_um;     // kDrill: height above the board where the plunge starts
  };
  int curve = -1;  // index into JobPlan::curves of the curve this step draws

  // kSpline: the curve (validated, in machine micrometres); empty for every other kind.
  const StepSpline& spline() const;
  void set_spline(StepSpline spline);
  // kPause: the operator's message (LCD, at most 16 characters used); empty otherwise.
  const std::string& text() const;
  void set_text(std::string text);

  // Same kind and fields, the target and curve aside (and the same spline and text).
  bool same_shape(const PlanStep& o) const;

 private:
  // Only spline and pause steps have these, so the others (a million feeds in a large job)
  // stay small. Never changed once made: copies of a step share them.
  struct Extra;
  // A counted pointer one word wide (a std::shared_ptr is two: 8 more bytes in each of the
  // four million steps of a million-line job). Counts atomically: the server copies plans
  // across threads.
  class ExtraRef {
   public:
    ExtraRef() = default;
    explicit ExtraRef(Extra* owned) : p_(owned) {}
    ExtraRef(const ExtraRef& other);
    ExtraRef(ExtraRef&& other) noexcept : p_(other.p_) { other.p_ = nullptr; }
    ExtraRef& operator=(ExtraRef other) noexcept {
      std::swap(p_, other.p_);
      return *this;
    }
    ~ExtraRef();
    const Extra* get() const { return p_; }

   private:
    Extra* p_ = nullptr;
  };
  ExtraRef extra_;
};

}  // namespace host

#endif  // HOST_LIB_PLAN_PLAN_STEP_H
