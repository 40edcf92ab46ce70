// The hand-off of the failed blocks to depth-integrated SPH run-out (seed
// pfe-ie-depth-integrated-sph-landslide §2.3): three rasters on one grid,
//   terrain      with a DEM: the DEM, but under the failed mass the top of
//                the blocks that hold (the slip surface), never above the
//                DEM; without one: the top of the blocks that hold wherever
//                one covers the cell centre;
//   thickness    the vertical thickness of the failed blocks over each cell,
//                averaged over 8 x 8 points of the cell (so its volume is the blocks' volume
//                to a fraction of a cell along the edges);
//   basal shear  the limit-state shear stress of the contacts on the slip
//                surface, interpolated to each cell centre by inverse distance
//                weighting with exponent 1 (seed eq. 30).
// Blocks are placed at the gravity-loaded state's poses.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "grid.hpp"
#include "limit_state.hpp"
#include "talus/blocks.hpp"

namespace talus::strength_reduction {

// The vertical extent [lo, hi] of a convex polyhedron at pose (x, q) over the
// plan point (px, py); false when the vertical line misses it.
bool vertical_extent(const Polyhedron& shape, const Vec3& x, const Quaternion& q, double px, double py, double& lo,
                     double& hi);

// sum_c values_c / d_c over sum_c 1 / d_c with d_c the plan distance (exponent
// m = 1); the value of a point the query sits on; nodata when there is none.
double inverse_distance(std::span<const Vec3> points, std::span<const double> values, double x, double y,
                        double nodata);

// Shepard's method with linear nodal functions (Franke & Nielson 1980): each
// point's value extended by the plane through it that fits its neighbours
// best (weights 1 / d^2 in plan; along their line when they are collinear),
// then weighted by 1 / d as above. Exact for a field linear in x and y, which
// plain inverse distance is not; it may leave the nodal range.
std::vector<Vec3> nodal_gradients(std::span<const Vec3> points, std::span<const double> values);
double inverse_distance_linear(std::span<const Vec3> points, std::span<const double> values,
                               std::span<const Vec3> gradients, double x, double y, double nodata);

// How the basal shear is interpolated from the slip-surface contacts.
enum class BasalShear { inverse_distance, inverse_distance_linear };

struct Handoff {
  runout::Grid terrain, thickness, basal_shear;
  double failed_volume = 0.0;  // of the released blocks, m^3
  double raster_volume = 0.0;  // sum of thickness x cell^2, m^3
  double density = 0.0;        // released mass / released volume, kg/m^3
  std::size_t slip_contacts = 0;  // contacts on the slip surface with an area (those the shear comes from)
};

// `layout`: the grid (the DEM's, or one over the blocks); `dem` may be null.
Handoff build_handoff(const BlockSet& blocks, const std::vector<Vec3>& position,
                      const std::vector<Quaternion>& orientation, const std::vector<std::uint8_t>& released,
                      const LimitState& limit, const runout::Grid& layout, const runout::Grid* dem,
                      BasalShear interpolation = BasalShear::inverse_distance);

}  // namespace talus::strength_reduction
