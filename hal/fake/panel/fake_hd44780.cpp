// Simulated HD44780: instruction decoding per the HD44780U data sheet's Table 6.
#include "hal/fake/panel/fake_hd44780.h"

#include <sstream>

namespace fake {

namespace {
std::string hex(unsigned v) {
  std::ostringstream s;
  s << "0x" << std::hex << v;
  return s.str();
}
}  // namespace

Hd44780Model::Hd44780Model()
    : now_ns_(0), busy_until_ns_(0), init_step_(kPowerOn), last_init_latch_ns_(0) {}

void Hd44780Model::violation(const std::string& what) {
  violations_.push_back("t=" + std::to_string(now_ns_) + "ns: " + what);
}

// Watches E: the rising edge checks RS/RW setup and the cycle time, the falling edge checks
// the pulse width and data setup, then latches (write cycles only).
void Hd44780Model::set_control(uint8_t control_bits) {
  const bool e_was = (pins_.control & kE) != 0;
  const bool e_now = (control_bits & kE) != 0;
  const uint8_t address_lines = kRs | kRw;
  if ((control_bits & address_lines) != (pins_.control & address_lines)) {
    if (e_was) violation("RS or R/W changed while E was high");
    pins_.control_changed_ns = now_ns_;
  }
  if (!e_was && e_now) {
    // At power-on (t = 0) the lines count as just changed.
    if (now_ns_ - pins_.control_changed_ns < kAddressSetupNs)
      violation("E rose less than t_AS after RS/RW changed");
    if (pins_.enable_seen && now_ns_ - pins_.enable_rose_ns < kEnableCycleNs)
      violation("E cycle shorter than t_cycE");
    pins_.enable_rose_ns = now_ns_;
    pins_.enable_seen = true;
  }
  pins_.control = control_bits;
  if (e_was && !e_now) {
    if (now_ns_ - pins_.enable_rose_ns < kEnableHighNs) violation("E high shorter than PW_EH");
    if (now_ns_ - pins_.data_changed_ns < kDataSetupNs) violation("data set up less than t_DSW");
    if (control_bits & kRw) {
      violation("read cycle (the model only takes writes)");
    } else {
      latch((control_bits & kRs) != 0, pins_.data);
    }
  }
}

void Hd44780Model::set_data(uint8_t byte) {
  if (byte != pins_.data) pins_.data_changed_ns = now_ns_;
  pins_.data = byte;
}

void Hd44780Model::delay_us(uint16_t us) {
  now_ns_ += (uint64_t)us * 1000u;
}

// One write cycle: checks the init sequence and the busy time, then executes it.
void Hd44780Model::latch(bool rs, uint8_t byte) {
  latches_.push_back(Latch{now_ns_, rs, byte});
  const bool function_set_8bit = !rs && (byte & 0xF0) == 0x30;
  switch (init_step_) {
    case kPowerOn:
      if (!function_set_8bit) {
        violation("first write is not function set 8-bit: " + hex(byte));
      } else if (now_ns_ < kPowerOnNs) {
        violation("first function set before 15 ms after power-on");
      } else {
        init_step_ = kAfterFirst;
        last_init_latch_ns_ = now_ns_;
      }
      return;  // busy flag not valid yet: no busy check, nothing executed but DL
    case kAfterFirst:
    case kAfterSecond: {
      const uint64_t gap = init_step_ == kAfterFirst ? kInitGap1Ns : kInitGap2Ns;
      if (!function_set_8bit) {
        violation("init sequence interrupted by " + hex(byte));
        init_step_ = kPowerOn;
      } else if (now_ns_ - last_init_latch_ns_ < gap) {
        violation(init_step_ == kAfterFirst ? "second function set sooner than 4.1 ms"
                                            : "third function set sooner than 100 us");
        init_step_ = kPowerOn;
      } else {
        init_step_ = init_step_ == kAfterFirst ? kAfterSecond : kInitDone;
        last_init_latch_ns_ = now_ns_;
        busy_until_ns_ = now_ns_ + kExecNs;
      }
      return;
    }
    case kInitDone:
      break;
  }
  if (now_ns_ < busy_until_ns_) {
    violation(std::string(rs ? "data " : "instruction ") + hex(byte) + " while busy for " +
              std::to_string(busy_until_ns_ - now_ns_) + " ns more");
  }
  const bool slow = !rs && (byte == 0x01 || (byte & 0xFE) == 0x02);
  busy_until_ns_ = now_ns_ + (slow ? kClearHomeExecNs : kExecNs);
  if (rs) {
    display_.write_data(byte);
  } else {
    instruction(byte);
  }
}

// Decodes by the highest set bit (Table 6).
void Hd44780Model::instruction(uint8_t code) {
  if (code & 0x80) {
    const uint8_t address = code & 0x7F;
    if (!display_.set_ddram_address(address))
      violation("DDRAM address outside the lines: " + hex(address));
  } else if (code & 0x40) {
    display_.set_cgram_address(code & 0x3F);
  } else if (code & 0x20) {
    display_.set_function((code & 0x10) != 0, (code & 0x08) != 0);
    if (!display_.eight_bit()) violation("function set selected the 4-bit interface");
  } else if (code & 0x10) {
    display_.shift((code & 0x08) != 0, (code & 0x04) != 0);
  } else if (code & 0x08) {
    display_.set_display_control((code & 0x04) != 0, (code & 0x02) != 0, (code & 0x01) != 0);
  } else if (code & 0x04) {
    display_.set_entry_mode((code & 0x02) != 0, (code & 0x01) != 0);
  } else if (code & 0x02) {
    display_.return_home();
  } else if (code & 0x01) {
    display_.clear();
  }
}

}  // namespace fake
