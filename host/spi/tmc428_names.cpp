// TMC428 register map and field layout, as in shared/reference/tmc428.md.
#include "host/spi/tmc428_names.h"

#include <cstdio>  // std::snprintf

namespace host::spi {
namespace {

const char* const kMotorRegs[16] = {
    "x_target", "x_actual",         "v_min",         "v_max",     "v_target",      "v_actual",
    "a_max",    "a_actual",         "current_scale", "pmul_pdiv", "ref_conf_mode", "interrupt",
    "dividers", "dx_ref_tolerance", "x_latched",     "unused15"};
const char* const kCommonRegs[16] = {
    "datagram_low_word", "datagram_high_word", "cover_pos_len", "cover_datagram",
    "unused_c4",         "unused_c5",          "unused_c6",     "unused_c7",
    "power_down",        "unused_c9",          "unused_c10",    "unused_c11",
    "unused_c12",        "unused_c13",         "ref_switches",  "SMGP"};

int64_t sign_extend(uint32_t v, int bits) {
  uint32_t m = 1u << (bits - 1);
  v &= (1u << bits) - 1;
  return static_cast<int64_t>(static_cast<int32_t>((v ^ m) - m));
}

uint32_t bits_of(uint32_t v, int hi, int lo) {
  return (v >> lo) & ((1u << (hi - lo + 1)) - 1);
}

// Driver-chain RAM entry: primary signal code + NxM flag.
std::string chain_entry(uint32_t e) {
  static const char* const kCodes[] = {"DAC_A0", "DAC_A1", "DAC_A2", "DAC_A3", "DAC_A4",
                                       "DAC_A5", "PH_A",   "FD_A",   "DAC_B0", "DAC_B1",
                                       "DAC_B2", "DAC_B3", "DAC_B4", "DAC_B5", "PH_B",
                                       "FD_B",   "ZERO",   "ONE",    "DIR",    "STEP"};
  uint32_t code = e & 0x1F;
  std::string s = code < 20 ? kCodes[code] : "unused" + std::to_string(code);
  if (e & 0x20) s += "+NxM";
  return s;
}

}  // namespace

std::string tmc428_register_name(uint8_t a) {
  if (a & 0x80) {
    int pair = (a >> 1) & 0x1F;
    return (a & 0x40) ? "ustep_table[" + std::to_string(pair) + "]"
                      : "drv_chain[" + std::to_string(pair) + "]";
  }
  int smda = (a >> 5) & 3;
  int idx = (a >> 1) & 0xF;
  if (smda == 3) return kCommonRegs[idx];
  return "M" + std::to_string(smda + 1) + "." + kMotorRegs[idx];
}

std::vector<std::string> tmc428_status_bits(uint8_t s) {
  static const char* const kBits[8] = {"INT", "CDGW",  "RS3", "xEQt3",
                                       "RS2", "xEQt2", "RS1", "xEQt1"};
  std::vector<std::string> out;
  for (int i = 0; i < 8; ++i)
    if (s & (0x80 >> i)) out.push_back(kBits[i]);
  return out;
}

Tmc428Datagram decode_tmc428(uint32_t mosi, bool has_miso, uint32_t miso) {
  Tmc428Datagram d;
  uint8_t a = static_cast<uint8_t>(mosi >> 24);
  d.read = a & 1;
  d.ram = a & 0x80;
  d.reg = tmc428_register_name(a);
  d.known = d.reg.find("unused") == std::string::npos;
  if (d.read && !has_miso) return d;  // nothing to decode: the data is in MISO
  d.fields_from_miso = d.read;
  uint32_t v = (d.read ? miso : mosi) & 0xFFFFFF;
  auto add = [&d](const char* n, int64_t x, bool hex = false) {
    d.fields.push_back({n, x, hex, ""});
  };
  if (d.ram) {
    if (a & 0x40) {
      add("y_even", bits_of(v, 5, 0));
      add("y_odd", bits_of(v, 13, 8));
    } else {
      d.fields.push_back({"even", bits_of(v, 5, 0), true, chain_entry(bits_of(v, 5, 0))});
      d.fields.push_back({"odd", bits_of(v, 13, 8), true, chain_entry(bits_of(v, 13, 8))});
    }
    return d;
  }
  int smda = (a >> 5) & 3;
  int idx = (a >> 1) & 0xF;
  if (smda == 3) {
    switch (idx) {
      case 0:
      case 1:
        add("data", v, true);
        break;
      case 2:
        add("cover_pos", bits_of(v, 13, 8));
        add("cover_len", bits_of(v, 4, 0));
        add("cover_waiting", bits_of(v, 23, 23));
        break;
      case 3:
        add("cover_datagram", v, true);
        break;
      case 14:
        add("r1", bits_of(v, 0, 0));
        add("l1", bits_of(v, 1, 1));
        add("r2", bits_of(v, 2, 2));
        add("l2", bits_of(v, 3, 3));
        add("r3", bits_of(v, 4, 4));
        add("l3", bits_of(v, 5, 5));
        break;
      case 15:
        add("lsmd", bits_of(v, 1, 0));
        add("pol_nscs_s", bits_of(v, 2, 2));
        add("pol_sck_s", bits_of(v, 3, 3));
        add("pol_ph_ab", bits_of(v, 4, 4));
        add("pol_fd_ab", bits_of(v, 5, 5));
        add("pol_dac_ab", bits_of(v, 6, 6));
        add("cs_comind", bits_of(v, 7, 7));
        add("clk2_div", bits_of(v, 15, 8));
        add("cont_update", bits_of(v, 16, 16));
        add("refmux", bits_of(v, 20, 20));
        add("mot1r", bits_of(v, 21, 21));
        break;
      default:
        if (v) add("data", v, true);
        break;
    }
    return d;
  }
  switch (idx) {
    case 0:
    case 1:
    case 14:
      add("x", sign_extend(v, 24));
      break;
    case 2:
    case 3:
      add("v", bits_of(v, 10, 0));
      break;
    case 4:
    case 5:
      add("v", sign_extend(v, 12));
      break;
    case 6:
      add("a", bits_of(v, 10, 0));
      break;
    case 7:
      add("a", sign_extend(v, 12));
      break;
    case 8:
      add("is_agtat", bits_of(v, 22, 20));
      add("is_aleat", bits_of(v, 18, 16));
      add("is_v0", bits_of(v, 14, 12));
      add("a_threshold", bits_of(v, 10, 0));
      break;
    case 9:
      add("pmul", bits_of(v, 15, 8));
      add("pdiv", bits_of(v, 3, 0));
      break;
    case 10: {
      static const char* const kModes[] = {"RAMP", "SOFT", "VELOCITY", "HOLD"};
      d.fields.push_back({"ramp_mode", v & 3, false, kModes[v & 3]});
      add("ref_conf", bits_of(v, 11, 8), true);
      add("lp", bits_of(v, 16, 16));
      break;
    }
    case 11:
      add("int_mask", bits_of(v, 15, 8), true);
      add("int_flags", bits_of(v, 7, 0), true);
      break;
    case 12:
      add("pulse_div", bits_of(v, 15, 12));
      add("ramp_div", bits_of(v, 11, 8));
      add("usrs", bits_of(v, 2, 0));
      break;
    case 13:
      add("dx_ref_tolerance", bits_of(v, 11, 0));
      break;
    default:
      if (v) add("data", v, true);
      break;
  }
  return d;
}

std::string fields_text(const std::vector<Field>& fields) {
  std::string s;
  for (const Field& f : fields) {
    if (!s.empty()) s += ' ';
    if (!f.text.empty()) {
      s += f.name + "=" + f.text;
      continue;
    }
    char buf[40];
    if (f.hex)
      std::snprintf(buf, sizeof buf, "=0x%llX", static_cast<unsigned long long>(f.value));
    else
      std::snprintf(buf, sizeof buf, "=%lld", static_cast<long long>(f.value));
    s += f.name + buf;
  }
  return s;
}

}  // namespace host::spi
