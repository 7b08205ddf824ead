// Every default a job is planned with, written once: PlanOptions, pcb::BoardOptions (with
// IsolationOptions and CutoutOptions), the command line's options, the server's settings and
// its job record all start from here. The machine's figures come from the reference machine
// (firmware/config/machine_config.h) until a controller answers; then from its *I.
#ifndef HOST_LIB_PLAN_JOB_DEFAULTS_H
#define HOST_LIB_PLAN_JOB_DEFAULTS_H

#include <stdint.h>  // uint16_t

#include "firmware/config/machine_config.h"

namespace host::defaults {

// ---- The machine (reference machine; a connected controller's *I where it says) ----

// An axis's travel from the zero, mm (297 x 210 x 40 for the A4 reference machine).
inline double travel_mm(int axis) {
  return config::default_machine_config().axis[axis].travel_um / 1000.0;
}
// The work area a job is planned for: the whole X/Y travel (the A4 table).
inline double work_width_mm() {
  return travel_mm(config::kAxisX);
}
inline double work_height_mm() {
  return travel_mm(config::kAxisY);
}
// Cutting feed of drawings (DXF, G-code) where none is given: the machine's default feed.
inline double feed_mm_per_s() {
  return config::default_machine_config().default_feed_um_per_s / 1000.0;
}
// Rapid (pen-up X/Y) rate the run-time estimates use.
inline double rapid_mm_per_s() {
  return config::default_machine_config().rapid_feed_um_per_s / 1000.0;
}
// Feed of pen-up Z moves (#Z): the Z axis's fastest feed; a connected controller's own
// max_feed_z_um_per_s from its *I instead (host/lib/stream/job_encoder.h, use_session()).
inline uint16_t z_rapid_um_per_s() {
  const uint32_t z = config::default_machine_config().axis[config::kAxisZ].max_speed_um_per_s;
  return z > 65535UL ? 65535U : static_cast<uint16_t>(z);
}

// ---- Every job ----

inline constexpr double kZUpMm = 2.0;               // travel height above the work zero
inline constexpr double kChordToleranceMm = 0.005;  // #U chord error of the controller's points

// ---- Drawings (DXF, G-code) ----

inline constexpr double kScale = 1.0;
inline constexpr double kMarginMm = 0.0;            // the drawing's corner from the zero
inline constexpr double kChainToleranceMm = 0.01;   // ends closer: no pen lift between curves
inline constexpr double kZDownMm = -0.1;            // cutting depth
inline constexpr double kPlungeMmPerS = 2.0;        // Z feed for pen down
inline constexpr double kFitToleranceMm = 0.005;    // G-code: runs of G1 fitted as cubics
inline constexpr double kDrillFeedMaxMmPerS = 5.0;  // G-code drilling: plunge feed cap

// ---- PCB boards ----

// The chord tolerance a board is sent with (#U): the controller's points cut inside a curve
// by up to this much, toward the copper the curve goes round, so it comes out of the
// isolation clearance. At 5 um the A64-OlinuXino's top isolation touched copper in the
// simulator (-3.4 um); at 1 um its least clearance is +1.4 um (docs/performance.md).
inline constexpr double kBoardChordToleranceMm = 0.001;
inline constexpr double kBoardMarginMm = 5.0;      // the job's corner (tool extent) from zero
inline constexpr double kBoardFeedMmPerS = 5.0;    // isolation feed
inline constexpr double kBoardPlungeMmPerS = 1.0;  // isolation plunge
inline constexpr double kToolWidthMm = 0.2;        // V-bit width at the isolation depth
inline constexpr int kPasses = 1;                  // isolation contours per island
inline constexpr double kOverlap = 0.25;           // of the tool width, between passes
// Kept between the tool's edge and the copper on top of the tool radius: room for the curve
// fit (2 um) and the machine's contour error (up to 7 um on the simulated machine with the
// board's 1 um chords), so the tool that really cuts does not touch copper.
inline constexpr double kClearanceMm = 0.008;
inline constexpr double kIsolationDepthMm = 0.05;      // below the copper surface
inline constexpr double kBoardFitToleranceMm = 0.002;  // isolation polylines -> lines/arcs/cubics
inline constexpr double kDrillStartMm = 0.5;           // above the board, where a plunge starts
inline constexpr double kDrillDepthMm = 1.8;           // board thickness + breakthrough
inline constexpr double kDrillFeedMmPerS = 1.0;
inline constexpr double kCutterMm = 1.0;  // cut-out cutter diameter
inline constexpr double kCutDepthMm = 1.8;
inline constexpr double kCutStepMm = 0.6;  // depth per cut-out pass
inline constexpr double kCutFeedMmPerS = 3.0;
inline constexpr double kTabWidthMm = 2.0;   // material left standing at a tab
inline constexpr int kTabs = 4;              // per outer loop
inline constexpr double kTabHeightMm = 0.5;  // board thickness a tab keeps
inline constexpr uint32_t kSpindleSpinupMs = 2000;

// ---- The ranges the board options take: `board`/`run`/`send` (CLI::Range) and the server's
// upload fields (check_board_settings) refuse the same values ----

struct Range {
  double min, max;
  const char* unit = "";  // as the refusals and --help give it: "mm", "mm/s"; "" for none
  // Written so that NaN is outside.
  bool holds(double v) const { return v >= min && v <= max; }
};
inline constexpr Range kToolWidthRangeMm{0.01, 5.0, "mm"};
inline constexpr Range kPassesRange{1, 50};  // isolation passes, and narrow passes
inline constexpr Range kClearingToolRangeMm{0.0, 10.0, "mm"};  // 0: no clearing tool
inline constexpr Range kAlignDiameterRangeMm{0.1, 10.0, "mm"};
inline constexpr Range kAlignDepthRangeMm{0.1, 20.0, "mm"};
// The rest of the board options (host/cli/option_ranges.cpp holds the table by name).
inline constexpr Range kOverlapRange{0.0, 0.9};  // a fraction of the tool width
inline constexpr Range kClearanceRangeMm{0.0, 0.1, "mm"};
inline constexpr Range kIsolationDepthRangeMm{0.001, 5.0, "mm"};
inline constexpr Range kDrillDepthRangeMm{0.01, 20.0, "mm"};
inline constexpr Range kHeightAboveBoardRangeMm{0.1, 50.0, "mm"};  // travel and drill start
inline constexpr Range kFeedRangeMmPerS{0.1, 60.0, "mm/s"};        // every feed and plunge feed
inline constexpr Range kCutterRangeMm{0.1, 10.0, "mm"};
inline constexpr Range kCutDepthRangeMm{0.01, 20.0, "mm"};  // the cut-out's depth and its step
inline constexpr Range kTabWidthRangeMm{0.0, 100.0, "mm"};  // 0: no tabs
inline constexpr Range kTabsRange{0, 100};                  // 0: no tabs
inline constexpr Range kTabSpacingRangeMm{0.0, 10000.0, "mm"};
inline constexpr Range kTabHeightRangeMm{0.0, 20.0, "mm"};
inline constexpr Range kMarginRangeMm{0.0, 100.0, "mm"};
inline constexpr Range kWorkAreaRangeMm{1.0, 10000.0, "mm"};      // each side
inline constexpr Range kMachinePositionRangeMm{-1e4, 1e4, "mm"};  // a measured position
// The other number options of the command line (host/cli/option_ranges.cpp).
inline constexpr Range kChordToleranceRangeMm{0.001, 1.0, "mm"};  // --tol: every command's
inline constexpr Range kScaleRange{0.001, 1000.0};
inline constexpr Range kChainToleranceRangeMm{0.0, 1.0, "mm"};
inline constexpr Range kToolRadiusRangeMm{0.0, 10.0, "mm"};
inline constexpr Range kZDownRangeMm{
    -20.0, 0.0, "mm"};  // a drawing's cutting depth: at or below zero  // --tool-side's offset
inline constexpr Range kFitToleranceRangeMm{0.0, 0.1, "mm"};
inline constexpr Range kPollIntervalRangeMs{0, 1000, "ms"};  // send's status poll; 0: always one
inline constexpr Range kProbeSpacingRangeMm{1.0, 65.0, "mm"};
inline constexpr Range kProbeGridRange{2, 16};  // rows and columns each
inline constexpr Range kProbeMarginRangeMm{0.0, 50.0, "mm"};
inline constexpr Range kOutlierLimitRangeUm{1.0, 1000.0, "um"};
inline constexpr Range kVbitAngleRangeDeg{5.0, 150.0, "degrees"};
inline constexpr Range kCopperRangeUm{1.0, 500.0, "um"};
// --offset X Y (machine = drawing + offset): within the machine's longest travel either way.
inline Range offset_range_mm() {
  const double t = travel_mm(config::kAxisX) > travel_mm(config::kAxisY)
                       ? travel_mm(config::kAxisX)
                       : travel_mm(config::kAxisY);
  return Range{-t, t, "mm"};
}
inline constexpr double kAlignDiameterMm = 3.0;  // alignment hole (pin) diameter
inline constexpr double kAlignDepthMm = 3.0;     // through the blank into the spoil board

}  // namespace host::defaults

#endif  // HOST_LIB_PLAN_JOB_DEFAULTS_H
