// Progress bar / periodic progress lines (see progress_meter.h).
#include "host/lib/progress/progress_meter.h"

#include <fmt/format.h>  // fmt::format
#include <unistd.h>      // isatty

#include <algorithm>  // std::min
#include <cmath>      // std::lround

namespace host {

std::string format_duration(double seconds) {
  const long s = std::max(0L, std::lround(seconds));
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

ProgressMeter::ProgressMeter(std::string what, std::string unit, std::ostream& out,
                             ProgressStyle style, std::function<Clock::time_point()> clock)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      out_(out),
      style_(style),
      clock_(std::move(clock)),
      start_(now()),
      last_draw_(start_) {}

ProgressStyle ProgressMeter::for_stderr() {
  ProgressStyle s;
  s.terminal = isatty(STDERR_FILENO) != 0;
  return s;
}

ProgressMeter::~ProgressMeter() {
  finish();
}

std::string ProgressMeter::summary(size_t done, size_t total, double elapsed_s) const {
  // The share rounded down: 100 % only when all is done (111/112 read 99 %, 253/254 100 %).
  std::string s = total > 0 ? fmt::format("{}/{} {} ({}%)", done, total, unit_,
                                          done >= total ? 100 : done * 100 / total)
                            : fmt::format("{} {}", done, unit_);
  if (elapsed_s <= 0) return s;
  const double rate = done / elapsed_s;
  s += rate >= 10 ? fmt::format(", {:.0f}/s", rate) : fmt::format(", {:.1f}/s", rate);
  if (total > 0 && done > 0 && done < total)
    s += fmt::format(", {} left", format_duration((total - done) / rate));
  return s;
}

void ProgressMeter::draw(size_t done, size_t total, const std::string& detail, double elapsed_s) {
  std::string text = summary(done, total, elapsed_s);
  if (!detail.empty()) text += "; " + detail;
  if (style_.terminal) {
    std::string bar;
    if (total > 0) {
      const int filled =
          static_cast<int>(style_.bar_width * std::min<double>(1.0, double(done) / total));
      bar = "[" + std::string(filled, '#') + std::string(style_.bar_width - filled, '.') + "] ";
    }
    std::string line = fmt::format("\r{}: {}{}", what_, bar, text);
    const size_t width = line.size();
    if (width < width_) line += std::string(width_ - width, ' ');
    width_ = width;
    out_ << line << std::flush;
  } else {
    out_ << fmt::format("engraver: {}: {}\n", what_, text) << std::flush;
  }
  drawn_ = true;
  drawn_done_ = done;
  drawn_total_ = total;
}

double ProgressMeter::working_s(Clock::time_point t) const {
  const Clock::duration waiting = waited_ + (waiting_ ? t - waiting_since_ : Clock::duration{});
  return std::chrono::duration<double>(t - start_ - waiting).count();
}

void ProgressMeter::update(size_t done, size_t total, const std::string& detail, bool waiting) {
  last_done_ = done;
  last_total_ = total;
  last_detail_ = detail;
  const Clock::time_point t = now();
  if (waiting && !waiting_) waiting_since_ = t;
  if (!waiting && waiting_) waited_ += t - waiting_since_;
  waiting_ = waiting;
  if (t - start_ < style_.first) return;
  const auto every = style_.terminal ? style_.redraw : style_.line_every;
  if (drawn_ && t - last_draw_ < every) return;
  last_draw_ = t;
  draw(done, total, detail, working_s(t));
}

void ProgressMeter::finish() {
  if (finished_) return;
  finished_ = true;
  if (!drawn_) return;
  // Off a terminal the last line may already say it all.
  const bool said = !style_.terminal && drawn_done_ == last_done_ && drawn_total_ == last_total_;
  if (!said) draw(last_done_, last_total_, last_detail_, working_s(now()));
  if (style_.terminal) out_ << "\n" << std::flush;
}

void ProgressMeter::finish_done() {
  if (last_total_ > 0) last_done_ = last_total_;
  finish();
}

StagedProgress::StagedProgress(std::string what, std::ostream& out, ProgressStyle style,
                               std::function<ProgressMeter::Clock::time_point()> clock)
    : what_(std::move(what)), out_(out), style_(style), clock_(std::move(clock)) {}

void StagedProgress::update(const std::string& unit, size_t done, size_t total) {
  if (!meter_ || unit != unit_) {
    if (meter_) meter_->finish_done();  // the next stage began: this one is done
    meter_.reset();
    unit_ = unit;
    meter_ = std::make_unique<ProgressMeter>(what_, unit, out_, style_, clock_);
  }
  meter_->update(done, total);
}

void StagedProgress::finish() {
  if (meter_) meter_->finish();
  meter_.reset();
}

}  // namespace host
