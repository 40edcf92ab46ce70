#include "terrain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>
#include <numbers>

#include "esri_ascii.hpp"
#include "geotiff.hpp"
#include "talus/error.hpp"

namespace talus::runout {
namespace {

double tan_deg(double deg) { return std::tan(deg * std::numbers::pi / 180.0); }

// Loops a final surface's inline formulas over all positions.
template <class Surface>
void sample_all(const Surface& s, std::span<const Vec3> pos, double* z, Vec3* grad, Hessian* hess) {
#pragma omp parallel for schedule(static) if (pos.size() > 4096)  // cheap per point: fork/join costs more below
  for (std::size_t i = 0; i < pos.size(); ++i) {
    z[i] = s.Surface::elevation(pos[i].x, pos[i].y);
    grad[i] = s.Surface::gradient(pos[i].x, pos[i].y);
    hess[i] = s.Surface::hessian(pos[i].x, pos[i].y);
  }
}

// Z = z0 - tan(theta) x.
class InclinedPlane final : public Terrain {
 public:
  InclinedPlane(double slope_deg, double z0) : s_(tan_deg(slope_deg)), z0_(z0), deg_(slope_deg) {}
  double elevation(double x, double) const override { return z0_ - s_ * x; }
  Vec3 gradient(double, double) const override { return {-s_, 0.0, 0.0}; }
  Hessian hessian(double, double) const override { return {}; }
  void sample(std::span<const Vec3> pos, double* z, Vec3* g, Hessian* h) const override {
    sample_all(*this, pos, z, g, h);
  }
  std::string summary() const override { return "inclined plane " + std::to_string(deg_) + " deg"; }

 private:
  double s_, z0_, deg_;
};

// Slope tan(theta) down to the foot at x_t, flat (Z = 0) beyond. With a
// transition length L > 0 the slope eases linearly to zero over
// [x_t - L/2, x_t + L/2] (a parabolic blend, continuous gradient, curvature
// tan(theta) / L inside it). With L = 0 the break is sharp: no curvature, so
// friction sees no centrifugal load there (the flow turns without loss).
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
  Hessian hessian(double x, double) const override {
    if (x >= b_ || x <= a_) return {};
    return {s_ / L_, 0.0, 0.0};
  }
  void sample(std::span<const Vec3> pos, double* z, Vec3* g, Hessian* h) const override {
    sample_all(*this, pos, z, g, h);
  }
  std::string summary() const override {
    return "plane " + std::to_string(deg_) + " deg with a flat run-out zone beyond x = " +
           std::to_string(0.5 * (a_ + b_)) + (L_ > 0.0 ? ", transition " + std::to_string(L_) + " m" : ", sharp break");
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
  Hessian hessian(double, double) const override { return {0.0, 0.0, 2.0 * k_}; }
  void sample(std::span<const Vec3> pos, double* z, Vec3* g, Hessian* h) const override {
    sample_all(*this, pos, z, g, h);
  }
  std::string summary() const override { return "parabolic channel " + std::to_string(deg_) + " deg"; }

 private:
  double s_, yc_, k_, deg_;
};

// Uniform cubic B-spline basis on [0, 1]: weights of the control points
// k - 1 .. k + 2 for a point at k + t, and their first and second derivatives.
struct SplineWeights {
  double w[4], d[4], s[4];
  explicit SplineWeights(double t) {
    const double u = 1.0 - t, t2 = t * t, t3 = t2 * t;
    w[0] = u * u * u / 6.0;
    w[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    w[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    w[3] = t3 / 6.0;
    d[0] = -0.5 * u * u;
    d[1] = 1.5 * t2 - 2.0 * t;
    d[2] = -1.5 * t2 + t + 0.5;
    d[3] = 0.5 * t2;
    s[0] = u;
    s[1] = 3.0 * t - 2.0;
    s[2] = 1.0 - 3.0 * t;
    s[3] = t;
  }
};

// The DEM as the smoothed bicubic surface described in terrain.hpp.
class GridTerrain final : public Terrain {
 public:
  GridTerrain(Grid z, std::string source) : z_(std::move(z)), source_(std::move(source)) {
    if (z_.ncols < 2 || z_.nrows < 2)
      throw InputError("error: " + source_ + ": a DEM needs at least 2 x 2 cells (has " + std::to_string(z_.ncols) +
                       " x " + std::to_string(z_.nrows) + ")");
    const int nc = z_.ncols, nr = z_.nrows, wc = nc + 2 * ghost;
    control_.assign(static_cast<std::size_t>(wc) * (nr + 2 * ghost), 0.0);
    valid_.assign(control_.size(), 0);
    for (int r = 0; r < nr; ++r)
      for (int c = 0; c < nc; ++c) {
        const double v = z_.at(c, r);
        const bool ok = v != z_.nodata && std::isfinite(v);
        control(c, r) = ok ? v : 0.0;
        valid(c, r) = ok;
      }
    // Ghost rings: the line through the two nearest values (columns, then rows,
    // so the corners extrapolate the extrapolated columns).
    auto extend = [&](int n, auto&& point, auto&& ok) {
      for (int k = 1; k <= ghost; ++k) {
        point(-k) = (1.0 + k) * point(0) - k * point(1);
        ok(-k) = ok(0) && ok(1);
        point(n - 1 + k) = (1.0 + k) * point(n - 1) - k * point(n - 2);
        ok(n - 1 + k) = ok(n - 1) && ok(n - 2);
      }
    };
    for (int r = 0; r < nr; ++r)
      extend(nc, [&](int c) -> double& { return control(c, r); }, [&](int c) -> std::uint8_t& { return valid(c, r); });
    for (int c = -ghost; c < nc + ghost; ++c)
      extend(nr, [&](int r) -> double& { return control(c, r); }, [&](int r) -> std::uint8_t& { return valid(c, r); });
    // A span [k, k + 1] is defined when its 4 x 4 control points are.
    span_ok_.assign(static_cast<std::size_t>(nc + 1) * (nr + 1), 0);
    for (int j = -1; j < nr; ++j)
      for (int i = -1; i < nc; ++i) {
        bool ok = true;
        for (int b = -1; b <= 2 && ok; ++b)
          for (int a = -1; a <= 2 && ok; ++a) ok = valid(i + a, j + b);
        span_ok_[static_cast<std::size_t>(j + 1) * (nc + 1) + (i + 1)] = ok;
      }
  }

  double elevation(double x, double y) const override { return eval<0>(x, y).z; }
  Vec3 gradient(double x, double y) const override { return eval<1>(x, y).grad; }
  Hessian hessian(double x, double y) const override { return eval<2>(x, y).hess; }
  bool defined(double x, double y) const override { return span_ok(locate(x, y)); }
  void sample(std::span<const Vec3> pos, double* z, Vec3* g, Hessian* h) const override {
#pragma omp parallel for schedule(static) if (pos.size() > 4096)
    for (std::size_t i = 0; i < pos.size(); ++i) {
      const Point p = eval<2>(pos[i].x, pos[i].y);
      z[i] = p.z;
      g[i] = p.grad;
      h[i] = p.hess;
    }
  }
  const Grid* grid() const override { return &z_; }
  std::string summary() const override {
    return "DEM " + source_ + " (" + std::to_string(z_.ncols) + " x " + std::to_string(z_.nrows) + ", cell " +
           std::to_string(z_.cell) + " m, smoothed bicubic surface)";
  }

 private:
  static constexpr int ghost = 2;
  struct Span {
    int i, j;
    double tx, ty;
  };
  struct Point {
    double z = 0.0;
    Vec3 grad{};
    Hessian hess{};
  };

  double& control(int c, int r) { return control_[index(c, r)]; }
  double control(int c, int r) const { return control_[index(c, r)]; }
  std::uint8_t& valid(int c, int r) { return valid_[index(c, r)]; }
  std::size_t index(int c, int r) const {
    return static_cast<std::size_t>(r + ghost) * (z_.ncols + 2 * ghost) + (c + ghost);
  }
  // The span holding (x, y), in [-1, n - 1] per axis (the ghosts reach half a
  // cell beyond the outer cell centres and more; further out, the edge span).
  Span locate(double x, double y) const {
    // A non-finite point (a particle gone NaN within the step) has no span;
    // floor() of it would not fit the int.
    if (!std::isfinite(x) || !std::isfinite(y)) return {-2, -2, 0.0, 0.0};
    const double u = std::clamp((x - z_.x0) / z_.cell, -1.0, static_cast<double>(z_.ncols));
    const double v = std::clamp((y - z_.y0) / z_.cell, -1.0, static_cast<double>(z_.nrows));
    const int i = std::min(static_cast<int>(std::floor(u)), z_.ncols - 1);
    const int j = std::min(static_cast<int>(std::floor(v)), z_.nrows - 1);
    return {i, j, u - i, v - j};
  }
  bool span_ok(const Span& s) const {
    if (s.i < -1) return false;
    return span_ok_[static_cast<std::size_t>(s.j + 1) * (z_.ncols + 1) + (s.i + 1)] != 0;
  }
  // Elevation and, up to `order`, its derivatives.
  template <int order>
  Point eval(double x, double y) const {
    const Span sp = locate(x, y);
    Point p;
    if (!span_ok(sp)) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return {nan, {nan, nan, 0.0}, {nan, nan, nan}};
    }
    const SplineWeights wx(sp.tx), wy(sp.ty);
    const double inv = 1.0 / z_.cell;
    for (int b = 0; b < 4; ++b) {
      double row = 0.0, row_d = 0.0, row_s = 0.0;
      for (int a = 0; a < 4; ++a) {
        const double c = control(sp.i - 1 + a, sp.j - 1 + b);
        row += wx.w[a] * c;
        if constexpr (order >= 1) row_d += wx.d[a] * c;
        if constexpr (order >= 2) row_s += wx.s[a] * c;
      }
      p.z += wy.w[b] * row;
      if constexpr (order >= 1) {
        p.grad.x += wy.w[b] * row_d * inv;
        p.grad.y += wy.d[b] * row * inv;
      }
      if constexpr (order >= 2) {
        p.hess.xx += wy.w[b] * row_s * inv * inv;
        p.hess.xy += wy.d[b] * row_d * inv * inv;
        p.hess.yy += wy.s[b] * row * inv * inv;
      }
    }
    return p;
  }

  Grid z_;
  std::vector<double> control_;      // DEM values with two ghost rings
  std::vector<std::uint8_t> valid_;  // per control point: not no-data
  std::vector<std::uint8_t> span_ok_;
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

  ParamSet dem{"dem", "digital elevation model: ESRI ASCII grid (.asc), or GeoTIFF (.tif) when built with GDAL; no-data "
                      "cells allowed (the surface is undefined within two cells of one); see docs/runout.md"};
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
    if (ends_with(file, ".tif") || ends_with(file, ".tiff"))
      return v.read_file("file", [](const std::string& f) { return make_grid_terrain(read_geotiff(f, true), f); });
    if (!ends_with(file, ".asc"))
      v.fail("file", "'" + file + "' is not a DEM this build reads; allowed: .asc (ESRI ASCII grid), .tif (GeoTIFF, "
                     "with GDAL)");
    return v.read_file("file", [](const std::string& f) { return make_grid_terrain(read_esri_ascii(f, true), f); });
  }
  values.fail("terrain", "unknown terrain '" + kind + "'");
}

}  // namespace talus::runout
