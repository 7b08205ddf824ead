// Progress of long work for people: a bar redrawn in place when the output is a terminal,
// a plain line every few seconds when it is not (logs, pipes). Counts, rate and time left.
// Nothing is printed for work that ends within the first moments.
#ifndef HOST_LIB_PROGRESS_PROGRESS_METER_H
#define HOST_LIB_PROGRESS_PROGRESS_METER_H

#include <chrono>      // steady_clock
#include <cstddef>     // size_t
#include <functional>  // std::function
#include <memory>      // std::unique_ptr
#include <ostream>     // std::ostream
#include <string>      // std::string

namespace host {

struct ProgressStyle {
  bool terminal = false;                       // redraw one line (else: periodic lines)
  std::chrono::milliseconds first{500};        // quiet for this long after the start
  std::chrono::milliseconds redraw{100};       // terminal: at most this often
  std::chrono::milliseconds line_every{5000};  // not a terminal: one line this often
  int bar_width = 24;
};

class ProgressMeter {
 public:
  using Clock = std::chrono::steady_clock;
  // what: "run", "plan"...; unit: "commands", "curves"... Prints to out (std::cerr).
  ProgressMeter(std::string what, std::string unit, std::ostream& out, ProgressStyle style,
                std::function<Clock::time_point()> clock = nullptr);
  // The style for stderr: terminal or not, decided by isatty.
  static ProgressStyle for_stderr();
  ~ProgressMeter();

  // done of total (total 0: unknown); detail is appended (state, position, machine time).
  // waiting: the work stands still for someone (a hold, a tool-change pause, zeroing): that
  // time is not counted in the rate, so the time left does not grow while it waits.
  void update(size_t done, size_t total, const std::string& detail = std::string(),
              bool waiting = false);
  // Ends the bar's line (terminal) or prints a last line if any were printed.
  void finish();
  // The same for work known to be done: the last line says all of it (a stage reports each
  // item before it works on it, so its last report was one short).
  void finish_done();

  // The text of one report (no bar), for tests and logs: "1200/5000 commands (24%),
  // 400/s, 0:09 left".
  std::string summary(size_t done, size_t total, double elapsed_s) const;

 private:
  Clock::time_point now() const { return clock_ ? clock_() : Clock::now(); }
  // Seconds of work since the start: the time spent waiting left out.
  double working_s(Clock::time_point t) const;
  void draw(size_t done, size_t total, const std::string& detail, double elapsed_s);

  std::string what_, unit_;
  std::ostream& out_;
  ProgressStyle style_;
  std::function<Clock::time_point()> clock_;
  Clock::time_point start_, last_draw_;
  bool drawn_ = false, finished_ = false;
  bool waiting_ = false;
  Clock::time_point waiting_since_;
  Clock::duration waited_{};  // waits that ended
  size_t last_done_ = 0, last_total_ = 0;
  size_t drawn_done_ = 0, drawn_total_ = 0;  // what the last drawn report said
  std::string last_detail_;
  size_t width_ = 0;  // characters of the last terminal line (to blank leftovers)
};

// Work in stages, each counted in its own unit ("bytes checked", then "bytes read"; "curves
// ordered", then "curves checked against the work area" ...): one meter per stage, the last
// ended when the unit changes, so each stage shows its own counts, rate and time left.
class StagedProgress {
 public:
  StagedProgress(std::string what, std::ostream& out, ProgressStyle style,
                 std::function<ProgressMeter::Clock::time_point()> clock = nullptr);
  void update(const std::string& unit, size_t done, size_t total);
  void finish();

 private:
  std::string what_;
  std::ostream& out_;
  ProgressStyle style_;
  std::function<ProgressMeter::Clock::time_point()> clock_;
  std::string unit_;
  std::unique_ptr<ProgressMeter> meter_;
};

// "1:05", "12:00:07": seconds as minutes:seconds (hours when needed).
std::string format_duration(double seconds);

}  // namespace host

#endif  // HOST_LIB_PROGRESS_PROGRESS_METER_H
