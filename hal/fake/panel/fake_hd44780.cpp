// Simulated HD44780: instruction decoding per the HD44780U data sheet's Table 6.
#include "hal/fake/panel/fake_hd44780.h"

#include <cstring>
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
    : now_ns_(0),
      control_(0),
      data_(0),
      control_changed_ns_(0),
      data_changed_ns_(0),
      enable_rose_ns_(0),
      enable_seen_(false),
      busy_until_ns_(0),
      init_step_(kPowerOn),
      last_init_latch_ns_(0),
      address_counter_(0),
      address_in_cgram_(false),
      display_shift_(0),
      // Power-on reset state (data sheet "Initialization by internal reset circuit").
      display_on_(false),
      cursor_on_(false),
      blink_on_(false),
      increment_(true),
      shift_on_write_(false),
      eight_bit_(true),
      two_lines_(false) {
  std::memset(ddram_, ' ', sizeof ddram_);
  std::memset(cgram_, 0, sizeof cgram_);
}

void Hd44780Model::violation(const std::string& what) {
  violations_.push_back("t=" + std::to_string(now_ns_) + "ns: " + what);
}

// Watches E: the rising edge checks RS/RW setup and the cycle time, the falling edge checks
// the pulse width and data setup, then latches (write cycles only).
void Hd44780Model::set_control(uint8_t control_bits) {
  const bool e_was = (control_ & kE) != 0;
  const bool e_now = (control_bits & kE) != 0;
  const uint8_t address_lines = kRs | kRw;
  if ((control_bits & address_lines) != (control_ & address_lines)) {
    if (e_was) violation("RS or R/W changed while E was high");
    control_changed_ns_ = now_ns_;
  }
  if (!e_was && e_now) {
    // At power-on (t = 0) the lines count as just changed.
    if (now_ns_ - control_changed_ns_ < kAddressSetupNs)
      violation("E rose less than t_AS after RS/RW changed");
    if (enable_seen_ && now_ns_ - enable_rose_ns_ < kEnableCycleNs)
      violation("E cycle shorter than t_cycE");
    enable_rose_ns_ = now_ns_;
    enable_seen_ = true;
  }
  control_ = control_bits;
  if (e_was && !e_now) {
    if (now_ns_ - enable_rose_ns_ < kEnableHighNs) violation("E high shorter than PW_EH");
    if (now_ns_ - data_changed_ns_ < kDataSetupNs) violation("data set up less than t_DSW");
    if (control_bits & kRw) {
      violation("read cycle (the model only takes writes)");
    } else {
      latch((control_bits & kRs) != 0, data_);
    }
  }
}

void Hd44780Model::set_data(uint8_t byte) {
  if (byte != data_) data_changed_ns_ = now_ns_;
  data_ = byte;
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
    write_data(byte);
  } else {
    instruction(byte);
  }
}

// Decodes by the highest set bit (Table 6).
void Hd44780Model::instruction(uint8_t code) {
  if (code & 0x80) {
    const uint8_t address = code & 0x7F;
    if (ddram_index(address) < 0) violation("DDRAM address outside the lines: " + hex(address));
    address_counter_ = address;
    address_in_cgram_ = false;
  } else if (code & 0x40) {
    address_counter_ = code & 0x3F;
    address_in_cgram_ = true;
  } else if (code & 0x20) {
    eight_bit_ = (code & 0x10) != 0;
    two_lines_ = (code & 0x08) != 0;
    if (!eight_bit_) violation("function set selected the 4-bit interface");
  } else if (code & 0x10) {
    const bool display = (code & 0x08) != 0;
    const bool right = (code & 0x04) != 0;
    if (display) {
      display_shift_ += right ? -1 : 1;
    } else {
      address_counter_ = step_address(address_counter_, right);
    }
  } else if (code & 0x08) {
    display_on_ = (code & 0x04) != 0;
    cursor_on_ = (code & 0x02) != 0;
    blink_on_ = (code & 0x01) != 0;
  } else if (code & 0x04) {
    increment_ = (code & 0x02) != 0;
    shift_on_write_ = (code & 0x01) != 0;
  } else if (code & 0x02) {
    address_counter_ = 0;
    address_in_cgram_ = false;
    display_shift_ = 0;
  } else if (code & 0x01) {
    std::memset(ddram_, ' ', sizeof ddram_);
    address_counter_ = 0;
    address_in_cgram_ = false;
    display_shift_ = 0;
    increment_ = true;
  }
}

// Data goes where the address counter points, which then moves by the entry mode.
void Hd44780Model::write_data(uint8_t byte) {
  if (address_in_cgram_) {
    cgram_[address_counter_ & 0x3F] = byte;
    address_counter_ = (uint8_t)((address_counter_ + (increment_ ? 1 : 0x3F)) & 0x3F);
    return;
  }
  const int index = ddram_index(address_counter_);
  if (index >= 0) ddram_[index] = byte;
  address_counter_ = step_address(address_counter_, increment_);
  if (shift_on_write_) display_shift_ += increment_ ? 1 : -1;
}

// Next DDRAM address; in 2-line mode the gap 0x28..0x3F is skipped (0x27 -> 0x40 ->...
// 0x67 -> 0x00).
uint8_t Hd44780Model::step_address(uint8_t address, bool up) const {
  if (!two_lines_) return (uint8_t)(up ? (address + 1) % 80 : (address + 79) % 80);
  if (up) {
    if (address == 0x27) return 0x40;
    if (address == 0x67) return 0x00;
    return (uint8_t)(address + 1);
  }
  if (address == 0x40) return 0x27;
  if (address == 0x00) return 0x67;
  return (uint8_t)(address - 1);
}

// Index into ddram_ (row * 40 + column), -1 for addresses that hold no character.
int Hd44780Model::ddram_index(uint8_t address) const {
  if (!two_lines_) return address < 80 ? address : -1;
  if (address <= 0x27) return address;
  if (address >= 0x40 && address <= 0x67) return 40 + (address - 0x40);
  return -1;
}

std::string Hd44780Model::visible_line(int row) const {
  std::string line(16, ' ');
  if (!display_on_ || row < 0 || row > 1 || (!two_lines_ && row == 1)) return line;
  for (int column = 0; column < 16; ++column) {
    const int shifted = ((column + display_shift_) % 40 + 40) % 40;
    line[column] = (char)ddram_[row * 40 + shifted];
  }
  return line;
}

std::string Hd44780Model::ddram(uint8_t first, uint8_t count) const {
  std::string out;
  uint8_t address = first;
  for (uint8_t i = 0; i < count; ++i) {
    const int index = ddram_index(address);
    out.push_back(index >= 0 ? (char)ddram_[index] : '?');
    address = step_address(address, true);
  }
  return out;
}

}  // namespace fake
