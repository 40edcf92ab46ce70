// The terrain Z(x, y) a depth-integrated flow runs over: analytic surfaces
// for tests (inclined plane, tilted-then-flat plane with a run-out zone,
// parabolic channel) and DEMs (ESRI ASCII; GeoTIFF when built with GDAL).
// The stage samples elevation and gradient for all particles with one
// virtual call per step (sample()); inside, each surface's own inline
// formulas run in a plain loop. Slopes descend towards +x.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "talus/params.hpp"
#include "talus/vec3.hpp"
#include "grid.hpp"

namespace talus::runout {

class Terrain {
 public:
  virtual ~Terrain() = default;
  virtual double elevation(double x, double y) const = 0;
  // (dZ/dx, dZ/dy, 0).
  virtual Vec3 gradient(double x, double y) const = 0;
  // z[i], grad[i] for every position (plan x, y).
  virtual void sample(std::span<const Vec3> pos, double* z, Vec3* grad) const = 0;
  // The DEM grid for output rasters, or null for analytic surfaces.
  virtual const Grid* grid() const { return nullptr; }
  virtual std::string summary() const = 0;
};

// Declares the "terrain" one-of in a stage's parameter set.
void declare_terrain(ParamSet& set);
// Builds the terrain chosen in `values` (the stage's values; member "terrain").
std::unique_ptr<Terrain> make_terrain(const ParamValues& values);

// Terrain from an elevation grid: bilinear elevation; the gradient is the
// bilinear interpolation of central-difference gradients at the cell centres,
// so normals vary continuously across cells.
std::unique_ptr<Terrain> make_grid_terrain(Grid elevation, std::string source);

}  // namespace talus::runout
