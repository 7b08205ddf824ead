// The progress meter: quiet at first, periodic lines off a terminal, a redrawn bar on one,
// counts, rate and time left that follow the numbers given.
#include <gtest/gtest.h>

#include <sstream>  // std::ostringstream

#include "host/lib/progress/progress_meter.h"

namespace host {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

struct FakeClock {
  Clock::time_point t{};
  std::function<Clock::time_point()> fn() {
    return [this] { return t; };
  }
};

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

TEST(ProgressMeter, SummaryHasCountsRateAndTimeLeft) {
  std::ostringstream out;
  ProgressMeter m("run", "commands", out, ProgressStyle{});
  EXPECT_EQ(m.summary(250, 1000, 5.0), "250/1000 commands (25%), 50/s, 0:15 left");
  EXPECT_EQ(m.summary(3, 0, 2.0), "3 commands, 1.5/s");
  EXPECT_EQ(format_duration(3725), "1:02:05");
}

TEST(ProgressMeter, OffATerminalPrintsAPlainLineEveryFewSeconds) {
  std::ostringstream out;
  FakeClock c;
  ProgressStyle st;
  st.terminal = false;
  st.first = milliseconds(1000);
  st.line_every = milliseconds(5000);
  {
    ProgressMeter m("run", "commands", out, st, c.fn());
    for (int s = 0; s <= 20; ++s) {  // 20 s of work, an update every second
      c.t = Clock::time_point(std::chrono::seconds(s));
      m.update(static_cast<size_t>(s) * 10, 200, "running");
    }
  }
  const std::string text = out.str();
  EXPECT_EQ(text.find('\r'), std::string::npos);
  // Lines at 1, 6, 11, 16 s, and the last one at the end.
  EXPECT_EQ(count(text, "\n"), 5u) << text;
  EXPECT_NE(text.find("engraver: run: 10/200 commands (5%), 10/s, 0:19 left; running\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("200/200 commands (100%), 10/s; running\n"), std::string::npos) << text;
}

// Work in stages: each stage its own lines in its own unit, the earlier stage ended with its
// last line when the next begins. `run` on 200 000 lines said "plan: 0/200000 curves ordered"
// for ~40 s: the stages after ordering reported nothing.
TEST(StagedProgress, EachStageReportsInItsOwnUnit) {
  std::ostringstream out;
  FakeClock c;
  ProgressStyle st;
  st.terminal = false;
  st.first = milliseconds(500);
  st.line_every = milliseconds(5000);
  {
    StagedProgress p("plan", out, st, c.fn());
    for (int s = 0; s <= 6; ++s) {  // 6 s ordering, then 6 s checking, an update every second
      c.t = Clock::time_point(std::chrono::seconds(s));
      p.update("curves ordered", static_cast<size_t>(s) * 100, 600);
    }
    for (int s = 0; s <= 6; ++s) {
      c.t = Clock::time_point(std::chrono::seconds(7 + s));
      p.update("curves checked against the work area", static_cast<size_t>(s) * 100, 600);
    }
  }
  const std::string text = out.str();
  EXPECT_NE(text.find("engraver: plan: 100/600 curves ordered (16%)"), std::string::npos) << text;
  EXPECT_NE(text.find("engraver: plan: 600/600 curves ordered (100%)"), std::string::npos) << text;
  EXPECT_NE(text.find("engraver: plan: 100/600 curves checked against the work area (16%)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("engraver: plan: 600/600 curves checked against the work area (100%)"),
            std::string::npos)
      << text;
  // Never more than 5 s without a line: at 1 and 6 s, then 8 and 13 s.
  EXPECT_EQ(count(text, "\n"), 4u) << text;
}

// A stage reports each item before working on it, so its last report is one short: when the
// next stage begins the earlier one is done, and its last line says all of it (the outside
// tester saw "598/600 curves measured (99%)" as a stage's last line).
TEST(StagedProgress, AStageThatEndsSaysAllOfIt) {
  std::ostringstream out;
  FakeClock c;
  ProgressStyle st;
  st.terminal = false;
  st.first = milliseconds(500);
  {
    StagedProgress p("plan", out, st, c.fn());
    for (int i = 0; i < 600; ++i) {  // 1.2 s of measuring, the last report 599 of 600
      c.t = Clock::time_point(milliseconds(2 * i));
      p.update("curves measured", static_cast<size_t>(i), 600);
    }
    p.update("curves moved to the margin", 0, 600);
  }
  const std::string text = out.str();
  EXPECT_NE(text.find("engraver: plan: 600/600 curves measured (100%)"), std::string::npos) << text;
  EXPECT_EQ(text.find("599/600"), std::string::npos) << text;
  EXPECT_EQ(count(text, "\n"), 2u) << text;  // its first line at 0.5 s and its last
}

// The share is rounded down: 100 % only when all is done (the outside tester saw 111/112 as
// 99 % and 253/254 as 100 %).
TEST(ProgressMeter, TheShareIsRoundedDownSoOnlyAllDoneIs100Percent) {
  std::ostringstream out;
  ProgressMeter m("run", "commands", out, ProgressStyle{});
  EXPECT_EQ(m.summary(111, 112, 0), "111/112 commands (99%)");
  EXPECT_EQ(m.summary(253, 254, 0), "253/254 commands (99%)");
  EXPECT_EQ(m.summary(254, 254, 0), "254/254 commands (100%)");
  EXPECT_EQ(m.summary(1, 3, 0), "1/3 commands (33%)");
  EXPECT_EQ(m.summary(0, 5, 0), "0/5 commands (0%)");
}

TEST(ProgressMeter, OnATerminalRedrawsOneLineWithABar) {
  std::ostringstream out;
  FakeClock c;
  ProgressStyle st;
  st.terminal = true;
  st.first = milliseconds(0);
  st.redraw = milliseconds(100);
  st.bar_width = 10;
  {
    ProgressMeter m("send", "commands", out, st, c.fn());
    for (int i = 1; i <= 10; ++i) {
      c.t = Clock::time_point(milliseconds(i * 100));
      m.update(static_cast<size_t>(i) * 10, 100);
    }
  }
  const std::string text = out.str();
  EXPECT_EQ(count(text, "\n"), 1u);  // only the final newline
  EXPECT_GE(count(text, "\r"), 10u);
  EXPECT_NE(text.find("send: [#####.....] 50/100 commands (50%)"), std::string::npos) << text;
  EXPECT_NE(text.find("[##########] 100/100"), std::string::npos) << text;
}

TEST(ProgressMeter, ShortWorkPrintsNothing) {
  std::ostringstream out;
  FakeClock c;
  ProgressStyle st;
  st.first = milliseconds(500);
  {
    ProgressMeter m("plan", "curves", out, st, c.fn());
    c.t = Clock::time_point(milliseconds(200));
    m.update(5, 10);
    m.update(10, 10);
  }
  EXPECT_EQ(out.str(), "");
}

// The time left grew while a send stood in a hold or a tool-change pause (the rate fell as
// the clock ran on): waiting time is left out, so the estimate stays what it was.
TEST(ProgressMeter, TimeLeftDoesNotGrowWhileTheWorkWaits) {
  std::ostringstream out;
  FakeClock c;
  ProgressStyle st;
  st.terminal = false;
  st.first = milliseconds(0);
  st.line_every = milliseconds(5000);
  {
    ProgressMeter m("send", "commands", out, st, c.fn());
    for (int s = 0; s <= 10; ++s) {  // 10 s of work: 10 commands a second
      c.t = Clock::time_point(std::chrono::seconds(s));
      m.update(static_cast<size_t>(s) * 10, 200, "running");
    }
    for (int s = 11; s <= 70; ++s) {  // a minute held at 100 of 200
      c.t = Clock::time_point(std::chrono::seconds(s));
      m.update(100, 200, "held", true);
    }
    c.t = Clock::time_point(std::chrono::seconds(75));  // working again
    m.update(100, 200, "running");
  }
  const std::string text = out.str();
  // The hold is seen at 11 s: 11 s of work at 100 commands, 9.1/s. Every line while held
  // (one a 5 s, 15 .. 70 s) and the first after it say the same time left; without leaving
  // the wait out the rate fell to 1.4/s and the time left grew to 1:10.
  EXPECT_EQ(count(text, "100/200 commands (50%), 9.1/s, 0:11 left; held\n"), 12u) << text;
  EXPECT_EQ(count(text, "left; held\n"), 12u) << text;
  EXPECT_NE(text.find("100/200 commands (50%), 9.1/s, 0:11 left; running\n"), std::string::npos)
      << text;
}

}  // namespace
}  // namespace host
