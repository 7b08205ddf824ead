// Height map: validation, interpolation and the JSON file (height_map.h).
#include "host/lib/heightmap/height_map.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>          // std::clamp
#include <cmath>              // std::isfinite
#include <cstdio>             // std::rename
#include <fstream>            // std::ifstream
#include <nlohmann/json.hpp>  // nlohmann::json
#include <set>                // std::set
#include <sstream>            // std::stringstream

#include "host/lib/drawing/file_text.h"  // not_a_file_text

namespace host::heightmap {

namespace {

constexpr const char* kFormat = "engraver height map";
constexpr int kVersion = 1;

using Json = nlohmann::json;

[[noreturn]] void fail(const std::string& what, const std::string& message) {
  throw HeightMapError(fmt::format("{}: {}", what, message));
}

const Json& field(const Json& obj, const char* key, const std::string& what,
                  const std::string& where) {
  const auto it = obj.find(key);
  if (it == obj.end()) fail(what, fmt::format("'{}{}' is missing", where, key));
  return *it;
}

double number(const Json& v, const std::string& what, const std::string& name) {
  if (!v.is_number()) fail(what, fmt::format("'{}' must be a number", name));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(what, fmt::format("'{}' must be finite", name));
  return d;
}

int whole(const Json& v, const std::string& what, const std::string& name) {
  if (!v.is_number_integer()) fail(what, fmt::format("'{}' must be a whole number", name));
  const long long n = v.get<long long>();
  if (n < 0 || n > 1000) fail(what, fmt::format("'{}' is {}, outside 0 .. 1000", name, n));
  return static_cast<int>(n);
}

std::string text(const Json& v, const std::string& what, const std::string& name) {
  if (!v.is_string()) fail(what, fmt::format("'{}' must be a string", name));
  return v.get<std::string>();
}

// Unknown keys are refused: a misspelt one would otherwise be silently ignored.
void only_keys(const Json& obj, const std::set<std::string>& keys, const std::string& what,
               const std::string& where) {
  for (auto it = obj.begin(); it != obj.end(); ++it)
    if (keys.count(it.key()) == 0) fail(what, fmt::format("unknown key '{}{}'", where, it.key()));
}

std::pair<double, double> pair_of(const Json& v, const std::string& what, const std::string& name) {
  if (!v.is_array() || v.size() != 2) fail(what, fmt::format("'{}' must be [x, y]", name));
  return {number(v[0], what, name + "[0]"), number(v[1], what, name + "[1]")};
}

}  // namespace

bool HeightMap::covers(double x, double y) const {
  constexpr double kEdgeMm = 1e-6;
  return x >= origin_x_mm - kEdgeMm && x <= max_x_mm() + kEdgeMm && y >= origin_y_mm - kEdgeMm &&
         y <= max_y_mm() + kEdgeMm;
}

double HeightMap::interpolate_um(double x, double y) const {
  // Cell coordinates, clamped to the grid: outside, the nearest edge value.
  const double u = std::clamp((x - origin_x_mm) / pitch_x_mm, 0.0, double(cols - 1));
  const double v = std::clamp((y - origin_y_mm) / pitch_y_mm, 0.0, double(rows - 1));
  const int c = std::min(static_cast<int>(u), cols - 2);
  const int r = std::min(static_cast<int>(v), rows - 2);
  const double fu = u - c, fv = v - r;
  const double bottom = height_um(r, c) * (1 - fu) + height_um(r, c + 1) * fu;
  const double top = height_um(r + 1, c) * (1 - fu) + height_um(r + 1, c + 1) * fu;
  return bottom * (1 - fv) + top * fv;
}

double HeightMap::min_um() const {
  return *std::min_element(heights_um.begin(), heights_um.end());
}
double HeightMap::max_um() const {
  return *std::max_element(heights_um.begin(), heights_um.end());
}

void validate(const HeightMap& m, const std::string& what) {
  if (m.rows < 2 || m.rows > kMaxGridSide || m.cols < 2 || m.cols > kMaxGridSide)
    fail(what, fmt::format("the grid is {} rows x {} cols; each side must be 2 to {} points",
                           m.rows, m.cols, kMaxGridSide));
  if (!std::isfinite(m.origin_x_mm) || !std::isfinite(m.origin_y_mm))
    fail(what, "the grid's origin must be finite");
  if (!(m.pitch_x_mm > 0) || !(m.pitch_y_mm > 0) || !std::isfinite(m.pitch_x_mm) ||
      !std::isfinite(m.pitch_y_mm))
    fail(what, fmt::format("the grid's pitch ({:g}, {:g}) mm must be above 0", m.pitch_x_mm,
                           m.pitch_y_mm));
  if (m.heights_um.size() != static_cast<size_t>(m.rows) * m.cols)
    fail(what, fmt::format("{} heights for {} x {} points", m.heights_um.size(), m.rows, m.cols));
  for (size_t i = 0; i < m.heights_um.size(); ++i)
    if (!std::isfinite(m.heights_um[i]))
      fail(what, fmt::format("the height at row {}, col {} is not finite", i / m.cols, i % m.cols));
  if (m.repeatability_um && !(*m.repeatability_um >= 0))
    fail(what, "repeatability_um must be 0 or above");
  // Z 0 (the copper at the zero corner) counts: the controller adds the heights to the Z
  // it was zeroed at, so their span from it is what it must follow.
  const double range = std::max(m.max_um(), 0.0) - std::min(m.min_um(), 0.0);
  if (range > kMaxMapRangeUm)
    fail(what, fmt::format("the heights span {:.1f} um with Z 0, more than the {:g} um a blank "
                           "may be out of flat (clamp it flat, check the probe clip)",
                           range, kMaxMapRangeUm));
  if (m.pitch_x_mm < kMinPitchMm || m.pitch_x_mm > kMaxPitchMm || m.pitch_y_mm < kMinPitchMm ||
      m.pitch_y_mm > kMaxPitchMm)
    fail(what, fmt::format("the grid's pitch ({:g}, {:g}) mm is outside the controller's {:g} .. "
                           "{:g} mm",
                           m.pitch_x_mm, m.pitch_y_mm, kMinPitchMm, kMaxPitchMm));
}

std::string height_map_text(const HeightMap& m) {
  Json heights = Json::array();
  for (int r = 0; r < m.rows; ++r) {
    Json row = Json::array();
    for (int c = 0; c < m.cols; ++c) row.push_back(std::round(m.height_um(r, c) * 10) / 10);
    heights.push_back(row);
  }
  Json j = Json::object();
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["units"] = {{"xy", "mm"}, {"height", "um"}};
  j["grid"] = {{"origin_mm", {m.origin_x_mm, m.origin_y_mm}},
               {"pitch_mm", {m.pitch_x_mm, m.pitch_y_mm}},
               {"rows", m.rows},
               {"cols", m.cols}};
  j["heights_um"] = heights;
  j["repeatability_um"] = m.repeatability_um ? Json(*m.repeatability_um) : Json(nullptr);
  j["probed_at"] = m.probed_at;
  j["blank"] = m.blank;
  // One row of heights a line: the file reads as the grid it is.
  std::string out = "{\n";
  const char* order[] = {"format",     "version",          "units",     "grid",
                         "heights_um", "repeatability_um", "probed_at", "blank"};
  for (size_t k = 0; k < std::size(order); ++k) {
    out += fmt::format("  \"{}\": ", order[k]);
    if (std::string(order[k]) == "heights_um") {
      out += "[\n";
      for (size_t r = 0; r < heights.size(); ++r)
        out += "    " + heights[r].dump() + (r + 1 < heights.size() ? ",\n" : "\n");
      out += "  ]";
    } else {
      out += j[order[k]].dump();
    }
    out += k + 1 < std::size(order) ? ",\n" : "\n";
  }
  return out + "}\n";
}

HeightMap read_height_map_text(const std::string& text_in, const std::string& what) {
  Json j;
  // A key given twice in any object would silently take its last value (a second
  // "heights_um" replacing the probed one): refused, as the server refuses it.
  std::vector<std::set<std::string>> open_objects;
  std::string twice;
  const auto note_key = [&](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) open_objects.emplace_back();
    if (event == Json::parse_event_t::object_end && !open_objects.empty()) open_objects.pop_back();
    if (event == Json::parse_event_t::key && !open_objects.empty() && twice.empty() &&
        !open_objects.back().insert(parsed.get<std::string>()).second)
      twice = parsed.get<std::string>();
    return true;
  };
  try {
    j = Json::parse(text_in, note_key);
  } catch (const Json::parse_error& e) {
    fail(what, fmt::format("not JSON ({})", e.what()));
  } catch (const Json::exception& e) {
    // A number JSON allows but a double does not hold (1e400: out_of_range).
    fail(what, fmt::format("a number beyond the range of any height or length ({})", e.what()));
  }
  if (!twice.empty()) fail(what, fmt::format("key '{}' given more than once", twice));
  if (!j.is_object()) fail(what, "not a height map (expected a JSON object)");
  only_keys(j,
            {"format", "version", "units", "grid", "heights_um", "repeatability_um", "probed_at",
             "blank"},
            what, "");
  if (field(j, "format", what, "") != kFormat)
    fail(what, fmt::format("'format' must be \"{}\"", kFormat));
  if (field(j, "version", what, "") != kVersion)
    fail(what, fmt::format("version {} is not known here (this engraver reads version {})",
                           j["version"].dump(), kVersion));
  const Json& units = field(j, "units", what, "");
  if (!units.is_object() || units != Json({{"xy", "mm"}, {"height", "um"}}))
    fail(what, "'units' must be {\"xy\": \"mm\", \"height\": \"um\"}");
  const Json& grid = field(j, "grid", what, "");
  if (!grid.is_object()) fail(what, "'grid' must be an object");
  only_keys(grid, {"origin_mm", "pitch_mm", "rows", "cols"}, what, "grid.");
  HeightMap m;
  std::tie(m.origin_x_mm, m.origin_y_mm) =
      pair_of(field(grid, "origin_mm", what, "grid."), what, "grid.origin_mm");
  std::tie(m.pitch_x_mm, m.pitch_y_mm) =
      pair_of(field(grid, "pitch_mm", what, "grid."), what, "grid.pitch_mm");
  m.rows = whole(field(grid, "rows", what, "grid."), what, "grid.rows");
  m.cols = whole(field(grid, "cols", what, "grid."), what, "grid.cols");
  const Json& heights = field(j, "heights_um", what, "");
  if (!heights.is_array() || heights.size() != static_cast<size_t>(m.rows))
    fail(what, fmt::format("'heights_um' must be {} rows (grid.rows)", m.rows));
  for (int r = 0; r < m.rows; ++r) {
    if (!heights[r].is_array() || heights[r].size() != static_cast<size_t>(m.cols))
      fail(what, fmt::format("'heights_um' row {} must have {} heights (grid.cols)", r, m.cols));
    for (int c = 0; c < m.cols; ++c)
      m.heights_um.push_back(number(heights[r][c], what, fmt::format("heights_um[{}][{}]", r, c)));
  }
  const Json& rep = field(j, "repeatability_um", what, "");
  if (!rep.is_null()) m.repeatability_um = number(rep, what, "repeatability_um");
  m.probed_at = text(field(j, "probed_at", what, ""), what, "probed_at");
  m.blank = text(field(j, "blank", what, ""), what, "blank");
  validate(m, what);
  return m;
}

HeightMap read_height_map_file(const std::string& path) {
  const std::string not_a_file = not_a_file_text(path);  // a FIFO's open would wait
  if (!not_a_file.empty()) fail(path, not_a_file);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open the height map");
  std::stringstream s;
  s << in.rdbuf();
  return read_height_map_text(s.str(), path);
}

void write_height_map_file(const HeightMap& map, const std::string& path) {
  validate(map, path);
  // Written beside and renamed: an old map at `path` stays whole if the write fails.
  const std::string part = path + ".part";
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    out << height_map_text(map);
    out.flush();
    if (!out) {
      std::remove(part.c_str());
      fail(path, "cannot write the height map");
    }
  }
  if (std::rename(part.c_str(), path.c_str()) != 0) {
    std::remove(part.c_str());
    fail(path, "cannot write the height map");
  }
}

}  // namespace host::heightmap
