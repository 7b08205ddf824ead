// The register map's names and fields as tables (from TMC428_REGISTER_MAP).
#include "hal/drivers/tmc428/tmc428_map.h"

#include "hal/drivers/tmc428/tmc428_regs.h"  // the address constants

namespace drivers {
namespace tmc428 {

namespace {

#define TMC428_TABLE_REG(block, idx, constant, text) const RegisterField kFields_##constant[] = {
#define TMC428_TABLE_FIELD(constant, name, hi, lo, kind) {#name, hi, lo, kind},
#define TMC428_TABLE_END(constant) \
  { 0, 0, 0, kFieldEnd }           \
  }                                \
  ;
TMC428_REGISTER_MAP(TMC428_TABLE_REG, TMC428_TABLE_FIELD, TMC428_TABLE_END)
#undef TMC428_TABLE_REG
#undef TMC428_TABLE_FIELD
#undef TMC428_TABLE_END

#define TMC428_INFO_REG(block, idx, constant, text) {constant, text, kFields_##constant},
#define TMC428_INFO_SKIP(...)
const RegisterInfo kRegisters[] = {
    TMC428_REGISTER_MAP(TMC428_INFO_REG, TMC428_INFO_SKIP, TMC428_INFO_SKIP)};
#undef TMC428_INFO_REG
#undef TMC428_INFO_SKIP

const uint8_t kRegisterCount = (uint8_t)(sizeof kRegisters / sizeof kRegisters[0]);

}  // namespace

const RegisterInfo* find_register(uint8_t address_byte) {
  if ((address_byte & kRamBit) != 0) return 0;
  const uint8_t smda = (uint8_t)((address_byte >> 5) & 3U);
  // Motors 1..3 share one block of names: look up motor 0's address.
  const uint8_t address =
      smda == 3 ? (uint8_t)(address_byte & 0x7E) : (uint8_t)(address_byte & 0x1E);
  for (uint8_t i = 0; i < kRegisterCount; ++i) {
    if (kRegisters[i].address == address) return &kRegisters[i];
  }
  return 0;
}

namespace {

// Appends text at *n, leaving room for the NUL.
void put(char* out, uint8_t* n, const char* text) {
  while (*text != 0 && *n + 1 < kRegisterNameBytes) out[(*n)++] = *text++;
}

void put_number(char* out, uint8_t* n, uint8_t v) {
  char digits[4];
  uint8_t k = 0;
  do {
    digits[k++] = (char)('0' + v % 10U);
    v = (uint8_t)(v / 10U);
  } while (v != 0);
  while (k > 0 && *n + 1 < kRegisterNameBytes) out[(*n)++] = digits[--k];
}

}  // namespace

void register_name(uint8_t a, char* out) {
  uint8_t n = 0;
  if ((a & kRamBit) != 0) {
    put(out, &n, (a & 0x40) != 0 ? "ustep_table[" : "drv_chain[");
    put_number(out, &n, (uint8_t)((a >> 1) & 0x1F));
    put(out, &n, "]");
  } else {
    const uint8_t smda = (uint8_t)((a >> 5) & 3U);
    const uint8_t idx = (uint8_t)((a >> 1) & 0xFU);
    if (smda != 3) {
      put(out, &n, "M");
      put_number(out, &n, (uint8_t)(smda + 1));
      put(out, &n, ".");
    }
    const RegisterInfo* r = find_register(a);
    if (r != 0) {
      put(out, &n, r->name);
    } else {
      put(out, &n, smda == 3 ? "unused_c" : "unused");
      put_number(out, &n, idx);
    }
  }
  out[n] = 0;
}

const RegisterInfo* all_registers(uint8_t* count) {
  *count = kRegisterCount;
  return kRegisters;
}

}  // namespace tmc428
}  // namespace drivers
