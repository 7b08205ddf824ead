// Height map frames and probe touches through the controller (controller_map.h).
#include "host/lib/heightmap/controller_map.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>   // std::lround
#include <memory>  // std::make_shared

#include "firmware/protocol/messages.h"
#include "host/lib/stream/encode_command.h"

namespace host::heightmap {

namespace {

int32_t um(double mm) {
  return static_cast<int32_t>(std::lround(mm * 1000.0));
}

}  // namespace

std::vector<QueuedCommand> height_map_commands(const HeightMap& map) {
  validate(map, "the height map");
  std::vector<QueuedCommand> out;
  proto::HeightMapHeaderCmd header{};
  header.cols = static_cast<uint8_t>(map.cols);
  header.rows = static_cast<uint8_t>(map.rows);
  header.x0_um = um(map.origin_x_mm);
  header.y0_um = um(map.origin_y_mm);
  header.pitch_x_um = static_cast<uint16_t>(um(map.pitch_x_mm));
  header.pitch_y_um = static_cast<uint16_t>(um(map.pitch_y_mm));
  out.push_back(encode_command(header));
  const size_t n = map.heights_um.size();
  for (size_t first = 0; first < n; first += 8) {
    proto::HeightMapDataCmd data{};
    data.index = static_cast<uint8_t>(first);
    data.height_n = static_cast<uint8_t>(std::min<size_t>(8, n - first));
    for (uint8_t i = 0; i < data.height_n; ++i)
      data.height_um[i] = static_cast<int32_t>(std::lround(map.heights_um[first + i]));
    out.push_back(encode_command(data));
  }
  return out;
}

QueuedCommand clear_height_map_command() {
  return encode_command(proto::HeightMapHeaderCmd{});
}

std::vector<QueuedCommand> job_map_commands(const HeightMap* map) {
  if (map != nullptr) return height_map_commands(*map);
  return {clear_height_map_command()};
}

ProbeTouch controller_touch(Sender& sender, const ProbeMotion& m,
                            std::function<void(const Progress&)> on_progress,
                            std::function<void()> before_descent) {
  auto first = std::make_shared<bool>(true);
  return [&sender, m, first, on_progress, before_descent](double x_mm, double y_mm) {
    const auto follow = [&on_progress](const Progress& p) {
      if (on_progress) on_progress(p);
    };
    const auto check = [&](JobOutcome outcome) {
      if (outcome != JobOutcome::kCompleted)
        throw ProbeFailed(fmt::format("probing at ({:.3f}, {:.3f}) mm: {}: {}", x_mm, y_mm,
                                      outcome_name(outcome), sender.message()),
                          outcome == JobOutcome::kLinkLost);
    };
    std::vector<QueuedCommand> travel;
    const uint16_t rapid_z = 65535;  // Z moves at the machine's rapid rate (capped there)
    if (*first) travel.push_back(encode_command(proto::ZMoveCmd{um(m.travel_z_mm), rapid_z}));
    *first = false;
    travel.push_back(encode_command(proto::ZMoveCmd{um(m.start_z_mm), rapid_z}));
    travel.push_back(encode_command(proto::RapidMoveCmd{um(x_mm), um(y_mm)}));
    proto::ProbeCmd probe{};
    probe.z_limit_um = um(m.limit_z_mm);
    probe.feed_um_per_s = static_cast<uint16_t>(um(m.feed_mm_s));
    probe.retract_um = static_cast<uint16_t>(um(m.retract_mm));
    const uint16_t before = sender.read_probe_result().probe_count;
    if (before_descent) {
      // The travel alone first: a caller's wait (an operator's hold) comes with the tool
      // above the point, before the descent is sent.
      check(sender.run(travel, follow));
      before_descent();
      check(sender.run({encode_command(probe)}, follow));
    } else {
      travel.push_back(encode_command(probe));
      check(sender.run(travel, follow));
    }
    // The touch is done when the controller counts it (its queue may still be moving). Its
    // last status is where the tool stands, retracted: the one a watcher keeps showing.
    Progress rest;
    rest.status = sender.read_status_at_rest(std::chrono::seconds(60));
    if (on_progress) on_progress(rest);
    const proto::ProbeResultReply r = sender.read_probe_result();
    if (r.probe_count == before)
      throw ProbeFailed(
          fmt::format("probing at ({:.3f}, {:.3f}) mm: the controller counted no "
                      "probe",
                      x_mm, y_mm));
    if (r.result != 1)
      throw ProbeFailed(
          fmt::format("probing at ({:.3f}, {:.3f}) mm: no contact down to Z {:.3f} "
                      "mm (is the probe clip on the blank?)",
                      x_mm, y_mm, r.z_um / 1000.0));
    return static_cast<double>(r.z_um);
  };
}

std::string raise_tool_after_abort(Link& link, SenderOptions options, double z_mm) {
  options.zero_first = false;
  try {
    Sender lift(link, options);
    lift.open_session();
    const uint16_t rapid_z = 65535;
    const std::vector<QueuedCommand> up = {encode_command(proto::ZMoveCmd{um(z_mm), rapid_z})};
    if (lift.run(up, [](const Progress&) {}) != JobOutcome::kCompleted)
      return fmt::format("the tool was not raised: {}", lift.message());
    return fmt::format("the tool raised to Z {:.3f} mm", z_mm);
  } catch (const std::exception& e) {
    return fmt::format("the tool was not raised: {}", e.what());
  }
}

}  // namespace host::heightmap
