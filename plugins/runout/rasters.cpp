#include "rasters.hpp"

#include <algorithm>
#include <cmath>

#include "esri_ascii.hpp"

namespace talus::runout {

void RunoutRasters::configure(const Grid& layout, const Terrain& terrain, double threshold) {
  threshold_ = threshold;
  cos_ = layout;
  cos_.nodata = -9999.0;
  cos_.value.assign(layout.value.size(), 1.0);
  for (int r = 0; r < cos_.nrows; ++r)
    for (int c = 0; c < cos_.ncols; ++c) {
      const Vec3 g = terrain.gradient(cos_.x_of(c), cos_.y_of(r));
      const double cosine = 1.0 / std::sqrt(1.0 + g.x * g.x + g.y * g.y);
      cos_.at(c, r) = std::isfinite(cosine) ? cosine : 1.0;  // undefined terrain: no flow reaches it
    }
  h_ = hv_ = peak_h_ = peak_v_ = cos_;
  std::fill(h_.value.begin(), h_.value.end(), 0.0);
  hv_.value = peak_h_.value = peak_v_.value = h_.value;
  arrival_ = cos_;
  std::fill(arrival_.value.begin(), arrival_.value.end(), arrival_.nodata);
}

void RunoutRasters::record(std::span<const Vec3> pos, std::span<const double> volume,
                           std::span<const double> smoothing, std::span<const double> speed,
                           const VariableKernel& kernel, double time) {
  std::fill(h_.value.begin(), h_.value.end(), 0.0);
  std::fill(hv_.value.begin(), hv_.value.end(), 0.0);
  const double inv = 1.0 / h_.cell;
  // Scatter: each particle adds V W(r, l) to the cells inside its support.
  // Serial on purpose: the scatter would race, and it runs every few steps.
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const double l = smoothing[i], radius = kernel.support * l;
    const int c0 = std::max(0, static_cast<int>(std::ceil((pos[i].x - radius - h_.x0) * inv)));
    const int c1 = std::min(h_.ncols - 1, static_cast<int>(std::floor((pos[i].x + radius - h_.x0) * inv)));
    const int r0 = std::max(0, static_cast<int>(std::ceil((pos[i].y - radius - h_.y0) * inv)));
    const int r1 = std::min(h_.nrows - 1, static_cast<int>(std::floor((pos[i].y + radius - h_.y0) * inv)));
    for (int r = r0; r <= r1; ++r) {
      const double dy = h_.y_of(r) - pos[i].y;
      for (int c = c0; c <= c1; ++c) {
        const double dx = h_.x_of(c) - pos[i].x;
        const double w = volume[i] * kernel.w(std::sqrt(dx * dx + dy * dy), l);
        h_.at(c, r) += w;
        hv_.at(c, r) += w * speed[i];
      }
    }
  }
  for (std::size_t k = 0; k < h_.value.size(); ++k) {
    const double hv = h_.value[k];
    const double v = hv > 0.0 ? hv_.value[k] / hv : 0.0;
    h_.value[k] = hv * cos_.value[k];  // vertical -> slope-normal thickness
    peak_h_.value[k] = std::max(peak_h_.value[k], h_.value[k]);
    if (h_.value[k] > threshold_) {
      peak_v_.value[k] = std::max(peak_v_.value[k], v);
      if (arrival_.value[k] == arrival_.nodata) arrival_.value[k] = time;
    }
  }
}

std::vector<std::string> RunoutRasters::write(const std::string& prefix, const Terrain& terrain) const {
  std::vector<std::string> files;
  auto put = [&](const char* name, const Grid& g) {
    files.push_back(prefix + "_" + name + ".asc");
    write_esri_ascii(files.back(), g);
  };
  put("peak_thickness", peak_h_);
  put("peak_velocity", peak_v_);
  put("deposit_thickness", h_);
  put("arrival_time", arrival_);
  // A DEM is written as read (the flow's smoothed surface departs from it by
  // millimetres where it is curved); analytic terrain is sampled.
  if (const Grid* dem = terrain.grid()) {
    put("elevation", *dem);
    return files;
  }
  Grid z = cos_;
  for (int r = 0; r < z.nrows; ++r)
    for (int c = 0; c < z.ncols; ++c) z.at(c, r) = terrain.elevation(z.x_of(c), z.y_of(r));
  put("elevation", z);
  return files;
}

}  // namespace talus::runout
