// TMC428 datagrams decoded with the register map the driver uses (tmc428_map.h).
#include "host/spi/tmc428_names.h"

#include <cstdio>  // std::snprintf

#include "hal/drivers/tmc428/tmc428_map.h"   // find_register, register_name
#include "hal/drivers/tmc428/tmc428_regs.h"  // sign_extend

namespace host::spi {
namespace {

using drivers::tmc428::sign_extend;  // the driver's, for the same register fields

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
  char name[drivers::tmc428::kRegisterNameBytes];
  drivers::tmc428::register_name(a, name);
  return name;
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
  const drivers::tmc428::RegisterInfo* info = drivers::tmc428::find_register(a);
  if (info == nullptr || info->fields[0].kind == drivers::tmc428::kFieldEnd) {
    if (v) add("data", v, true);
    return d;
  }
  static const char* const kModes[] = {"RAMP", "SOFT", "VELOCITY", "HOLD"};
  for (const auto* f = info->fields; f->kind != drivers::tmc428::kFieldEnd; ++f) {
    const uint32_t raw = bits_of(v, f->hi, f->lo);
    switch (f->kind) {
      case drivers::tmc428::kFieldSigned:
        add(f->name, sign_extend(raw, static_cast<uint8_t>(f->hi - f->lo + 1)));
        break;
      case drivers::tmc428::kFieldHex:
        add(f->name, raw, true);
        break;
      case drivers::tmc428::kFieldRampMode:
        d.fields.push_back({f->name, raw, false, kModes[raw & 3]});
        break;
      default:
        add(f->name, raw);
        break;
    }
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
