// `engraver sim` as a function (see sim_command.h).
#include "host/lib/commands/sim_command.h"

#include <fmt/format.h>  // fmt::format

#include <chrono>     // system_clock
#include <memory>     // std::make_shared
#include <stdexcept>  // std::runtime_error

#include "firmware/config/machine_config.h"      // travel of the simulated blank
#include "host/lib/commands/exit_codes.h"        // CommandFailure
#include "host/lib/heightmap/simulated_blank.h"  // the blank the simulated probe touches
#include "host/lib/stream/host_port.h"           // ADDR:PORT as serve and send read it

namespace host::commands {

sim::ServerOptions listen_options(const std::string& listen) {
  sim::ServerOptions so;
  const std::string serial = "serial:";
  if (listen.compare(0, serial.size(), serial) == 0 || (!listen.empty() && listen[0] == '/')) {
    so.device = listen[0] == '/' ? listen : listen.substr(serial.size());
    so.device = so.device.substr(0, so.device.find(','));  // a baud rate means nothing here
    if (so.device.empty())
      throw CommandFailure(kExitUsage, fmt::format("--listen: '{}': no device", listen));
    return so;
  }
  if (listen.find(':') == std::string::npos) {
    throw CommandFailure(
        kExitUsage, fmt::format("--listen: '{}': expected ADDR:PORT or serial:DEVICE", listen));
  }
  try {
    const HostPort hp = parse_host_port(listen, PortUse::kListen);  // as serve's --listen
    so.address = hp.host;
    so.port = hp.port;
  } catch (const std::invalid_argument& e) {
    throw CommandFailure(kExitUsage, fmt::format("--listen: '{}': {}", listen, e.what()));
  }
  return so;
}

TraceWriter::TraceWriter(const std::string& path) : out_(path, std::ios::trunc) {
  if (!out_) throw CommandFailure(kExitUsage, fmt::format("--trace: '{}': cannot write", path));
  out_ << "t_ms,x_mm,y_mm,z_mm,pen,wall_ms\n";
}

void TraceWriter::add(const sim::ToolSample& s) {
  const auto wall_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count();
  out_ << fmt::format("{},{:.4f},{:.4f},{:.4f},{},{}\n", s.t_ms, s.x_mm, s.y_mm, s.z_mm,
                      s.z_mm < 0 ? 1 : 0, wall_ms);
}

bool TraceWriter::ok() {
  out_.flush();
  return static_cast<bool>(out_);
}

namespace {

// The simulated blank over the machine's whole travel, as the machine's probe sees it.
std::shared_ptr<heightmap::SimulatedBlank> blank_over_travel(const heightmap::SurfaceSpec& spec,
                                                             sim::SimOptions* mo) {
  const config::MachineConfig& mc = mo->machine;
  auto blank = std::make_shared<heightmap::SimulatedBlank>(heightmap::SurfaceModel(
      spec, heightmap::AreaMm{0, 0, mc.axis[config::kAxisX].travel_um / 1000.0,
                              mc.axis[config::kAxisY].travel_um / 1000.0}));
  mo->surface_um = [blank](int32_t x_um, int32_t y_um) { return blank->surface_um(x_um, y_um); };
  return blank;
}

}  // namespace

SimCommandResult run_sim(const SimCommandOptions& o, const std::atomic<bool>& stop,
                         std::ostream& log) {
  sim::ServerOptions so = listen_options(o.listen);
  so.realtime = o.realtime;
  sim::SimOptions mo;
  mo.pause_confirm_ms = o.pause_confirm_ms;
  std::shared_ptr<heightmap::SimulatedBlank> blank;
  if (o.blank) blank = blank_over_travel(*o.blank, &mo);
  sim::SimMachine machine{mo};
  if (!machine.chip_ok()) log << "engraver: simulated TMC428 failed its self-check\n";
  std::unique_ptr<TraceWriter> trace;
  if (!o.trace.empty()) {
    trace = std::make_unique<TraceWriter>(o.trace);
    trace->add(machine.position());
  }
  if (trace || blank) {
    machine.set_sample_sink([&trace, blank](const sim::ToolSample& s) {
      if (blank) blank->tool_at(s.x_mm, s.y_mm, s.z_mm);
      if (trace) trace->add(s);
    });
  }
  std::unique_ptr<sim::SimServer> server;
  try {
    server = std::make_unique<sim::SimServer>(machine, so);
  } catch (const std::runtime_error& e) {
    // The option named, as every bad command line's message does.
    throw CommandFailure(kExitUsage, fmt::format("--listen: '{}': {}", o.listen, e.what()));
  }
  const std::string where = so.device.empty() ? host_port_text(so.address, server->port())
                                              : fmt::format("device {}", so.device);
  log << fmt::format(
      "engraver: simulated machine on {} ({}); Ctrl-C stops\n", where,
      o.realtime ? "real time" : "fast while the host talks, real time while it is silent");
  log << (o.pause_confirm_ms < 0
              ? std::string("engraver: the simulated operator never confirms a pause\n")
              : fmt::format("engraver: the simulated operator confirms each pause (#P) "
                            "after {} ms\n",
                            o.pause_confirm_ms));
  SimCommandResult r;
  r.machine_ms = server->run(stop);
  machine.set_sample_sink(nullptr);
  r.trace_ok = !trace || trace->ok();
  r.pauses_confirmed = machine.pauses_confirmed();
  r.spindle_on = machine.spindle_on();
  r.spindle_switches = machine.spindle_switches();
  return r;
}

}  // namespace host::commands
