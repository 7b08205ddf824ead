// Parses --machine specs.
#include "host/lib/server/machine_spec.h"

#include <fmt/format.h>  // fmt::format

#include <sstream>  // std::istringstream

#include "host/lib/server/job_intake.h"
#include "host/lib/stream/link.h"

namespace host::server {

MachineSpec parse_machine_spec(const std::string& spec, const std::string& default_name) {
  auto bad = [&](const std::string& why) {
    return std::invalid_argument(fmt::format(
        "--machine '{}': {} (expected: ADDRESS [name=NAME] [work=WxH] [tags=a,b])", spec, why));
  };
  std::istringstream words(spec);
  MachineSpec m;
  m.name = default_name;
  if (!(words >> m.address)) throw bad("no address");
  try {
    parse_link_spec(m.address);
  } catch (const std::exception& e) {
    throw bad(e.what());
  }
  std::string word;
  while (words >> word) {
    const size_t eq = word.find('=');
    if (eq == std::string::npos) throw bad("'" + word + "' is not key=value");
    const std::string key = word.substr(0, eq);
    const std::string value = word.substr(eq + 1);
    if (key == "name") {
      if (value.empty() || !check_tag(value).empty()) throw bad("name: " + check_tag(value));
      m.name = value;
    } else if (key == "work") {
      double w = 0, h = 0;
      char x = 0;
      std::istringstream v(value);
      if (!(v >> w >> x >> h) || x != 'x' || !(w > 0 && w <= 5000) || !(h > 0 && h <= 5000)) {
        throw bad("work must be WxH in mm, e.g. 297x210");
      }
      m.fit.work_width_mm = w;
      m.fit.work_height_mm = h;
    } else if (key == "tags") {
      std::istringstream v(value);
      std::string tag;
      while (std::getline(v, tag, ',')) {
        if (tag.empty() || !check_tag(tag).empty()) throw bad("tag '" + tag + "'");
        m.fit.tags.push_back(tag);
      }
    } else {
      throw bad("unknown key '" + key + "'");
    }
  }
  return m;
}

}  // namespace host::server
