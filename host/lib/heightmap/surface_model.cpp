// The simulated blank's surface and probe noise (surface_model.h).
#include "host/lib/heightmap/surface_model.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>    // std::cos
#include <cstdlib>  // std::strtod
#include <map>      // std::map
#include <vector>   // std::vector

#include "host/lib/plan/plain_decimal.h"  // is_whole_decimal: the rule of every count

namespace host::heightmap {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const size_t end = text.find(sep, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

// "0.1mm" or "100um" -> um; the unit is required so a value cannot be read in the wrong one.
double length_um(const std::string& key, const std::string& value) {
  std::string unit;
  double scale = 0;
  if (value.size() > 2 && value.compare(value.size() - 2, 2, "mm") == 0) {
    unit = "mm";
    scale = 1000.0;
  } else if (value.size() > 2 && value.compare(value.size() - 2, 2, "um") == 0) {
    unit = "um";
    scale = 1.0;
  } else {
    throw SurfaceSpecError(fmt::format(
        "--surface {}={}: give the length with its unit, e.g. 0.1mm or 100um", key, value));
  }
  const std::string number = value.substr(0, value.size() - 2);
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != number.size() || !std::isfinite(v))
    throw SurfaceSpecError(
        fmt::format("--surface {}={}: '{}' is not a number", key, value, number));
  return v * scale;
}

std::vector<double> lengths_um(const std::string& key, const std::string& value, size_t count) {
  const std::vector<std::string> parts = split(value, ':');
  if (parts.size() != count)
    throw SurfaceSpecError(
        fmt::format("--surface {}={}: expected {} lengths separated by ':'", key, value, count));
  std::vector<double> out;
  for (const std::string& p : parts) out.push_back(length_um(key, p));
  return out;
}

// A surface more than this far from flat is no blank a V-bit can follow (the map's limit).
constexpr double kMaxShapeUm = 1000.0;

// "tilt=2mm: 2mm is outside the allowed range -1 .. 1 mm": the value as typed and the range
// in its unit, as the other options say it (a value converted and rounded could read as
// inside the range: "1000 um is outside -1000 .. 1000 um" for 1.0000001mm).
void check_range(const std::string& item, const std::string& label, const std::string& typed,
                 double um, double lo_um, double hi_um) {
  if (um >= lo_um && um <= hi_um) return;
  const bool in_mm = typed.size() > 2 && typed.compare(typed.size() - 2, 2, "mm") == 0;
  const double per_unit_um = in_mm ? 1000.0 : 1.0;
  throw SurfaceSpecError(
      fmt::format("--surface {}: {}{} is outside the allowed range {:g} .. {:g} {}", item, label,
                  typed, lo_um / per_unit_um, hi_um / per_unit_um, in_mm ? "mm" : "um"));
}

// The noise's seed: a whole number up to 1e15, where a double's whole numbers still have no
// gaps (the rule of every count: 1e0 and 2.0 are whole).
constexpr double kMaxSeed = 1e15;

}  // namespace

SurfaceSpec parse_surface_spec(const std::string& text) {
  SurfaceSpec s;
  if (text.empty()) throw SurfaceSpecError("--surface: empty (e.g. tilt=0.1mm,bow=0.2mm)");
  std::map<std::string, std::string> given;  // each key once (tilt and tilt_x are one)
  for (const std::string& item : split(text, ',')) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
      throw SurfaceSpecError(fmt::format("--surface: '{}' is not KEY=VALUE", item));
    const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
    const std::string same = key == "tilt" ? "tilt_x" : key;
    const auto earlier = given.find(same);
    if (earlier != given.end()) {
      // Named as typed: 'tilt' given twice is 'tilt', not its other name 'tilt_x'.
      const std::string earlier_key = earlier->second.substr(0, earlier->second.find('='));
      throw SurfaceSpecError(fmt::format(
          "--surface: '{}' is given twice ('{}' and '{}'{}): give each key once", key,
          earlier->second, item,
          earlier_key == key ? "" : fmt::format("; {} and {} are one key", earlier_key, key)));
    }
    given[same] = item;
    if (key == "tilt" || key == "tilt_x") {
      s.tilt_x_um = length_um(key, value);
      check_range(item, "", value, s.tilt_x_um, -kMaxShapeUm, kMaxShapeUm);
    } else if (key == "tilt_y") {
      s.tilt_y_um = length_um(key, value);
      check_range(item, "", value, s.tilt_y_um, -kMaxShapeUm, kMaxShapeUm);
    } else if (key == "bow") {
      s.bow_um = length_um(key, value);
      check_range(item, "", value, s.bow_um, -kMaxShapeUm, kMaxShapeUm);
    } else if (key == "bump") {
      const std::vector<double> v = lengths_um(key, value, 4);
      if (!(v[2] > 0))
        throw SurfaceSpecError(fmt::format("--surface bump={}: the radius must be above 0", value));
      check_range(item, "the height ", split(value, ':')[3], v[3], -kMaxShapeUm, kMaxShapeUm);
      s.bump = Bump{v[0] / 1000.0, v[1] / 1000.0, v[2] / 1000.0, v[3]};
    } else if (key == "noise") {
      s.noise_um = length_um(key, value);
      check_range(item, "", value, s.noise_um, 0.0, 100.0);
    } else if (key == "seed") {
      if (!is_whole_decimal(value))
        throw SurfaceSpecError(
            fmt::format("--surface seed={}: '{}' is not a whole number", value, value));
      const double seed = std::strtod(value.c_str(), nullptr);
      if (!(seed >= 0 && seed <= kMaxSeed))
        throw SurfaceSpecError(
            fmt::format("--surface seed={}: {} is outside the allowed range 0 .. {:.0f}", value,
                        value, kMaxSeed));
      s.seed = static_cast<uint64_t>(seed);
    } else if (key == "area") {
      const std::vector<double> v = lengths_um(key, value, 4);
      const AreaMm a{v[0] / 1000.0, v[1] / 1000.0, v[2] / 1000.0, v[3] / 1000.0};
      if (a.empty())
        throw SurfaceSpecError(
            fmt::format("--surface area={}: X1 must be above X0 and Y1 above Y0", value));
      s.area = a;
    } else {
      throw SurfaceSpecError(fmt::format(
          "--surface: unknown key '{}' (tilt, tilt_y, bow, bump, noise, seed, area)", key));
    }
  }
  return s;
}

std::string surface_spec_text(const SurfaceSpec& s) {
  std::string t =
      fmt::format("tilt={:g}um,tilt_y={:g}um,bow={:g}um", s.tilt_x_um, s.tilt_y_um, s.bow_um);
  if (s.bump)
    t += fmt::format(",bump={:g}mm:{:g}mm:{:g}mm:{:g}um", s.bump->x_mm, s.bump->y_mm,
                     s.bump->radius_mm, s.bump->height_um);
  t += fmt::format(",noise={:g}um,seed={}", s.noise_um, s.seed);
  if (s.area)
    t += fmt::format(",area={:g}mm:{:g}mm:{:g}mm:{:g}mm", s.area->x0, s.area->y0, s.area->x1,
                     s.area->y1);
  return t;
}

SurfaceModel::SurfaceModel(const SurfaceSpec& spec, const AreaMm& area)
    : spec_(spec), area_(spec.area ? *spec.area : area), rng_(spec.seed) {
  if (area_.empty()) throw SurfaceSpecError("--surface: the surface's area is empty");
  zero_um_ = shape_um(0.0, 0.0);
}

double SurfaceModel::shape_um(double x_mm, double y_mm) const {
  const double w = area_.x1 - area_.x0, h = area_.y1 - area_.y0;
  // u, v: -1 .. 1 across the area; the bow is a paraboloid, zero at the corners.
  const double u = (2.0 * x_mm - area_.x0 - area_.x1) / w;
  const double v = (2.0 * y_mm - area_.y0 - area_.y1) / h;
  double z = spec_.tilt_x_um * (x_mm - area_.x0) / w + spec_.tilt_y_um * (y_mm - area_.y0) / h +
             spec_.bow_um * (1.0 - 0.5 * (u * u + v * v));
  if (spec_.bump) {
    const Bump& b = *spec_.bump;
    const double d = std::hypot(x_mm - b.x_mm, y_mm - b.y_mm);
    if (d < b.radius_mm) z += b.height_um * 0.5 * (1.0 + std::cos(kPi * d / b.radius_mm));
  }
  return z;
}

double SurfaceModel::height_um(double x_mm, double y_mm) const {
  return shape_um(x_mm, y_mm) - zero_um_;
}

double SurfaceModel::next_noise_um() {
  if (spec_.noise_um <= 0) return 0.0;
  // From the generator's bits (not a std distribution): the same numbers on every library.
  const double unit = static_cast<double>(rng_() >> 11) / static_cast<double>(uint64_t{1} << 53);
  return (2.0 * unit - 1.0) * spec_.noise_um;
}

double SurfaceModel::probe_um(double x_mm, double y_mm) {
  return height_um(x_mm, y_mm) + next_noise_um();
}

}  // namespace host::heightmap
