// Planning G-code programs: file order kept, pauses/dwells/spindle/drill steps where the
// program put them, the program's depths, drilling as drill steps or Z moves; the
// work-area advice and the controller's travel. Also: the shared pcb2gcode files plan.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>

#include "host/lib/drawing/conics.h"
#include "host/lib/plan/job_plan.h"

namespace host {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + "/" + std::to_string(getpid()) + "-" + name;
  std::ofstream(path) << text;
  return path;
}

JobPlan plan_text(const std::string& text, const PlanOptions& o = PlanOptions()) {
  return plan_job(import_drawing(write_temp("prog.ngc", text)), o);
}

std::string kinds(const JobPlan& p) {
  std::string s;
  for (const PlanStep& st : p.steps) s += "UDRFSPWOX"[st.kind];
  return s;
}

// pcb2gcode's shape: tool change at a height, dwells, spindle, two cuts, a retract, M5.
const char* kMill =
    "G94\nG21\nG90\nG64 P0.01\n"
    "G00 Z20 (tool change height)\nT1\nM5\nG04 P1\n(MSG, Change tool bit to mill 0.2mm)\nM6\nM0\n"
    "M3\nG04 P0.5\nG04 P0\nG00 Z2\n"
    "G00 X10 Y10\nG01 Z-0.2 F60\nG04 P0\nG01 X30 Y10\nG01 X30 Y20\n"
    "G00 Z2\nG00 X5 Y5\nG01 Z-0.3\nG01 X5 Y25\n"
    "G00 Z20\nM5\nM2\n";

TEST(ProgramPlan, MillingStepsFollowTheProgramStepByStep) {
  const JobPlan p = plan_text(kMill);
  // The zero is the lower-left corner of everything cut: (5, 5) -> (0, 0).
  EXPECT_NEAR(p.offset_mm.x(), -5.0, 1e-9);
  const StepList& s = p.steps;
  // U up, O spindle off, W dwell 1 s, U tool-change height, P pause, O on, W 0.5 s,
  // R to the first cut, U down to travel height (rapid), D plunge, F F, U R D F, U O R.
  ASSERT_EQ(kinds(p), "UOWUPOWRUDFFURDFUOR") << kinds(p);
  EXPECT_EQ(s[0].z_um, 2000);
  EXPECT_FALSE(s[1].spindle_on);
  EXPECT_EQ(s[2].dwell_ms, 1000u);
  EXPECT_EQ(s[3].z_um, 20000);         // the program's tool-change height
  EXPECT_EQ(s[4].text(), "T1 0.2mm");  // the tool and the message's last word fit 16 columns
  EXPECT_TRUE(s[5].spindle_on);
  EXPECT_EQ(s[6].dwell_ms, 500u);
  EXPECT_EQ(s[7].to.x_um, 5000);  // (10, 10) in the machine frame
  EXPECT_EQ(s[7].to.y_um, 5000);
  EXPECT_EQ(s[8].z_um, 2000);  // rapid down to the travel height before the plunge
  EXPECT_EQ(s[9].z_um, -200);  // the program's depth, not --z-down
  EXPECT_EQ(s[10].to.x_um, 25000);
  EXPECT_EQ(s[11].to.y_um, 15000);
  EXPECT_EQ(s[12].z_um, 2000);  // lift between the cuts
  EXPECT_EQ(s[13].to.x_um, 0);  // second cut: in file order, though it starts nearer zero
  EXPECT_EQ(s[14].z_um, -300);
  EXPECT_EQ(s[15].to.y_um, 20000);
  EXPECT_EQ(s[16].z_um, 2000);  // the program retracted before M5: so does the plan
  EXPECT_FALSE(s[17].spindle_on);
  EXPECT_EQ(s[18].to.x_um, 0);  // home
  EXPECT_EQ(p.curves.size(), 2u);
  EXPECT_EQ(p.curves[0].drawing_index, 0);
  EXPECT_FALSE(p.curves[0].reversed);
  EXPECT_EQ(p.pen_lifts, 1);
}

TEST(ProgramPlan, AToolChangeShowsTheToolAndTheMessagesLastWordOnTheLcd) {
  const JobPlan p = plan_text(
      "G21\nG0 Z10\nT3\n(MSG, Change tool bit to mill diameter 0.00800in)\nM6\nM0\nG1 Z-0.1\nG1 "
      "X1\n");
  ASSERT_EQ(p.steps[2].kind, PlanStep::kPause);
  EXPECT_EQ(p.steps[2].text(), "T3 0.00800in");
  const JobPlan q =
      plan_text("G21\nG0 Z10\n(MSG, Please check the clamps now)\nM0\nG1 Z-0.1\nG1 X1\n");
  EXPECT_EQ(q.steps[2].text(), "Please check the");  // not a tool change: the first 16
}

TEST(ProgramPlan, TheToolChangeHeightIsCappedAtHalfTheZTravel) {
  // pcb2gcode's "G00 Z1.0" in inches is 25.4 mm: above what the Z axis has over the work.
  const JobPlan p = plan_text("G20\nG0 Z1.0\nT1 M6\nG0 Z0.1\nG1 Z-0.01\nG1 X1\n");
  ASSERT_EQ(p.steps[1].kind, PlanStep::kPenUp);
  EXPECT_EQ(p.steps[1].z_um, 20000);
  EXPECT_EQ(p.steps[2].kind, PlanStep::kPause);
}

TEST(ProgramPlan, DepthFromThePlannerWhenTheFileHasNone) {
  PlanOptions o;
  o.z_down_mm = -0.15;
  const JobPlan p = plan_text("G21\nG1 X10\n", o);
  int downs = 0;
  for (const PlanStep& s : p.steps) {
    if (s.kind == PlanStep::kPenDown) {
      EXPECT_EQ(s.z_um, -150);
      ++downs;
    }
  }
  EXPECT_EQ(downs, 1);
  o.file_depths = false;  // --z-down for every cut
  const JobPlan q = plan_text("G21\nG0 Z1\nG1 Z-1\nG1 X10\n", o);
  for (const PlanStep& s : q.steps)
    if (s.kind == PlanStep::kPenDown) EXPECT_EQ(s.z_um, -150);
}

TEST(ProgramPlan, ASecondPassAtAGreaterDepthPlungesInPlace) {
  const JobPlan p = plan_text("G21\nG0 Z1\nG0 X0 Y0\nG1 Z-0.1\nG1 X10\nG1 Z-0.2\nG1 X0\n");
  EXPECT_EQ(kinds(p), "URDFDFUR") << kinds(p);
  EXPECT_EQ(p.steps[4].z_um, -200);
  EXPECT_TRUE(p.curves[1].chained);
  EXPECT_EQ(p.pen_lifts, 0);
}

const char* kDrill =
    "G20\nG90\nG0 Z1.0\nT1\nM6\nM3\nG0 Z0.08\n"
    "G81 R0.08 Z-0.06 F30 X0.9 Y-0.45\nX1.65 Y-0.55\nX1.65 Y-0.80\nG80\nG0 Z1.0\nM5\nM2\n";

TEST(ProgramPlan, G81HolesBecomeDrillStepsInFileOrder) {
  const JobPlan p = plan_text(kDrill);
  EXPECT_EQ(p.holes, 3);
  std::vector<PlanStep> drills;
  for (const PlanStep& s : p.steps) {
    if (s.kind == PlanStep::kDrill) drills.push_back(s);
  }
  ASSERT_EQ(drills.size(), 3u);
  // Lower-left of the holes -> zero: (0.9, -0.8) in.
  const int32_t x[] = {0, 19050, 19050}, y[] = {8890, 6350, 0};
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(drills[i].to.x_um, x[i]);
    EXPECT_EQ(drills[i].to.y_um, y[i]);
    EXPECT_EQ(drills[i].z_start_um, 2032);
    EXPECT_EQ(drills[i].z_um, -1524);
    EXPECT_EQ(drills[i].feed_um_per_s, 5000);  // 12.7 mm/s from the file, capped at 5
  }
  // Up to the tool-change height, stop, spindle on; each drill step goes to its hole itself
  // at the height the tool is at (here still the tool-change height, then R); off, home.
  EXPECT_EQ(kinds(p), "UUPOXXXOR") << kinds(p);
  EXPECT_EQ(p.steps[2].text(), "Change tool T1");
}

TEST(ProgramPlan, HolesAsZMovesWhenAsked) {
  PlanOptions o;
  o.drill_mode = DrillMode::kZMoves;
  const JobPlan p = plan_text("G21\nG0 Z5\nG81 X1 Y1 R2 Z-1 F30\nG80\n", o);
  // Up to 2 (= R), rapid, plunge at F30 mm/min, back to R, then (G98) to the start height 5.
  ASSERT_EQ(kinds(p), "URDUUR") << kinds(p);
  EXPECT_EQ(p.steps[2].z_um, -1000);
  EXPECT_EQ(p.steps[2].feed_um_per_s, 500);
  EXPECT_EQ(p.steps[3].z_um, 2000);
  EXPECT_EQ(p.steps[4].z_um, 5000);
}

TEST(ProgramPlan, PeckDrillingGoesDownInPecksAndDwellAtTheBottom) {
  const JobPlan p = plan_text("G21\nG0 Z2\nG99 G83 X1 Y1 R1 Z-2 Q1.2\nG82 X3 R1 Z-1 P0.25\nG80\n");
  std::vector<int32_t> z;
  std::string k;
  for (const PlanStep& s : p.steps) {
    if (s.kind == PlanStep::kPenUp || s.kind == PlanStep::kPenDown) z.push_back(s.z_um);
    k += "UDRFSPWOX"[s.kind];
  }
  // G83: R 1, peck to -0.2, out to R, back to just above -0.2, down to -1.4 ... -2, out.
  const std::vector<int32_t> want = {2000,  1000, -200, 1000, 54,    -1400, 1000, -1146,
                                     -2000, 1000, 2000, 1000, -1000, 1000,  2000};
  EXPECT_EQ(z, want);
  EXPECT_NE(k.find("DWU"), std::string::npos) << k;  // G82: dwell at the bottom
  bool dwell = false;
  for (const PlanStep& s : p.steps)
    dwell = dwell || (s.kind == PlanStep::kDwell && s.dwell_ms == 250);
  EXPECT_TRUE(dwell);
}

TEST(ProgramPlan, AProgramOfOnlyHolesPlansAndOneOfNothingIsRefused) {
  EXPECT_NO_THROW(plan_text("G21\nG81 X1 Y1 R1 Z-1\n"));
  EXPECT_THROW(plan_text("G21\nM0\n"), PlanError);
}

TEST(ProgramPlan, HoleOutsideTheWorkAreaIsNamed) {
  PlanOptions o;
  o.work_width_mm = 50;
  o.work_height_mm = 50;
  try {
    plan_text("G21\nG1 X10\nG81 X80 Y1 R1 Z-1\n", o);
    FAIL() << "accepted";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("the hole of line 3"), std::string::npos) << e.what();
  }
}

TEST(ProgramPlan, ZBeyondTheTravelIsRefusedWithTheLine) {
  try {
    plan_text("G21\nG1 X10\nG81 X8 Y1 R1 Z-60\n");
    FAIL() << "accepted";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3: Z -60 mm is beyond the controller's Z travel"),
              std::string::npos)
        << e.what();
  }
}

TEST(ProgramPlan, AFixedOffsetLinesUpFilesWithDifferentExtents) {
  // A board's drill file and outline: the hole at (10, 10) of the same board frame.
  PlanOptions o;
  o.fixed_offset = true;
  o.offset_mm = Point2(20, 30);
  const JobPlan drill = plan_text("G21\nG81 X10 Y10 R1 Z-1\nG80\n", o);
  const JobPlan outline = plan_text("G21\nG0 X0 Y0\nG1 X50\nG1 Y40\n", o);
  int32_t hole_x = -1;
  for (const PlanStep& s : drill.steps)
    if (s.kind == PlanStep::kDrill) hole_x = s.to.x_um;
  EXPECT_EQ(hole_x, 30000);
  EXPECT_NEAR(outline.extents_mm.min.x(), 20.0, 1e-9);  // board x 0 -> machine 20
  EXPECT_NEAR(outline.extents_mm.min.y(), 30.0, 1e-9);
  o.offset_mm = Point2(-5, 0);  // the outline would start left of the zero
  EXPECT_THROW(plan_text("G21\nG0 X0 Y0\nG1 X50\n", o), PlanError);
}

// ---- work area: what is too big, by how much, and what would fit ----

Drawing rectangle(double w, double h) {
  Drawing d;
  d.path = "big.dxf";
  Curve c;
  c.set_spline(line_spline({0, 0}, {w, h}));
  c.source = "LINE #1";
  d.curves.push_back(c);
  return d;
}

std::string refusal(const Drawing& d, const PlanOptions& o) {
  try {
    plan_job(d, o);
  } catch (const PlanError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(WorkArea, TooBigSaysBothSizesAndTheScaleThatFits) {
  const std::string m = refusal(rectangle(582, 370), PlanOptions());
  EXPECT_NE(m.find("the drawing is 582 x 370 mm at --scale 1"), std::string::npos) << m;
  EXPECT_NE(m.find("the work area is 297 x 210 mm"), std::string::npos) << m;
  EXPECT_NE(m.find("--scale 0.51 or smaller"), std::string::npos) << m;  // 297/582 = 0.5103
  EXPECT_NE(m.find("travel is 297 x 210 mm, so the drawing has to be scaled down"),
            std::string::npos)
      << m;
  PlanOptions o;
  o.scale = 0.51;
  EXPECT_NO_THROW(plan_job(rectangle(582, 370), o));
}

TEST(WorkArea, AMarginThatPushesItOutSaysWhichMarginFits) {
  PlanOptions o;
  o.margin_mm = 20;
  const std::string m = refusal(rectangle(280, 100), o);
  EXPECT_NE(m.find("--margin 17 or less"), std::string::npos) << m;
  o.margin_mm = 17;
  EXPECT_NO_THROW(plan_job(rectangle(280, 100), o));
}

TEST(WorkArea, ASmallWorkAreaSuggestsALargerOneWithinTheTravel) {
  PlanOptions o;
  o.work_width_mm = 100;
  o.work_height_mm = 100;
  const std::string m = refusal(rectangle(150, 50), o);
  EXPECT_NE(m.find("--work 150 100"), std::string::npos) << m;
}

TEST(WorkArea, WorkBeyondTheControllersTravelIsRefused) {
  PlanOptions o;
  o.work_width_mm = 600;
  o.work_height_mm = 400;
  const std::string m = refusal(rectangle(10, 10), o);
  EXPECT_NE(m.find("--work 600 400 mm is beyond the controller's travel of 297 x 210 mm"),
            std::string::npos)
      << m;
  o.work_width_mm = 297;
  o.work_height_mm = 210;
  EXPECT_NO_THROW(plan_job(rectangle(10, 10), o));
}

// The refusal names the first curve that leaves the area and where; curves inside it (every
// control point inside: the whole curve is) are passed over without sampling.
TEST(WorkArea, TheRefusalNamesTheFirstCurveOutsideAndWhereItLeaves) {
  Drawing d = rectangle(100, 100);
  Curve wide;
  wide.set_spline(line_spline({0, 0}, {400, 50}));
  wide.source = "LINE #2";
  d.curves.push_back(wide);
  const std::string m = refusal(d, PlanOptions());
  // Its first sample beyond x 297 (the line is sampled at its quarters): (300, 37.5).
  EXPECT_NE(m.find("First outside: curve 1 (LINE #2) reaches (300, 37.5) mm in the machine frame"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find("LINE #1"), std::string::npos) << m;
}

// ---- the pcb2gcode files in ../shared/samples plan, in file order ----

const std::string kShared = std::string(ENGRAVER_SOURCE_DIR) + "/../shared/samples/";

bool exists(const std::string& p) {
  struct stat st;
  return stat(p.c_str(), &st) == 0;
}

TEST(SharedGcode, EveryNgcSamplePlansInFileOrder) {
  int planned = 0;
  for (const char* f : {"pcb2gcode_example_board_back.ngc", "pcb2gcode_example_board_drill.ngc",
                        "pcb2gcode_example_board_outline.ngc"}) {
    if (!exists(kShared + f)) continue;
    const Drawing d = import_drawing(kShared + f);
    JobPlan p;
    ASSERT_NO_THROW(p = plan_job(d, PlanOptions())) << f;
    // File order: the plan's curves are the drawing's, 0, 1, 2, ... none reversed.
    for (size_t i = 0; i < p.curves.size(); ++i) {
      EXPECT_EQ(p.curves[i].drawing_index, static_cast<int>(i)) << f;
      EXPECT_FALSE(p.curves[i].reversed) << f;
    }
    int pauses = 0;
    for (const PlanStep& s : p.steps) pauses += s.kind == PlanStep::kPause;
    EXPECT_EQ(pauses, 1) << f;
    ++planned;
  }
  if (planned == 0) GTEST_SKIP() << kShared << " not present";
}

TEST(SharedGcode, ViaconstructorSampleIsTooBigForA4AndSaysSo) {
  const std::string f = kShared + "viaconstructor_check_laser_g2g3.ngc";
  if (!exists(f)) GTEST_SKIP() << f << " not present";
  const std::string m = refusal(import_drawing(f), PlanOptions());
  EXPECT_NE(m.find("the drawing is 581.831 x 370.34 mm"), std::string::npos) << m;
  PlanOptions o;
  o.scale = 0.5;
  EXPECT_NO_THROW(plan_job(import_drawing(f), o));
}

}  // namespace
}  // namespace host
