// One job through the simulated machine over real loopback TCP, and its measurements.
#include "host/lib/sim/sim_job.h"

#include <algorithm>  // std::max, std::min
#include <atomic>     // std::atomic
#include <chrono>     // steady_clock
#include <thread>     // std::thread

#include <time.h>  // clock_gettime

#include "host/lib/sim/sim_link.h"
#include "host/lib/sim/sim_server.h"
#include "host/lib/sim/trace_meter.h"
#include "host/lib/stream/command_source.h"

namespace host::sim {

double pen_threshold_mm(const JobPlan& plan) {
  // Cutting heights: pen-down Z into the work (at or below its zero) and drill bottoms;
  // travel heights: pen-up Z and the drill start height, where the controller travels from
  // hole to hole. The threshold lies halfway between the highest cut and the lowest travel
  // above it (a drill-only job travels at its start height, far below the pen-up height).
  int32_t last_up = 0, last_down = 0;
  bool have_cut = false;
  int32_t cut = 0;
  auto add_cut = [&](int32_t z) {
    cut = have_cut ? std::max(cut, z) : z;
    have_cut = true;
  };
  for (const PlanStep& s : plan.steps) {
    if (s.kind == PlanStep::kPenUp) last_up = s.z_um;
    if (s.kind == PlanStep::kPenDown) {
      last_down = s.z_um;
      if (s.z_um <= 0) add_cut(s.z_um);
    }
    if (s.kind == PlanStep::kDrill) add_cut(s.z_um);
  }
  bool have_travel = false;
  int32_t travel = 0;
  auto add_travel = [&](int32_t z) {
    if (!have_cut || z <= cut) return;  // e.g. the top of a holding tab: still in the board
    travel = have_travel ? std::min(travel, z) : z;
    have_travel = true;
  };
  for (const PlanStep& s : plan.steps) {
    if (s.kind == PlanStep::kPenUp) add_travel(s.z_um);
    if (s.kind == PlanStep::kDrill) add_travel(s.z_start_um);
  }
  if (!have_travel) return (last_up + last_down) / 2000.0;  // heights above the work's zero
  return (cut + travel) / 2000.0;
}

namespace {

// Opens a session, encodes the plan for the controller's payload size and runs it.
void stream_job(Link& link, const JobPlan& plan, const SimJobOptions& options,
                const SenderOptions& sender_options, SimJobResult* r, std::atomic<bool>* in_setup) {
  Sender sender(link, sender_options);
  const proto::SessionReply caps = sender.open_session();
  EncodeOptions enc = options.encode;
  const unsigned max_payload = enc.max_payload;  // a smaller payload asked for is kept
  use_session(caps, &enc);
  enc.max_payload = std::min<unsigned>(max_payload, caps.max_payload);
  enc.controller = &caps;
  // Encoded as the sender goes: only the window it has not seen stored is held.
  EncodedJob commands(plan, enc);
  r->commands = commands.summary().commands;
  r->wire_bytes = commands.summary().wire_bytes;
  r->job_id = commands.summary().job_id;
  try {
    if (options.before_job) {
      *in_setup = true;
      std::vector<QueuedCommand> setup = options.before_job(sender);
      *in_setup = false;
      r->setup.commands = setup.size();
      r->setup.wire_bytes = wire_bytes(setup);
      commands.set_setup(std::move(setup));
    }
    r->outcome = sender.run(commands, [&](const Progress& p) {
      r->executed = p.executed;
      if (options.on_progress) options.on_progress(sender, p);
    });
  } catch (...) {
    if (options.after_stream) options.after_stream(link, sender_options);
    throw;
  }
  if (options.after_stream) options.after_stream(link, sender_options);
  r->commands_held_max = commands.held_max();
  r->executed = sender.executed();  // the report's count is the message's (it was 5 to 6)
  r->message = sender.message();
  r->stats = sender.stats();
}

}  // namespace

namespace {

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + t.tv_nsec * 1e-9;
}

}  // namespace

SimJobResult run_sim_job(const JobPlan& plan, const SimJobOptions& options) {
  SimJobResult r;
  SimMachine machine(options.machine);
  TraceMeter meter(plan, options.trace_step_mm, options.trace_max_samples);
  meter.add(machine.position());
  // The job is measured, not what runs before it (probing: SimJobOptions::before_job).
  std::atomic<bool> in_setup{false};  // the TCP server's thread reads it
  machine.set_sample_sink([&meter, &options, &in_setup](const ToolSample& s) {
    if (!in_setup) {
      ToolSample planned = s;
      if (options.z_offset_mm) planned.z_mm -= options.z_offset_mm(s.x_mm, s.y_mm);
      meter.add(planned);
    }
    if (options.on_sample) options.on_sample(s);
  });
  const uint64_t start_ms = machine.now_ms();
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = thread_cpu_s();
  if (!options.over_tcp) {
    SenderOptions so = options.sender;
    so.clock = [&machine] { return machine_clock(machine); };
    std::unique_ptr<Link> link = std::make_unique<SimLink>(machine, options.realtime);
    // The wrapper (tests) sees the link; the sender's clock is the machine's either way.
    if (options.wrap_link) link = options.wrap_link(std::move(link));
    try {
      stream_job(*link, plan, options, so, &r, &in_setup);
    } catch (const LinkError& e) {
      r.outcome = JobOutcome::kLinkLost;
      r.message = e.what();
    }
  } else {
    ServerOptions so;
    so.port = 0;
    so.realtime = options.realtime;
    SimServer server(machine, so);
    std::atomic<bool> stop{false};
    std::thread serving([&] { server.run(stop); });
    try {
      LinkSpec spec;
      spec.host = "127.0.0.1";
      spec.port = server.port();
      std::unique_ptr<Link> link = open_link(spec, std::chrono::milliseconds(2000));
      if (options.wrap_link) link = options.wrap_link(std::move(link));
      stream_job(*link, plan, options, options.sender, &r, &in_setup);
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
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  r.cpu_s = thread_cpu_s() - cpu0;
  r.virtual_ms = machine.now_ms() - start_ms;
  meter.finish();
  machine.set_sample_sink(nullptr);
  r.trace = std::move(meter.kept());
  r.plot_path = std::move(meter.path());
  r.trace_samples = meter.samples();
  r.trace_step_mm = meter.keep_step_mm();
  r.cut_mm = meter.cut_mm();
  r.rapid_mm = meter.rapid_mm();
  r.cut_s = meter.cut_s();
  r.motion_s = meter.motion_s();
  r.max_contour_error_um = meter.max_contour_error_um();
  r.worst_contour_sample = meter.worst_sample();
  r.lcd[0] = machine.lcd_line(0);
  r.lcd[1] = machine.lcd_line(1);
  r.pauses_confirmed = machine.pauses_confirmed();
  r.spindle_on = machine.spindle_on();
  return r;
}

}  // namespace host::sim
