// Turning recorded exchanges into golden lines (independent of how they were recorded).
#include "host/spi/scenario.h"

#include <fstream>  // std::ofstream

#include "host/spi/report.h"  // describe_tmc428

namespace host::spi {
namespace {

// Registers whose read value depends on motion or the outside world, not on what was written.
bool live_register(uint8_t address_byte) {
  if (address_byte & 0x80) return false;  // RAM tables read back what was written
  int smda = (address_byte >> 5) & 3;
  int idx = (address_byte >> 1) & 0xF;
  if (smda == 3) return idx == 0 || idx == 1 || idx == 2 || idx == 14;
  // x_actual, v_actual, a_actual, ref_conf/lp, interrupt flags, x_latched.
  return idx == 1 || idx == 5 || idx == 7 || idx == 10 || idx == 11 || idx == 14;
}

// Driver-chain answer words are polled until the chip has them: any number of reads.
bool polled_register(uint8_t address_byte) {
  return address_byte == 0x61 || address_byte == 0x63;
}

}  // namespace

Error record_scenario(const std::string& name, const std::string& job_file,
                      std::vector<Exchange>* out) {
  ScenarioRequest request;
  request.name = name;
  request.job_file = job_file;
  ScenarioRecording rec;
  Error e = record_scenario(request, false, &rec);
  *out = std::move(rec.exchanges);
  return e;
}

Error write_scenario_vcd(const std::string& name, const std::string& job_file,
                         const std::string& path) {
  ScenarioRequest request;
  request.name = name;
  request.job_file = job_file;
  ScenarioRecording rec;
  Error e = record_scenario(request, true, &rec);
  if (!e.ok()) return e;
  std::ofstream out(path, std::ios::binary);
  if (!(out << rec.vcd)) return {"E_OPEN", path + ": cannot write"};
  return {};
}

std::vector<Expected> golden_from_exchanges(const std::vector<Exchange>& ex) {
  std::vector<Expected> out;
  for (size_t i = 0; i < ex.size();) {
    uint8_t a = static_cast<uint8_t>(ex[i].mosi >> 24);
    bool read = a & 1;
    size_t run = 1;
    while (read && i + run < ex.size() && ex[i + run].mosi == ex[i].mosi) ++run;
    const Exchange& last = ex[i + run - 1];
    Expected e;
    e.mosi = exact_pattern(ex[i].mosi, 32);
    if (read && !live_register(a)) {
      e.miso = exact_pattern(last.miso, 32);
      e.miso.mask = 0x00FFFFFF;  // the status byte is never checked
    }
    if (read && (run > 1 || polled_register(a))) {
      e.min_count = 1;
      e.max_count = -1;
    }
    Frame f;
    f.bit_count = 32;
    f.mosi = last.mosi;
    f.miso = last.miso;
    f.has_miso = read && !live_register(a);
    e.comment = describe_tmc428(f);
    if (run > 1) e.comment += " (polled " + std::to_string(run) + "x in the model)";
    out.push_back(e);
    i += run;
  }
  return out;
}

}  // namespace host::spi
