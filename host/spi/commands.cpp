// `engraver spi decode | expect | diff` behaviour, independent of the option parser.
#include "host/spi/commands.h"

#include <filesystem>  // std::filesystem::is_directory
#include <fstream>     // std::ifstream
#include <iterator>    // std::istreambuf_iterator

#include "host/spi/capture.h"   // load_capture
#include "host/spi/diff.h"      // diff_datagrams
#include "host/spi/golden.h"    // parse_golden
#include "host/spi/scenario.h"  // record_scenario

namespace host::spi {
namespace {

void print_error(std::ostream& err, const Error& e) {
  err << "engraver spi: error " << e.code << ": " << e.message << "\n";
}

}  // namespace

Error capture_frames(const std::string& path, const FramerOptions& options,
                     std::vector<Frame>* frames, DecodeInfo* info) {
  Capture cap;
  Error e = load_capture(path, &cap);
  if (!e.ok()) return e;
  *info = DecodeInfo();
  info->source = path;
  info->mode = options.mode;
  info->bits = options.bits;
  if (cap.predecoded) {
    info->format = "saleae-spi-csv";
    info->channel_names = {"-", "-", "MOSI", "MISO"};
    *frames = cap.frames;
    for (Frame& f : *frames)
      if (options.bits > 0 && f.bit_count != options.bits) f.flags |= kFlagWrongBitCount;
  } else {
    FramerResult r;
    e = frame_capture(cap.trace, options, &r);
    if (!e.ok()) return {e.code, path + ": " + e.message};
    info->format = cap.trace.format;
    for (int idx : {r.cs, r.sck, r.mosi, r.miso})
      info->channel_names.push_back(idx >= 0 ? cap.trace.channels[idx].name : "-");
    info->empty_periods = r.empty_periods;
    info->min_pulse_ps = r.min_pulse_ps;
    *frames = std::move(r.frames);
  }
  if (frames->empty())
    return {"E_NO_FRAMES", path +
                               ": no datagrams found (wrong channels, or no chip-select "
                               "period with clock edges)"};
  return {};
}

int run_decode(const DecodeOptions& o, std::ostream& out, std::ostream& err) {
  std::vector<Frame> frames;
  DecodeInfo info;
  Error e = capture_frames(o.capture, o.framer, &frames, &info);
  if (!e.ok()) {
    print_error(err, e);
    return kExitUnusable;
  }
  if (o.json)
    out << decode_json(info, frames, o.raw)
               .dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
        << "\n";
  else
    out << decode_text(info, frames, o.raw);
  for (const Frame& f : frames)
    if (frame_is_error(f)) return kExitDiffer;
  return kExitOk;
}

namespace {

// Probes on the wrong lines: the answer line looks like what the firmware should send.
// "" when not.
std::string swapped_lines_hint(const std::vector<Frame>& frames,
                               const std::vector<Expected>& expected, const DiffResult& d,
                               const DiffOptions& o) {
  bool any_miso = false;
  for (const Frame& f : frames) any_miso = any_miso || f.has_miso;
  if (!d.same() && any_miso) {
    DiffResult swapped;
    if (diff_datagrams(swap_mosi_miso(frames), expected, &swapped, o.within).ok() &&
        swapped.equal > d.equal && swapped.equal * 2 >= static_cast<int>(expected.size()))
      return "MOSI and MISO look swapped: " + std::to_string(swapped.equal) +
             " datagrams match with the two exchanged (swap --mosi/--miso)";
  }
  return "";
}

// The comparison as JSON (o.json) or text with its notes and verdict.
void print_diff(const DiffOptions& o, const std::vector<Frame>& frames,
                const std::vector<Expected>& expected, const DiffResult& d, size_t partial,
                size_t errors, const std::string& hint, std::ostream& out) {
  if (o.json) {
    nlohmann::json j = diff_json(frames, expected, d);
    j["partial_frames_left_out"] = partial;
    j["frame_errors"] = errors;
    j["hint"] = hint;
    j["ignored_before"] = d.ignored_before;
    j["ignored_after"] = d.ignored_after;
    out << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  } else {
    out << diff_text(frames, expected, d, !o.raw);
    if (partial)
      out << "# note: " << partial << " datagram(s) cut by the capture window left out\n";
    if (errors) out << "# note: " << errors << " datagram(s) with frame errors (marked !)\n";
    if (!hint.empty()) out << "# hint: " << hint << "\n";
    if (d.ignored_before || d.ignored_after)
      out << "# note: --within: " << d.ignored_before << " datagram(s) before and "
          << d.ignored_after << " after the expected sequence not compared\n";
    out << diff_verdict(d, frames.size(), expected.size()) << "\n";
  }
}

}  // namespace

int run_diff(const DiffOptions& o, std::ostream& out, std::ostream& err) {
  std::error_code ec;
  // Asked before opening: a FIFO's open waits for a writer.
  if (std::filesystem::exists(o.expected, ec) && !std::filesystem::is_directory(o.expected, ec) &&
      !std::filesystem::is_regular_file(o.expected, ec)) {
    print_error(err, {"E_OPEN", o.expected + ": not a regular file (a pipe, device or socket)"});
    return kExitUnusable;
  }
  std::ifstream in(o.expected, std::ios::binary);
  if (!in || std::filesystem::is_directory(o.expected, ec)) {
    print_error(err, {"E_OPEN", o.expected + ": cannot open"});
    return kExitUnusable;
  }
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<Expected> expected;
  Error e = parse_golden(text, &expected);
  if (!e.ok()) {
    print_error(err, {e.code, o.expected + ": " + e.message});
    return kExitUnusable;
  }
  std::vector<Frame> all;
  DecodeInfo info;
  e = capture_frames(o.capture, o.framer, &all, &info);
  if (!e.ok()) {
    print_error(err, e);
    return kExitUnusable;
  }
  // Frames cut short by the capture window are not the firmware's fault: left out.
  std::vector<Frame> frames;
  size_t errors = 0, partial = 0;
  for (const Frame& f : all) {
    if (frame_is_partial(f)) {
      ++partial;
      continue;
    }
    if (frame_is_error(f)) ++errors;
    frames.push_back(f);
  }
  if (frames.empty()) {
    print_error(err, {"E_NO_FRAMES", o.capture + ": only partial datagrams"});
    return kExitUnusable;
  }
  if (errors > o.max_error_fraction * frames.size()) {
    print_error(
        err, {"E_FRAME_ERRORS",
              o.capture + ": " + std::to_string(errors) + " of " + std::to_string(frames.size()) +
                  " datagrams have frame errors (see `engraver spi decode`); check "
                  "--mode, --bits, channel names and the sample rate"});
    return kExitUnusable;
  }
  DiffResult d;
  e = diff_datagrams(frames, expected, &d, o.within);
  if (!e.ok()) {
    print_error(err, e);
    return kExitUnusable;
  }
  const std::string hint = swapped_lines_hint(frames, expected, d, o);
  print_diff(o, frames, expected, d, partial, errors, hint, out);
  return d.same() ? kExitOk : kExitDiffer;
}

int run_expect(const ExpectOptions& o, std::ostream& out, std::ostream& err) {
  ScenarioRequest request;
  request.name = o.scenario;
  request.job_file = o.job_file;
  request.max_job_datagrams = o.max_datagrams;
  ScenarioRecording rec;
  Error e = record_scenario(request, !o.vcd_path.empty(), &rec);
  if (!e.ok()) {
    print_error(err, e);
    return kExitUnusable;
  }
  if (!o.vcd_path.empty()) {
    std::ofstream vcd(o.vcd_path, std::ios::binary);
    if (!(vcd << rec.vcd)) {
      print_error(err, {"E_OPEN", o.vcd_path + ": cannot write"});
      return kExitUnusable;
    }
  }
  std::string header = "# engraver spi expect --scenario " + o.scenario +
                       (o.job_file.empty() ? "" : " " + o.job_file) +
                       "\n# Recorded from the host build: drivers::Tmc428 against "
                       "fake::Tmc428Model through fake::RecordingSpi.\n";
  if (!rec.note.empty())
    header += "# Job through the simulated machine (host::sim::SimMachine): " + rec.note +
              "; --max-datagrams " + std::to_string(o.max_datagrams) + ".\n";
  header += "# MOSI        MISO (status byte never checked)  # datagram\n";
  out << format_golden(golden_from_exchanges(rec.exchanges), header);
  return kExitOk;
}

}  // namespace host::spi
