// One job through the simulated machine over real loopback TCP, and its measurements.
#include "host/lib/sim/sim_job.h"

#include <atomic>  // std::atomic
#include <chrono>  // steady_clock
#include <thread>  // std::thread

#include "host/lib/sim/contour_error.h"
#include "host/lib/sim/sim_server.h"

namespace host::sim {

double pen_threshold_mm(const JobPlan& plan) {
  int32_t up = 0, down = 0;
  for (const PlanStep& s : plan.steps) {
    if (s.kind == PlanStep::kPenUp) up = s.z_um;
    if (s.kind == PlanStep::kPenDown) down = s.z_um;
  }
  return (up + down) / 2000.0;
}

std::vector<bool> pen_down_samples(const std::vector<ToolSample>& trace, const JobPlan& plan) {
  const double pen = pen_threshold_mm(plan);
  std::vector<bool> down(trace.size(), false);
  bool lifted = false;
  for (size_t i = 0; i < trace.size(); ++i) {
    if (trace[i].z_mm >= pen) lifted = true;
    down[i] = lifted && trace[i].z_mm < pen;
  }
  return down;
}

namespace {

// Path lengths, motion time and contour error of the trace against the planned curves.
void measure(const JobPlan& plan, SimJobResult* r) {
  const std::vector<bool> down = pen_down_samples(r->trace, plan);
  std::vector<std::vector<Point2>> reference;
  for (const PlannedCurve& c : plan.curves) reference.push_back(sample(c.spline, 0.0002));
  const NearestSegment nearest(reference);
  uint64_t first_move = 0, last_move = 0;
  for (size_t i = 1; i < r->trace.size(); ++i) {
    const ToolSample& a = r->trace[i - 1];
    const ToolSample& b = r->trace[i];
    if (first_move == 0) first_move = a.t_ms;
    last_move = b.t_ms;
    const double d = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
    (down[i] ? r->cut_mm : r->rapid_mm) += d;
    if (down[i] && down[i - 1] && d > 0) r->cut_s += (b.t_ms - a.t_ms) / 1000.0;
    if (down[i] && !reference.empty()) {
      const double e = nearest.distance(Point2(b.x_mm, b.y_mm)) * 1000.0;
      if (e > r->max_contour_error_um) r->max_contour_error_um = e;
    }
  }
  r->motion_s = (last_move - first_move) / 1000.0;
}

}  // namespace

SimJobResult run_sim_job(const JobPlan& plan, const SimJobOptions& options) {
  SimJobResult r;
  SimMachine machine(options.machine);
  ServerOptions so;
  so.port = 0;
  so.realtime = options.realtime;
  SimServer server(machine, so);
  std::atomic<bool> stop{false};
  uint64_t simulated = 0;
  const auto wall0 = std::chrono::steady_clock::now();
  std::thread serving([&] { simulated = server.run(stop); });
  try {
    LinkSpec spec;
    spec.host = "127.0.0.1";
    spec.port = server.port();
    std::unique_ptr<Link> link = open_link(spec, std::chrono::milliseconds(2000));
    if (options.wrap_link) link = options.wrap_link(std::move(link));
    Sender sender(*link, options.sender);
    const proto::SessionReply caps = sender.open_session();
    EncodeOptions enc = options.encode;
    enc.max_payload = std::min<unsigned>(enc.max_payload, caps.max_payload);
    enc.controller = &caps;
    const std::vector<QueuedCommand> commands = encode_job(plan, enc);
    r.commands = commands.size();
    r.wire_bytes = wire_bytes(commands);
    r.outcome = sender.run(commands, [&](const Progress& p) {
      if (options.on_progress) options.on_progress(sender, p);
    });
    r.message = sender.message();
    r.stats = sender.stats();
  } catch (const LinkError& e) {
    r.outcome = JobOutcome::kLinkLost;
    r.message = e.what();
  } catch (...) {
    stop = true;
    serving.join();
    throw;
  }
  stop = true;
  serving.join();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.virtual_ms = simulated;
  r.trace = machine.trace();
  r.lcd[0] = machine.lcd_line(0);
  r.lcd[1] = machine.lcd_line(1);
  r.pauses_confirmed = machine.pauses_confirmed();
  r.spindle_on = machine.spindle_on();
  measure(plan, &r);
  return r;
}

}  // namespace host::sim
