// Run-out rasters on the DEM grid (or a regular grid over the domain for
// analytic terrain): peak thickness, peak speed, arrival time and the final
// deposit thickness. Thickness and speed at a cell centre are SPH
// interpolations of the particles (scatter form, each particle's own
// smoothing length); thickness is measured normal to the slope.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "talus/vec3.hpp"
#include "grid.hpp"
#include "terrain.hpp"
#include "variable_kernel.hpp"

namespace talus::runout {

class RunoutRasters {
 public:
  // `layout` gives the cells (its values are ignored); `terrain` the slope
  // cosines at the cell centres; `threshold` the depth that counts as reached.
  void configure(const Grid& layout, const Terrain& terrain, double threshold);
  bool configured() const { return !cos_.value.empty(); }

  // Interpolates the current thickness and speed and updates the peaks and
  // arrival times. `speed` is the particles' speed along the surface.
  void record(std::span<const Vec3> pos, std::span<const double> volume, std::span<const double> smoothing,
              std::span<const double> speed, const VariableKernel& kernel, double time);

  // Writes PREFIX_peak_thickness.asc, _peak_velocity, _deposit_thickness,
  // _arrival_time and _elevation; returns the file names.
  std::vector<std::string> write(const std::string& prefix, const Terrain& terrain) const;

  const Grid& peak_thickness() const { return peak_h_; }
  const Grid& peak_velocity() const { return peak_v_; }
  const Grid& deposit_thickness() const { return h_; }  // the last recorded thickness
  const Grid& arrival_time() const { return arrival_; }

 private:
  Grid cos_, h_, hv_, peak_h_, peak_v_, arrival_;
  double threshold_ = 0.0;
};

}  // namespace talus::runout
