// The simulated blank's copper surface: a tilt, a bow and a local bump over an area, and the
// noise of a probe touching it; given to `sim` and `run` as `--surface` (docs/user-guide.md).
#ifndef HOST_LIB_HEIGHTMAP_SURFACE_MODEL_H
#define HOST_LIB_HEIGHTMAP_SURFACE_MODEL_H

#include <cstdint>    // uint64_t
#include <optional>   // std::optional
#include <random>     // std::mt19937_64
#include <stdexcept>  // std::runtime_error
#include <string>     // std::string

namespace host::heightmap {

// A `--surface` text that cannot be read; the message names the part.
class SurfaceSpecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An area of the machine's X/Y plane in mm.
struct AreaMm {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return !(x1 > x0) || !(y1 > y0); }
};

struct Bump {
  double x_mm = 0, y_mm = 0, radius_mm = 0, height_um = 0;
};

// Every length in um (the text gives each with its unit, mm or um).
struct SurfaceSpec {
  double tilt_x_um = 0;  // rise from the area's left edge to its right edge (+X)
  double tilt_y_um = 0;  // rise from the area's bottom edge to its top edge (+Y)
  double bow_um = 0;     // the area's centre above its corners (negative: a dish)
  std::optional<Bump> bump;
  double noise_um = 0;  // each probe touch reads within +-noise_um of the surface
  uint64_t seed = 1;
  std::optional<AreaMm> area;  // none: the job's extents (run) or the work area (sim)
};

// "tilt=0.1mm,bow=0.2mm,bump=30mm:20mm:4mm:40um,noise=2um,seed=1,area=0mm:0mm:100mm:80mm".
// Keys: tilt (alias tilt_x), tilt_y, bow, bump=X:Y:R:H, noise, seed, area=X0:Y0:X1:Y1; every
// length needs its unit (mm or um). Throws SurfaceSpecError naming what is wrong.
SurfaceSpec parse_surface_spec(const std::string& text);
// The spec as the text parse_surface_spec reads (for reports).
std::string surface_spec_text(const SurfaceSpec& spec);

// The surface over an area; heights relative to the surface at the machine's zero point
// (X 0, Y 0), where the operator touched off Z, so the uncompensated job is right there.
class SurfaceModel {
 public:
  SurfaceModel(const SurfaceSpec& spec, const AreaMm& area);
  // The true copper height at (x, y) in um above Z 0.
  double height_um(double x_mm, double y_mm) const;
  // What one probe touch at (x, y) reads: the height plus this touch's noise (seeded).
  double probe_um(double x_mm, double y_mm);
  // The noise of the next touch alone (for a probe that triggers on the surface itself).
  double next_noise_um();
  const SurfaceSpec& spec() const { return spec_; }
  const AreaMm& area() const { return area_; }

 private:
  double shape_um(double x_mm, double y_mm) const;  // before the zero-point offset
  SurfaceSpec spec_;
  AreaMm area_;
  double zero_um_ = 0;
  std::mt19937_64 rng_;
};

}  // namespace host::heightmap

#endif  // HOST_LIB_HEIGHTMAP_SURFACE_MODEL_H
