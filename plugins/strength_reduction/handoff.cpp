#include "handoff.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus::strength_reduction {
namespace {

// Sub-samples per cell side for the cell-averaged thickness.
constexpr int samples = 8;

}  // namespace

bool vertical_extent(const Polyhedron& shape, const Vec3& x, const Quaternion& q, double px, double py, double& lo,
                     double& hi) {
  lo = -std::numeric_limits<double>::infinity();
  hi = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < shape.faces.size(); ++f) {
    const Vec3 n = rotate(q, shape.normals[f]);
    const double rest = shape.offsets[f] + dot(n, x) - n.x * px - n.y * py;  // n_z z <= rest
    if (std::abs(n.z) < 1e-12) {
      if (rest < 0.0) return false;
    } else if (n.z > 0.0) {
      hi = std::min(hi, rest / n.z);
    } else {
      lo = std::max(lo, rest / n.z);
    }
  }
  return lo < hi;
}

double inverse_distance(std::span<const Vec3> points, std::span<const double> values, double x, double y,
                        double nodata) {
  double weights = 0.0, sum = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double d = std::hypot(points[k].x - x, points[k].y - y);
    if (d < 1e-12) return values[k];
    weights += 1.0 / d;
    sum += values[k] / d;
  }
  return weights > 0.0 ? sum / weights : nodata;
}

std::vector<Vec3> nodal_gradients(std::span<const Vec3> points, std::span<const double> values) {
  std::vector<Vec3> gradients(points.size(), Vec3{0.0, 0.0, 0.0});
  for (std::size_t k = 0; k < points.size(); ++k) {
    double axx = 0.0, axy = 0.0, ayy = 0.0, bx = 0.0, by = 0.0;
    for (std::size_t j = 0; j < points.size(); ++j) {
      const double dx = points[j].x - points[k].x, dy = points[j].y - points[k].y, d2 = dx * dx + dy * dy;
      if (d2 < 1e-24) continue;
      const double w = 1.0 / d2, df = values[j] - values[k];
      axx += w * dx * dx;
      axy += w * dx * dy;
      ayy += w * dy * dy;
      bx += w * dx * df;
      by += w * dy * df;
    }
    const double trace = axx + ayy, det = axx * ayy - axy * axy;
    if (!(trace > 0.0)) continue;  // no neighbour: a constant
    if (det > 1e-10 * trace * trace)
      gradients[k] = {(ayy * bx - axy * by) / det, (axx * by - axy * bx) / det, 0.0};
    else  // collinear neighbours, A = s u u^T and b = t u: the slope t / s along u
      gradients[k] = {bx / trace, by / trace, 0.0};
  }
  return gradients;
}

double inverse_distance_linear(std::span<const Vec3> points, std::span<const double> values,
                               std::span<const Vec3> gradients, double x, double y, double nodata) {
  double weights = 0.0, sum = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double dx = x - points[k].x, dy = y - points[k].y, d = std::hypot(dx, dy);
    if (d < 1e-12) return values[k];
    weights += 1.0 / d;
    sum += (values[k] + gradients[k].x * dx + gradients[k].y * dy) / d;
  }
  return weights > 0.0 ? sum / weights : nodata;
}

Handoff build_handoff(const BlockSet& b, const std::vector<Vec3>& position, const std::vector<Quaternion>& orientation,
                      const std::vector<std::uint8_t>& released, const LimitState& limit, const runout::Grid& layout,
                      const runout::Grid* dem, BasalShear interpolation) {
  Handoff h;
  h.terrain = h.thickness = h.basal_shear = layout;
  const double nodata = layout.nodata;
  std::fill(h.thickness.value.begin(), h.thickness.value.end(), 0.0);
  std::fill(h.basal_shear.value.begin(), h.basal_shear.value.end(), nodata);

  // The slip surface: contacts between a released block and one that holds.
  std::vector<Vec3> points;
  std::vector<double> stress;
  for (std::size_t c = 0; c < limit.point.size(); ++c) {
    if (released[limit.block_a[c]] == released[limit.block_b[c]] || !(limit.area[c] > 0.0)) continue;
    points.push_back(limit.point[c]);
    stress.push_back(limit.shear_force[c] / limit.area[c]);
  }
  h.slip_contacts = points.size();
  const bool linear = interpolation == BasalShear::inverse_distance_linear;
  const std::vector<Vec3> gradients = linear ? nodal_gradients(points, stress) : std::vector<Vec3>{};

  double mass = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (released[i]) {
      h.failed_volume += b.volume[i];
      mass += b.mass[i];
    }
  h.density = h.failed_volume > 0.0 ? mass / h.failed_volume : 0.0;

  // Plan bounds of each block, so that a cell tests only the blocks above it.
  std::vector<Vec3> lo(b.size(), Vec3{1e300, 1e300, 0.0}), hi(b.size(), Vec3{-1e300, -1e300, 0.0});
  for (std::size_t i = 0; i < b.size(); ++i)
    for (const Vec3& v : b.shape[i].vertices) {
      const Vec3 x = position[i] + rotate(orientation[i], v);
      lo[i] = {std::min(lo[i].x, x.x), std::min(lo[i].y, x.y), 0.0};
      hi[i] = {std::max(hi[i].x, x.x), std::max(hi[i].y, x.y), 0.0};
    }
  const double cell = layout.cell;
  std::vector<std::size_t> near;
  for (int r = 0; r < layout.nrows; ++r)
    for (int col = 0; col < layout.ncols; ++col) {
      const double x = layout.x_of(col), y = layout.y_of(r), half = 0.5 * cell;
      near.clear();
      for (std::size_t i = 0; i < b.size(); ++i)
        if (x + half >= lo[i].x && x - half <= hi[i].x && y + half >= lo[i].y && y - half <= hi[i].y)
          near.push_back(i);
      // With a DEM, the blocks replace it only under the failed mass (the
      // slip surface), and never rise above it: a tessellation's fixed walls
      // and base reach beyond the ground and are not terrain.
      double top = -std::numeric_limits<double>::infinity(), z0 = 0.0, z1 = 0.0;
      bool under_failed = false;
      for (const std::size_t i : near) {
        if (!vertical_extent(b.shape[i], position[i], orientation[i], x, y, z0, z1)) continue;
        if (released[i])
          under_failed = true;
        else
          top = std::max(top, z1);
      }
      double& z = h.terrain.at(col, r);
      if (dem)
        z = under_failed && std::isfinite(top) ? std::min(top, dem->at(col, r)) : dem->at(col, r);
      else
        z = std::isfinite(top) ? top : nodata;

      double column = 0.0;
      for (int sy = 0; sy < samples; ++sy)
        for (int sx = 0; sx < samples; ++sx) {
          const double px = x + ((sx + 0.5) / samples - 0.5) * cell, py = y + ((sy + 0.5) / samples - 0.5) * cell;
          for (const std::size_t i : near)
            if (released[i] && vertical_extent(b.shape[i], position[i], orientation[i], px, py, z0, z1))
              column += z1 - z0;
        }
      column /= samples * samples;
      h.thickness.at(col, r) = column;
      h.raster_volume += column * cell * cell;
      if (column > 0.0)
        h.basal_shear.at(col, r) = linear ? inverse_distance_linear(points, stress, gradients, x, y, nodata)
                                          : inverse_distance(points, stress, x, y, nodata);
    }
  return h;
}

}  // namespace talus::strength_reduction
