// VCD dump of recorded SPI datagrams (mode 3), for PulseView / sigrok-cli.
#include "hal/fake/spi/vcd_writer.h"  // declarations

#include <ostream>  // std::ostream

namespace fake {

namespace {

// Emits value changes in time order; one timestamp line per distinct time.
class VcdOut {
 public:
  explicit VcdOut(std::ostream& out) : out_(out) {}
  void at(uint64_t t_ns) {
    if (!started_ || t_ns != now_) out_ << '#' << t_ns << '\n';
    started_ = true;
    now_ = t_ns;
  }
  void set(char id, int level) { out_ << (level ? '1' : '0') << id << '\n'; }

 private:
  std::ostream& out_;
  uint64_t now_ = 0;
  bool started_ = false;
};

const char kCs = '!';
const char kSck = '"';
const char kMosi = '#';
const char kMiso = '$';
const uint64_t kLeadInNs = 1000;

}  // namespace

bool write_spi_vcd(std::ostream& out, const std::vector<SpiRecord>& records,
                   const SpiTiming& timing) {
  out << "$date engraver fake SPI $end\n"
         "$version engraver hal/fake/spi vcd_writer $end\n"
         "$timescale 1 ns $end\n"
         "$scope module spi $end\n"
         "$var wire 1 ! CS $end\n"
         "$var wire 1 \" SCK $end\n"
         "$var wire 1 # MOSI $end\n"
         "$var wire 1 $ MISO $end\n"
         "$upscope $end\n"
         "$enddefinitions $end\n";
  VcdOut vcd(out);
  vcd.at(0);
  out << "$dumpvars\n";
  vcd.set(kCs, 1);
  vcd.set(kSck, 1);
  vcd.set(kMosi, 0);
  vcd.set(kMiso, 0);
  out << "$end\n";
  const uint64_t period = timing.sck_period_ns;
  const uint64_t half = period / 2;
  uint64_t free_at = kLeadInNs;  // earliest start of the next datagram
  for (const SpiRecord& r : records) {
    uint64_t t0 = r.time_ns + kLeadInNs;
    if (t0 < free_at) t0 = free_at;
    vcd.at(t0);
    vcd.set(kCs, 0);
    uint64_t fall = t0 + timing.cs_setup_ns;
    for (int bit = 31; bit >= 0; --bit) {
      // Master and slave both shift on the falling edge; the slave's SDO lags a few CLK.
      vcd.at(fall);
      vcd.set(kSck, 0);
      vcd.set(kMosi, (int)((r.mosi >> bit) & 1));
      vcd.at(fall + timing.miso_delay_ns);
      vcd.set(kMiso, (int)((r.miso >> bit) & 1));
      vcd.at(fall + half);
      vcd.set(kSck, 1);
      fall += period;
    }
    const uint64_t cs_up = fall - period + half + timing.cs_hold_ns;
    vcd.at(cs_up);
    vcd.set(kCs, 1);
    free_at = cs_up + timing.cs_high_ns;
  }
  vcd.at(free_at + kLeadInNs);
  return static_cast<bool>(out);
}

}  // namespace fake
