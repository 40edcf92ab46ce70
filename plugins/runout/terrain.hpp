// The terrain Z(x, y) a depth-integrated flow runs over: analytic surfaces
// for tests (inclined plane, tilted-then-flat plane with a run-out zone,
// parabolic channel) and DEMs (ESRI ASCII; GeoTIFF when built with GDAL).
// The stage samples elevation, gradient and Hessian for all particles with
// one virtual call per step (sample()); inside, each surface's own inline
// formulas run in a plain loop. Slopes descend towards +x.
//
// DEM surface: a uniform bicubic B-spline with the DEM values as control
// points (cell centres), two ghost rings extrapolated linearly at the edges.
// It is C2, so the curvature the flow's normal stress needs is continuous;
// it reproduces planes exactly and quadratic surfaces up to the constant
// offset cell^2 (Zxx + Zyy) / 6, so their curvature is exact; and it damps
// cell-scale noise (gain 1/3 at the grid's Nyquist wavelength) where an
// interpolating bicubic, or the bilinear surface's kinks at every cell edge,
// would turn that noise into large second derivatives. The price: the
// surface departs from the DEM values by about cell^2 |curvature| / 6 where
// the terrain is curved (0.08 m for 5 m cells and a 50 m radius).
// No-data cells are allowed: the surface is undefined wherever the 4 x 4
// control points of a point include one (elevation NaN there, defined()
// false); the stage refuses a release there and removes particles that flow
// onto it.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "talus/params.hpp"
#include "talus/vec3.hpp"
#include "grid.hpp"

namespace talus::runout {

// Second derivatives of Z(x, y).
struct Hessian {
  double xx = 0.0, xy = 0.0, yy = 0.0;
};

// v^T H v for a plan vector v: the rate at which the slope along v turns.
inline double along(const Hessian& H, const Vec3& v) {
  return H.xx * v.x * v.x + 2.0 * H.xy * v.x * v.y + H.yy * v.y * v.y;
}

class Terrain {
 public:
  virtual ~Terrain() = default;
  virtual double elevation(double x, double y) const = 0;
  // (dZ/dx, dZ/dy, 0).
  virtual Vec3 gradient(double x, double y) const = 0;
  virtual Hessian hessian(double x, double y) const = 0;
  // False where the surface is undefined (a DEM's no-data cells and their neighbours).
  virtual bool defined(double, double) const { return true; }
  // z[i], grad[i], hess[i] for every position (plan x, y); NaN where undefined.
  virtual void sample(std::span<const Vec3> pos, double* z, Vec3* grad, Hessian* hess) const = 0;
  // The DEM grid for output rasters, or null for analytic surfaces.
  virtual const Grid* grid() const { return nullptr; }
  virtual std::string summary() const = 0;
};

// Declares the "terrain" one-of in a stage's parameter set.
void declare_terrain(ParamSet& set);
// Builds the terrain chosen in `values` (the stage's values; member "terrain").
std::unique_ptr<Terrain> make_terrain(const ParamValues& values);

// Terrain from an elevation grid (cells equal to grid.nodata are holes): the
// smoothed bicubic surface above.
std::unique_ptr<Terrain> make_grid_terrain(Grid elevation, std::string source);

}  // namespace talus::runout
