// The "job FILE" scenario: plan the drawing as `engraver run` does, stream it to a
// host::sim::SimMachine through an in-process link that advances the machine's virtual time
// only while the sender waits for bytes, and keep the SPI datagrams. The status polls the
// sender would time by the wall clock come from the link every kPollMs of machine time
// instead, so the same drawing gives the same datagrams every time.
#include "host/spi/scenario_job.h"

#include <algorithm>   // std::min
#include <filesystem>  // std::filesystem::is_regular_file
#include <memory>      // std::unique_ptr

#include "firmware/protocol/codec.h"      // proto::encode
#include "firmware/protocol/frame.h"      // proto::encode_frame
#include "host/lib/drawing/drawing.h"     // import_drawing, ImportError
#include "host/lib/plan/job_plan.h"       // plan_job, PlanError
#include "host/lib/sim/sim_machine.h"     // host::sim::SimMachine
#include "host/lib/stream/job_encoder.h"  // encode_job
#include "host/lib/stream/link.h"         // Link
#include "host/lib/stream/sender.h"       // Sender

namespace host::spi {
namespace {

// Machine time the tool may stand still, UART quiet, before the job counts as finished.
const uint64_t kIdleEndMs = 1000;
// Machine time between status queries (the sender's flow control learns the queue's room
// from the replies, as it would from its own polls).
const uint64_t kPollMs = 20;

// Why a recording ended early: the tool stood still, link quiet, after it had moved.
const char kAtRest[] = "tool at rest for 1 s";

// Thrown out of Sender::run through the link when the recording is complete.
struct StopRecording {
  std::string why;
};

// The simulated machine as a Link: bytes go straight to its UART; waiting for an answer
// steps it one millisecond at a time. Watches the recording's length and the job's end.
class SimLink : public Link {
 public:
  SimLink(sim::SimMachine& machine, size_t stop_at_records)
      : machine_(machine), stop_at_(stop_at_records) {}

  void write(const uint8_t* data, size_t size) override { machine_.from_host(data, size); }

  size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) override {
    const long steps = std::max<long>(1, timeout.count());
    for (long i = 0; i < steps && pending_.empty(); ++i) step();
    const size_t n = std::min(capacity, pending_.size());
    std::copy(pending_.begin(), pending_.begin() + n, buffer);
    pending_.erase(0, n);
    return n;
  }

  std::string name() const override { return "sim:in-process"; }

  // Records up to the moment the tool came to rest for the last time.
  size_t rest_records() const { return rest_records_; }

 private:
  // One machine millisecond, then the stop conditions.
  void step() {
    if (machine_.now_ms() % kPollMs == 0) poll_status();
    machine_.step_ms();
    pending_ += machine_.take_to_host();
    const size_t records = machine_.spi_records().size();
    if (stop_at_ != 0 && records >= stop_at_) throw StopRecording{"datagram limit"};
    moved_ = moved_ || machine_.trace().size() > 1;
    if (machine_.busy() || !moved_) {
      idle_ms_ = 0;
      rest_records_ = records;
      return;
    }
    if (++idle_ms_ >= kIdleEndMs) throw StopRecording{kAtRest};
  }

  // A status query on the sender's behalf; its reply reaches the sender like its own.
  void poll_status() {
    uint8_t frame[proto::kMaxFrameBytes];
    const uint8_t n = proto::encode_frame(proto::kCommandStart, proto::kCmdStatus, poll_seq_++, 0,
                                          0, frame, sizeof frame);
    machine_.from_host(frame, n);
  }

  sim::SimMachine& machine_;
  uint8_t poll_seq_ = 0x80;  // apart from the sender's own status numbers
  size_t stop_at_;
  std::string pending_;
  bool moved_ = false;
  uint64_t idle_ms_ = 0;
  size_t rest_records_ = 0;
};

// Reads and plans the drawing with the CLI's defaults (feed 10 mm/s, 5 um chords, A4).
Error plan_drawing(const std::string& path, JobPlan* plan) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return {"E_OPEN", path + ": cannot open"};
  try {
    *plan = plan_job(import_drawing(path), PlanOptions());
  } catch (const ImportError& e) {
    return {"E_SCENARIO", std::string("job: ") + e.what()};
  } catch (const PlanError& e) {
    return {"E_SCENARIO", path + ": " + e.what()};
  }
  return {};
}

// Zeroing queued ahead of the job (the simulated operator confirms it), so the sender need
// not poll the machine's state on its wall clock.
QueuedCommand zeroing_command() {
  proto::ZeroingCmd zero{proto::kAxisMaskAll};
  proto::Payload p;
  proto::encode(zero, &p);
  QueuedCommand c;
  c.letter = proto::kCmdZeroing;
  c.payload.assign(p.bytes, p.bytes + p.length);
  return c;
}

}  // namespace

Error record_job(const std::string& drawing_path, size_t max_after_init,
                 std::vector<fake::SpiRecord>* out, fake::SpiTiming* timing, std::string* note) {
  out->clear();
  JobPlan plan;
  Error e = plan_drawing(drawing_path, &plan);
  if (!e.ok()) return e;
  sim::SimOptions options;
  options.record_spi = true;
  sim::SimMachine machine(options);
  if (!machine.chip_ok()) return {"E_SCENARIO", "job: the TMC428 driver's init failed"};
  const size_t init_records = machine.spi_records().size();
  SimLink link(machine, max_after_init == 0 ? 0 : init_records + max_after_init);
  SenderOptions so;
  so.zero_first = false;                       // the zeroing is the job's first command
  so.status_interval = std::chrono::hours(1);  // one status at the start, none on the wall clock
  Sender sender(link, so);
  std::string end;
  try {
    const proto::SessionReply caps = sender.open_session();
    EncodeOptions enc;
    enc.max_payload = std::min<unsigned>(enc.max_payload, caps.max_payload);
    std::vector<QueuedCommand> commands{zeroing_command()};
    for (QueuedCommand& c : encode_job(plan, enc)) commands.push_back(std::move(c));
    const JobOutcome outcome = sender.run(commands, nullptr);
    if (outcome != JobOutcome::kCompleted)
      return {"E_SCENARIO", "job: the simulated machine did not complete it: " +
                                std::string(outcome_name(outcome)) + " (" + sender.message() + ")"};
    end = "job completed: " + sender.message();
  } catch (const StopRecording& stop) {
    end = stop.why;
  } catch (const LinkError& err) {
    return {"E_SCENARIO", std::string("job: ") + err.what()};
  } catch (const PlanError& err) {
    return {"E_SCENARIO", drawing_path + ": " + err.what()};
  }
  size_t keep = machine.spi_records().size();
  if (end == kAtRest) keep = std::min(keep, link.rest_records());
  if (max_after_init != 0) keep = std::min(keep, init_records + max_after_init);
  out->assign(machine.spi_records().begin(), machine.spi_records().begin() + keep);
  *timing = machine.spi_timing();
  *note = std::to_string(init_records) + " init datagrams + " +
          std::to_string(keep - init_records) + " after (" + end + ", machine time " +
          std::to_string(machine.now_ms()) + " ms)";
  return {};
}

}  // namespace host::spi
