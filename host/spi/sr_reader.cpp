// sigrok session (.sr) reader: a zip with a `metadata` ini file and raw logic sample chunks
// (`logic-1` or `logic-1-1`, `logic-1-2`...), read directly (no sigrok-cli needed).
#include <algorithm>  // std::sort
#include <map>        // std::map
#include <sstream>    // std::istringstream

#include "host/spi/capture.h"
#include "host/spi/text_values.h"  // trim, split_number_unit, unit_scale
#include "host/spi/zip_reader.h"   // unzip_all

namespace host::spi {
namespace {

// "4 MHz", "500 kHz", "1000000" -> Hz; 0 if unreadable.
uint64_t parse_rate_hz(const std::string& text) {
  static const UnitScale kHzPer[] = {{"", 1}, {"Hz", 1}, {"kHz", 1e3}, {"MHz", 1e6}, {"GHz", 1e9}};
  double v = 0;
  std::string unit;
  if (!split_number_unit(text, &v, &unit) || !(v > 0)) return 0;
  const double hz = v * unit_scale(trim(unit), kHzPer);
  if (hz < 1 || hz > 1e12) return 0;
  return static_cast<uint64_t>(hz + 0.5);
}

// Keys of section [device 1] of the metadata file.
std::map<std::string, std::string> device_keys(const std::string& ini) {
  std::map<std::string, std::string> keys;
  std::istringstream in(ini);
  std::string line, section;
  while (std::getline(in, line)) {
    line = trim(line);
    if (line.empty() || line[0] == ';' || line[0] == '#') continue;
    if (line[0] == '[') {
      section = line;
      continue;
    }
    size_t eq = line.find('=');
    if (section == "[device 1]" && eq != std::string::npos)
      keys[trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
  }
  return keys;
}

}  // namespace

Error parse_sigrok_sr(const std::string& bytes, Trace* out) {
  *out = Trace();
  out->format = "sigrok";
  std::map<std::string, std::string> files;
  Error e = unzip_all(bytes, &files, size_t(1) << 30);
  if (!e.ok()) return {e.code, "sigrok .sr: " + e.message};
  auto meta = files.find("metadata");
  if (meta == files.end()) return {"E_FORMAT", "sigrok .sr: no 'metadata' member"};
  auto keys = device_keys(meta->second);
  uint64_t rate = parse_rate_hz(keys["samplerate"]);
  if (rate == 0) return {"E_FORMAT", "sigrok .sr: missing or bad samplerate"};
  int unitsize = std::atoi(keys["unitsize"].c_str());
  if (unitsize < 1 || unitsize > 8) return {"E_FORMAT", "sigrok .sr: bad unitsize"};
  std::string base = keys.count("capturefile") ? keys["capturefile"] : "logic-1";
  // Logic probes: probeN = name, N from 1; bit N-1 of each sample.
  std::vector<int> bits;
  for (int n = 1; n <= unitsize * 8; ++n) {
    auto it = keys.find("probe" + std::to_string(n));
    if (it == keys.end()) continue;
    Channel ch;
    ch.name = it->second;
    out->channels.push_back(ch);
    bits.push_back(n - 1);
  }
  if (out->channels.empty()) return {"E_FORMAT", "sigrok .sr: no logic probes in metadata"};
  // Sample chunks: base, or base-1, base-2, ... in numeric order.
  std::vector<std::pair<int, const std::string*>> chunks;
  for (const auto& f : files) {
    if (f.first == base) chunks.push_back({0, &f.second});
    if (f.first.rfind(base + "-", 0) == 0) {
      std::string num = f.first.substr(base.size() + 1);
      if (!num.empty() && num.find_first_not_of("0123456789") == std::string::npos)
        chunks.push_back({std::atoi(num.c_str()), &f.second});
    }
  }
  if (chunks.empty()) return {"E_FORMAT", "sigrok .sr: no sample data ('" + base + "*')"};
  std::sort(chunks.begin(), chunks.end());
  const uint64_t ps_per_s = 1000000000000ULL;
  uint64_t sample = 0;
  uint64_t prev = 0;
  std::string carry;  // a sample split across chunks
  for (const auto& c : chunks) {
    std::string data = carry + *c.second;
    size_t whole = data.size() / unitsize * unitsize;
    for (size_t at = 0; at < whole; at += unitsize, ++sample) {
      uint64_t v = 0;
      for (int b = 0; b < unitsize; ++b)
        v |= static_cast<uint64_t>(static_cast<uint8_t>(data[at + b])) << (8 * b);
      if (sample == 0) {
        for (size_t i = 0; i < bits.size(); ++i) out->channels[i].initial_high = (v >> bits[i]) & 1;
      } else if (v != prev) {
        int64_t t = static_cast<int64_t>(static_cast<unsigned __int128>(sample) * ps_per_s / rate);
        for (size_t i = 0; i < bits.size(); ++i)
          if (((v ^ prev) >> bits[i]) & 1) out->channels[i].toggles_ps.push_back(t);
      }
      prev = v;
    }
    carry = data.substr(whole);
  }
  if (sample == 0) return {"E_FORMAT", "sigrok .sr: no samples"};
  out->start_ps = 0;
  out->end_ps = static_cast<int64_t>(static_cast<unsigned __int128>(sample - 1) * ps_per_s / rate);
  out->sample_period_ps = static_cast<int64_t>(ps_per_s / rate);
  return {};
}

}  // namespace host::spi
