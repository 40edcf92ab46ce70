#include "terrain.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "esri_ascii.hpp"
#include "geotiff.hpp"
#include "talus/error.hpp"

namespace talus::runout {
namespace {

double tan_deg(double deg) { return std::tan(deg * std::numbers::pi / 180.0); }

// Loops a final surface's inline formulas over all positions.
template <class Surface>
void sample_all(const Surface& s, std::span<const Vec3> pos, double* z, Vec3* grad) {
#pragma omp parallel for schedule(static) if (pos.size() > 4096)  // cheap per point: fork/join costs more below
  for (std::size_t i = 0; i < pos.size(); ++i) {
    z[i] = s.Surface::elevation(pos[i].x, pos[i].y);
    grad[i] = s.Surface::gradient(pos[i].x, pos[i].y);
  }
}

// Z = z0 - tan(theta) x.
class InclinedPlane final : public Terrain {
 public:
  InclinedPlane(double slope_deg, double z0) : s_(tan_deg(slope_deg)), z0_(z0), deg_(slope_deg) {}
  double elevation(double x, double) const override { return z0_ - s_ * x; }
  Vec3 gradient(double, double) const override { return {-s_, 0.0, 0.0}; }
  void sample(std::span<const Vec3> pos, double* z, Vec3* g) const override { sample_all(*this, pos, z, g); }
  std::string summary() const override { return "inclined plane " + std::to_string(deg_) + " deg"; }

 private:
  double s_, z0_, deg_;
};

// Slope tan(theta) down to the foot at x_t, flat (Z = 0) beyond. With a
// transition length L > 0 the slope eases linearly to zero over
// [x_t - L/2, x_t + L/2] (a parabolic blend, continuous gradient).
class PlaneWithRunout final : public Terrain {
 public:
  PlaneWithRunout(double slope_deg, double foot, double length)
      : s_(tan_deg(slope_deg)), a_(foot - 0.5 * length), b_(foot + 0.5 * length), L_(length), deg_(slope_deg) {}
  double elevation(double x, double) const override {
    if (x >= b_) return 0.0;
    if (x <= a_) return s_ * (0.5 * (a_ + b_) - x);
    const double d = b_ - x;
    return s_ * d * d / (2.0 * L_);
  }
  Vec3 gradient(double x, double) const override {
    if (x >= b_) return {};
    if (x <= a_) return {-s_, 0.0, 0.0};
    return {-s_ * (b_ - x) / L_, 0.0, 0.0};
  }
  void sample(std::span<const Vec3> pos, double* z, Vec3* g) const override { sample_all(*this, pos, z, g); }
  std::string summary() const override {
    return "plane " + std::to_string(deg_) + " deg with a flat run-out zone beyond x = " +
           std::to_string(0.5 * (a_ + b_));
  }

 private:
  double s_, a_, b_, L_, deg_;
};

// Z = -tan(theta) x + H ((y - y_c) / w)^2: a parabolic channel along +x.
class Channel final : public Terrain {
 public:
  Channel(double slope_deg, double axis, double half_width, double bank)
      : s_(tan_deg(slope_deg)), yc_(axis), k_(bank / (half_width * half_width)), deg_(slope_deg) {}
  double elevation(double x, double y) const override { return -s_ * x + k_ * (y - yc_) * (y - yc_); }
  Vec3 gradient(double, double y) const override { return {-s_, 2.0 * k_ * (y - yc_), 0.0}; }
  void sample(std::span<const Vec3> pos, double* z, Vec3* g) const override { sample_all(*this, pos, z, g); }
  std::string summary() const override { return "parabolic channel " + std::to_string(deg_) + " deg"; }

 private:
  double s_, yc_, k_, deg_;
};

class GridTerrain final : public Terrain {
 public:
  GridTerrain(Grid z, std::string source) : z_(std::move(z)), source_(std::move(source)) {
    gx_ = z_;
    gy_ = z_;
    const int nc = z_.ncols, nr = z_.nrows;
    for (int r = 0; r < nr; ++r)
      for (int c = 0; c < nc; ++c) {
        const int c0 = std::max(c - 1, 0), c1 = std::min(c + 1, nc - 1);
        const int r0 = std::max(r - 1, 0), r1 = std::min(r + 1, nr - 1);
        gx_.at(c, r) = (z_.at(c1, r) - z_.at(c0, r)) / ((c1 - c0) * z_.cell);
        gy_.at(c, r) = (z_.at(c, r1) - z_.at(c, r0)) / ((r1 - r0) * z_.cell);
      }
  }
  double elevation(double x, double y) const override { return z_.bilinear(x, y); }
  Vec3 gradient(double x, double y) const override { return {gx_.bilinear(x, y), gy_.bilinear(x, y), 0.0}; }
  void sample(std::span<const Vec3> pos, double* z, Vec3* g) const override { sample_all(*this, pos, z, g); }
  const Grid* grid() const override { return &z_; }
  std::string summary() const override {
    return "DEM " + source_ + " (" + std::to_string(z_.ncols) + " x " + std::to_string(z_.nrows) + ", cell " +
           std::to_string(z_.cell) + " m)";
  }

 private:
  Grid z_, gx_, gy_;
  std::string source_;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  std::string tail = s.substr(s.size() - suffix.size());
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == suffix;
}

}  // namespace

void declare_terrain(ParamSet& set) {
  ParamSet plane{"plane", "inclined plane Z = elevation - tan(slope) x, descending towards +x"};
  plane.real("slope").unit("deg").min(0.0).less_than(90.0).doc("inclination theta");
  plane.real("elevation").unit("m").default_value(0.0).doc("elevation at x = 0");

  ParamSet runout{"plane_runout", "inclined plane down to a foot at x = foot, flat (Z = 0) beyond"};
  runout.real("slope").unit("deg").min(0.0).less_than(90.0).doc("inclination of the slope");
  runout.real("foot").unit("m").doc("x of the slope foot (where the run-out zone starts)");
  runout.real("transition_length").unit("m").min(0.0).default_value(0.0)
      .doc("length over which the slope eases to flat (0: sharp break)");

  ParamSet channel{"channel", "parabolic channel along +x: Z = -tan(slope) x + bank_height ((y - axis) / half_width)^2"};
  channel.real("slope").unit("deg").min(0.0).less_than(90.0).doc("inclination of the channel axis");
  channel.real("axis").unit("m").default_value(0.0).doc("y of the channel axis");
  channel.real("half_width").unit("m").greater_than(0.0).doc("half width at which the banks reach bank_height");
  channel.real("bank_height").unit("m").min(0.0).doc("bank height above the axis at y = axis +- half_width");

  ParamSet dem{"dem", "digital elevation model: ESRI ASCII grid (.asc), or GeoTIFF (.tif) when built with GDAL"};
  dem.path("file").doc("DEM file, relative to the scene file");

  set.one_of("terrain")
      .alternative("plane", plane)
      .alternative("plane_runout", runout)
      .alternative("channel", channel)
      .alternative("dem", dem)
      .doc("the terrain Z(x, y) under the flow");
}

std::unique_ptr<Terrain> make_grid_terrain(Grid elevation, std::string source) {
  return std::make_unique<GridTerrain>(std::move(elevation), std::move(source));
}

std::unique_ptr<Terrain> make_terrain(const ParamValues& values) {
  const std::string& kind = values.alternative("terrain");
  const ParamValues& v = values.alternative_values("terrain");
  if (kind == "plane") return std::make_unique<InclinedPlane>(v.real("slope"), v.real("elevation"));
  if (kind == "plane_runout")
    return std::make_unique<PlaneWithRunout>(v.real("slope"), v.real("foot"), v.real("transition_length"));
  if (kind == "channel")
    return std::make_unique<Channel>(v.real("slope"), v.real("axis"), v.real("half_width"), v.real("bank_height"));
  if (kind == "dem") {
    const std::string& file = v.string("file");
    if (ends_with(file, ".tif") || ends_with(file, ".tiff")) return make_grid_terrain(read_geotiff(file), file);
    if (!ends_with(file, ".asc"))
      v.fail("file", "'" + file + "' is not a DEM this build reads; allowed: .asc (ESRI ASCII grid), .tif (GeoTIFF, "
                     "with GDAL)");
    return make_grid_terrain(read_esri_ascii(file), file);
  }
  values.fail("terrain", "unknown terrain '" + kind + "'");
}

}  // namespace talus::runout
