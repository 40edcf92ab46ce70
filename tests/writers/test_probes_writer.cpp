// Probes writer: Shepard interpolation of linear fields on a regular lattice
// is exact at the lattice's symmetry points in the interior, the wave gauge
// finds a flat free surface, integrals match their closed forms, and the CSV
// has the documented layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <iostream>
#include <sstream>

#include "../common/process.hpp"
#include "probes_writer.hpp"
#include "talus/error.hpp"
#include "world_fixture.hpp"

namespace talus {
namespace {

using test::TempDir;

struct Csv {
  std::vector<std::string> comments;
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) out.push_back(cell);
  return out;
}

Csv read_csv(const std::string& path) {
  Csv csv;
  std::stringstream in(test::read_file(path));
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("#", 0) == 0) {
      csv.comments.push_back(line);
    } else if (csv.header.empty()) {
      csv.header = split(line);
    } else {
      std::vector<double> row;
      for (const auto& c : split(line)) row.push_back(std::stod(c));
      csv.rows.push_back(row);
    }
  }
  return csv;
}

std::size_t column(const Csv& csv, const std::string& name) {
  for (std::size_t i = 0; i < csv.header.size(); ++i)
    if (csv.header[i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

double pressure_at(const Vec3& x) { return 1000.0 + 200.0 * x.x - 50.0 * x.y + 30.0 * x.z; }
Vec3 velocity_at(const Vec3& x) { return {1.0 + 2.0 * x.x, 3.0 * x.y - x.z, -x.x + 0.5}; }

// In the type the fields are kept in (float in a store in mixed precision).
void set_linear_fields(World& w) {
  auto x = w.fluid.position();
  w.fluid.visit_scalar("pressure", [&](auto p) {
    for (std::size_t i = 0; i < w.fluid.size(); ++i) p[i] = pressure_at(x[i]);
  });
  w.fluid.visit_vector("velocity", [&](auto v) {
    for (std::size_t i = 0; i < w.fluid.size(); ++i) v[i] = velocity_at(x[i]);
  });
}

std::string points_json(const std::vector<Vec3>& points, int dim) {
  std::string out = "[";
  for (std::size_t k = 0; k < points.size(); ++k) {
    out += k ? ", [" : "[";
    for (int a = 0; a < dim; ++a) out += (a ? ", " : "") + std::to_string(points[k][a]);
    out += "]";
  }
  return out + "]";
}

// Symmetry points of the lattice (every coordinate a node (i + 1/2) dp or a
// mid-point i dp) at least one support radius (2.6 dp) inside it, plus a
// control point near the edge where the kernel is truncated.
TEST(ProbesWriter, ShepardOfALinearFieldIsExactAtInteriorSymmetryPoints) {
  TempDir dir("probes-linear");
  World w;
  const double dp = 0.1;
  w.lo = {0, 0, 0};
  w.hi = {1.2, 1.2, 1.2};
  test::fill_lattice(w, 3, w.lo, 12, 12, 12, dp);
  set_linear_fields(w);
  const std::vector<Vec3> points{
      {0.35, 0.6, 0.45}, {0.6, 0.6, 0.6}, {0.55, 0.4, 0.75}, {0.8, 0.85, 0.3}, {0.05, 0.6, 0.6}};
  const std::string json =
      R"({"points": )" + points_json(points, 3) + R"(, "fields": ["pressure", "velocity", "velocity_mag"]})";
  writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(), json));
  writer.open(test::context_for(dir.str()), w);
  writer.write(w);
  writer.close(w);

  const Csv csv = read_csv(dir.file("scene_probes.csv"));
  ASSERT_EQ(csv.rows.size(), 1u);
  const auto& row = csv.rows[0];
  // In exact arithmetic the error is zero: V_j and W are equal for mirror
  // pairs, so sum_j V_j W (x_j - x) = 0 and the Shepard average of a + b.x_j
  // is a + b.x. What remains is rounding: ~74 neighbours, each term to 1e-16
  // relative, so 1e-12 of the field's scale is a 100x margin.
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const std::string P = "P" + std::to_string(k + 1);
    const Vec3 v = velocity_at(points[k]);
    EXPECT_NEAR(row[column(csv, P + "_pressure")], pressure_at(points[k]), 1e-12 * 1000.0) << P;
    EXPECT_NEAR(row[column(csv, P + "_velocity_x")], v.x, 1e-12 * 4.0) << P;
    EXPECT_NEAR(row[column(csv, P + "_velocity_y")], v.y, 1e-12 * 4.0) << P;
    EXPECT_NEAR(row[column(csv, P + "_velocity_z")], v.z, 1e-12 * 4.0) << P;
    EXPECT_NEAR(row[column(csv, P + "_velocity_mag")], norm(v), 1e-12 * 4.0) << P;
  }
  // Control: half a support from the edge the kernel is truncated and the
  // Shepard average is biased inwards by O(h b): the test above can fail.
  EXPECT_GT(std::abs(row[column(csv, "P5_pressure")] - pressure_at(points[4])), 1.0);
}

// A fluid kept in float (mixed precision) is read in the type it is kept in.
// The probes give the values of the same fluid in double to the rounding of
// the fields to float: 2^-24 of the largest value an average weighs (1240 Pa,
// 4 m/s), so 2e-4 Pa and 1e-6 m/s with a margin; the mass integral is the
// sum of the rounded masses, 2^-24 relative.
TEST(ProbesWriter, ReadsAFluidKeptInFloat) {
  auto probe = [](bool mixed) {
    TempDir dir(mixed ? "probes-float" : "probes-double");
    World w;
    w.fluid.set_mixed_precision(mixed);
    w.lo = {0, 0, 0};
    w.hi = {1.2, 1.2, 1.2};
    test::fill_lattice(w, 3, w.lo, 12, 12, 12, 0.1);
    set_linear_fields(w);
    EXPECT_EQ(is_single(w.fluid.info("pressure").type), mixed);
    EXPECT_EQ(is_single(w.fluid.info("velocity").type), mixed);
    writers::ProbesWriter writer(params_from_json(
        writers::ProbesWriter::describe(),
        R"({"points": [[0.6, 0.6, 0.6], [0.35, 0.6, 0.45]], "fields": ["pressure", "velocity"], "integrals": ["mass"]})"));
    writer.open(test::context_for(dir.str()), w);
    writer.write(w);
    writer.close(w);
    return read_csv(dir.file("scene_probes.csv"));
  };
  const Csv d = probe(false), f = probe(true);
  ASSERT_EQ(d.header, f.header);
  ASSERT_EQ(f.rows.size(), 1u);
  for (const std::string p : {"P1", "P2"}) {
    EXPECT_NEAR(f.rows[0][column(f, p + "_pressure")], d.rows[0][column(d, p + "_pressure")], 2e-4) << p;
    for (const char* axis : {"_velocity_x", "_velocity_y", "_velocity_z"})
      EXPECT_NEAR(f.rows[0][column(f, p + axis)], d.rows[0][column(d, p + axis)], 1e-6) << p << axis;
  }
  const double mass = d.rows[0][column(d, "mass")];
  EXPECT_NEAR(f.rows[0][column(f, "mass")], mass, mass * std::ldexp(1.0, -24));
}

TEST(ProbesWriter, WaveGaugeFindsAFlatFreeSurface) {
  TempDir dir("probes-gauge");
  World w;
  const double dp = 0.01, depth = 0.1;
  w.lo = {0, 0, 0};
  w.hi = {0.2, 0.3, 0};
  w.gravity = {0, -9.81, 0};
  test::fill_lattice(w, 2, w.lo, 20, 10, 1, dp);
  writers::ProbesWriter writer(
      params_from_json(writers::ProbesWriter::describe(),
                       R"({"gauges": [[0.1, 0.0], [0.07, 0.25]], "gauge_names": ["mid", "left"]})", 2));
  writer.open(test::context_for(dir.str()), w);
  writer.write(w);
  const Csv csv = read_csv(dir.file("scene_probes.csv"));
  ASSERT_EQ(csv.rows.size(), 1u);
  // The lattice fills [0, depth] exactly; phi = 0.5 at y = depth up to the
  // midpoint-rule error of the lattice sum of the half kernel, well below
  // 0.1 dp (measured: a few 1e-3 dp).
  std::cout << "gauge error: " << (csv.rows[0][column(csv, "mid_elevation")] - depth) / dp << " dp\n";
  EXPECT_NEAR(csv.rows[0][column(csv, "mid_elevation")], depth, 0.1 * dp);
  EXPECT_NEAR(csv.rows[0][column(csv, "left_elevation")], depth, 0.1 * dp);
}

// A 2D tank 0.4 m long of water to 0.1 m over sand to 0.05 m (materials water, sand).
void sand_under_water(World& w, double dp) {
  w.lo = {0, 0, 0};
  w.hi = {0.4, 0.3, 0};
  w.gravity = {0, -9.81, 0};
  w.materials = {{"water"}, {"sand"}};
  test::fill_lattice(w, 2, w.lo, 40, 10, 1, dp);
  const auto x = w.fluid.position();
  auto material = w.fluid.material();
  for (std::size_t i = 0; i < w.fluid.size(); ++i) material[i] = x[i].y < 0.05 ? 1 : 0;
}

// Bed gauges find the top of one material under another, and the bed's change
// between the first and the last row: sand 0.05 m deep under water to 0.1 m; the
// sand left of x = 0.2 sinks 0.02 m. Gauges 0.1 m apart (beyond the kernel's
// 2.6 dp support from the step): eroded = 0.02 * 0.1 (between B1 and B2) +
// 0.5 * 0.02 * 0.1 (B2 to B3) = 0.003 m^2 per metre, deposited none.
TEST(ProbesWriter, BedGaugesFindOneMaterialsSurfaceAndItsChange) {
  TempDir dir("probes-bed");
  World w;
  const double dp = 0.01;
  sand_under_water(w, dp);
  auto x = w.fluid.position();
  auto material = w.fluid.material();
  writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(),
                                                R"({"gauges": [[0.3, 0]], "gauge_names": ["W"],
                                                    "bed_gauges": [[0.05, 0], [0.15, 0], [0.25, 0], [0.35, 0]],
                                                    "bed_material": "sand", "integrals": [],
                                                    "material_masses": true})",
                                                2));
  EXPECT_EQ(writer.result_names(), (std::vector<std::string>{"bed_eroded_area", "bed_deposited_area"}));
  writer.open(test::context_for(dir.str()), w);
  writer.write(w);
  for (std::size_t i = 0; i < w.fluid.size(); ++i)
    if (material[i] == 1 && x[i].x < 0.2) x[i].y -= 0.02;
  w.time = 1.0;
  w.step = 1;
  writer.write(w);
  writer.close(w);
  const Csv csv = read_csv(dir.file("scene_probes.csv"));
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_NEAR(csv.rows[0][column(csv, "W_elevation")], 0.1, 0.1 * dp);
  for (const char* b : {"B1_bed", "B2_bed", "B3_bed", "B4_bed"}) EXPECT_NEAR(csv.rows[0][column(csv, b)], 0.05, 0.1 * dp);
  EXPECT_NEAR(csv.rows[1][column(csv, "B1_bed")], 0.03, 0.1 * dp);
  EXPECT_NEAR(csv.rows[1][column(csv, "B4_bed")], 0.05, 0.1 * dp);
  // Each phase's mass, the same on both rows (the sand moved, none was made or lost).
  const double sand = 0.4 * 0.05 * 1000.0, water = 0.4 * 0.05 * 1000.0;
  EXPECT_NEAR(csv.rows[0][column(csv, "mass_sand")], sand, 1e-9 * sand);
  EXPECT_NEAR(csv.rows[0][column(csv, "mass_water")], water, 1e-9 * water);
  EXPECT_EQ(csv.rows[1][column(csv, "mass_sand")], csv.rows[0][column(csv, "mass_sand")]);
  std::map<std::string, double> r;
  for (const auto& result : writer.results()) r[result.name] = result.number;
  EXPECT_NEAR(r["bed_eroded_area"], 0.003, 0.05 * dp * 0.1);
  EXPECT_NEAR(r["bed_deposited_area"], 0.0, 0.05 * dp * 0.1);
  EXPECT_TRUE(std::filesystem::exists(dir.file("scene_probes_results.json")));
  // A bed material the scene does not have is refused at the check.
  writers::ProbesWriter wrong(params_from_json(writers::ProbesWriter::describe(),
                                               R"({"bed_gauges": [[0.05, 0]], "bed_material": "gravel"})", 2));
  EXPECT_THROW(wrong.check(w), InputError);
}

// A tongue of water over an air gap (an overturning crest over the water it falls
// into): a surf gauge under it reads the tongue's top and the air below it; one
// beside it reads the flat surface and no air. Water to 0.1 m; the tongue from
// 0.14 to 0.17 m over x < 0.1 m: a 0.04 m gap between the lattice's particle
// edges (air_below finds it within a few gauge steps of the kernel's reach).
// The waves run along -x (offshore gauge at 0.28 m): the water moves at
// 0.2 m/s that way, the tongue at 0.5 m/s, one particle at the tongue's foot
// at 0.9 m/s but more than a kernel support below the tongue's surface.
// A 2D tank 0.3 m long of water to 0.1 m and a tongue from 0.14 to 0.17 m over
// x < 0.1 m; returns the number of the water's particles (the tongue's follow).
std::size_t tongue_over_water(World& w, double dp) {
  w.lo = {0, 0, 0};
  w.hi = {0.3, 0.3, 0};
  w.gravity = {0, -9.81, 0};
  test::fill_lattice(w, 2, w.lo, 30, 10, 1, dp);
  const std::size_t water = w.fluid.size();
  test::fill_lattice(w, 2, {0, 0.14, 0}, 10, 3, 1, dp);
  return water;
}

TEST(ProbesWriter, SurfGaugesFindTheAirUnderAnOverturningCrestAndItsSpeed) {
  TempDir dir("probes-air");
  World w;
  const double dp = 0.01;
  const std::size_t water = tongue_over_water(w, dp);
  auto velocity = w.fluid.vector("velocity");
  for (std::size_t i = 0; i < w.fluid.size(); ++i) velocity[i] = {i < water ? -0.2 : -0.5, 0.01, 0};
  velocity[water - 30 + 4] = {-0.9, 0, 0};  // the top row of the water at x = 0.045, under the tongue
  writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(),
                                                R"({"gauges": [[0.28, 0], [0.25, 0], [0.04, 0]], "gauge_names": ["OFF", "S2", "S1"],
                                                    "integrals": [],
                                                    "waves": {"offshore": "OFF", "surf": ["S2", "S1"]}})",
                                                2));
  writer.open(test::context_for(dir.str()), w);
  writer.write(w);
  const Csv csv = read_csv(dir.file("scene_probes.csv"));
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_NEAR(csv.rows[0][column(csv, "S1_elevation")], 0.17, 0.1 * dp);
  EXPECT_NEAR(csv.rows[0][column(csv, "S2_elevation")], 0.1, 0.1 * dp);
  // The gap between the surfaces phi = 0.5 finds: 0.14 - 0.10 = 0.04 m.
  EXPECT_NEAR(csv.rows[0][column(csv, "S1_air_below")], 0.04, 0.1 * dp);
  EXPECT_EQ(csv.rows[0][column(csv, "S2_air_below")], 0.0);
  // The fastest surface particle along -x; the offshore gauge records none.
  EXPECT_DOUBLE_EQ(csv.rows[0][column(csv, "S1_surface_u")], 0.5);
  EXPECT_DOUBLE_EQ(csv.rows[0][column(csv, "S2_surface_u")], 0.2);
  EXPECT_EQ(std::count(csv.header.begin(), csv.header.end(), "OFF_surface_u"), 0);
}

// The same tongue over an air gap, read as wire gauges: under the tongue the
// reading is the water's surface plus the tongue's wet thickness (0.1 + 0.03 m,
// each surface where phi = 0.5), beside it the flat surface, as the default
// reading gives it; a surf gauge still finds its air below the highest surface.
// A lone clump of splash high over the water adds its thickness, not its height.
TEST(ProbesWriter, WireGaugesAddOnlyTheWaterOnTheirLine) {
  World w;
  const double dp = 0.01;
  tongue_over_water(w, dp);
  test::fill_lattice(w, 2, {0.2, 0.25, 0}, 4, 2, 1, dp);  // splash: 0.02 m thick, 0.15 m over the water
  auto read = [&](const std::string& reading) {
    writers::ProbesWriter writer(params_from_json(
        writers::ProbesWriter::describe(),
        R"({"gauges": [[0.28, 0], [0.15, 0], [0.04, 0], [0.22, 0]], "gauge_names": ["OFF", "FLAT", "S1", "SPLASH"],
            "integrals": [], "waves": {"offshore": "OFF", "surf": ["S1"]}, "gauge_reading": ")" + reading + R"("})",
        2));
    TempDir out("probes-wire-" + reading);
    writer.open(test::context_for(out.str()), w);
    writer.write(w);
    return read_csv(out.file("scene_probes.csv"));
  };
  const Csv surface = read("surface"), wire = read("wire");
  ASSERT_EQ(wire.rows.size(), 1u);
  const auto& r = wire.rows[0];
  std::cout << "wire: under the tongue " << r[column(wire, "S1_elevation")] << " m, under the splash "
            << r[column(wire, "SPLASH_elevation")] << " m (surface reading "
            << surface.rows[0][column(surface, "SPLASH_elevation")] << " m)\n";
  EXPECT_NEAR(r[column(wire, "S1_elevation")], 0.13, 0.1 * dp);
  EXPECT_NEAR(r[column(wire, "S1_air_below")], 0.04, 0.1 * dp);
  EXPECT_NEAR(r[column(wire, "FLAT_elevation")], surface.rows[0][column(surface, "FLAT_elevation")], 1e-12);
  EXPECT_NEAR(r[column(wire, "FLAT_elevation")], 0.1, 0.1 * dp);
  // The splash clump's phi peaks below 1 (a kernel support is wider than it): its wet thickness is under its
  // 0.02 m, and the surface reading sits on top of it.
  EXPECT_NEAR(surface.rows[0][column(surface, "SPLASH_elevation")], 0.27, 0.5 * dp);
  EXPECT_GT(r[column(wire, "SPLASH_elevation")], 0.1 - 0.1 * dp);
  EXPECT_LT(r[column(wire, "SPLASH_elevation")], 0.12 + 0.1 * dp);
  EXPECT_NE(std::find_if(wire.comments.begin(), wire.comments.end(),
                         [](const std::string& c) { return c.find("wire reading") != std::string::npos; }),
            wire.comments.end());
}

// The waves' direction runs from the offshore gauge to the first surf gauge,
// and every surf gauge stands ahead of the offshore gauge.
TEST(ProbesWriter, SurfGaugesMustStandAheadOfTheOffshoreGauge) {
  World w;
  w.lo = {0, 0, 0};
  w.hi = {0.3, 0.3, 0};
  w.gravity = {0, -9.81, 0};
  test::fill_lattice(w, 2, w.lo, 30, 10, 1, 0.01);
  auto refused = [&](const char* json, const std::string& expected) {
    writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(), json, 2));
    try {
      writer.check(w);
      ADD_FAILURE() << "accepted " << json;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused(R"({"gauges": [[0.1, 0], [0.2, 0], [0.05, 0]], "gauge_names": ["OFF", "S1", "S2"],
              "waves": {"offshore": "OFF", "surf": ["S1", "S2"]}})",
          "/waves/surf: 'S2' is not ahead of the offshore gauge 'OFF' along the waves' direction");
  refused(R"({"gauges": [[0.05, 0], [0.05, 0.2]], "gauge_names": ["OFF", "S1"],
              "waves": {"offshore": "OFF", "surf": ["S1"]}})",
          "/waves/surf: the first surf gauge 'S1' stands on the offshore gauge's vertical line");
}

// The run-up line's highest wet point: a line rising through a flat surface at
// 0.1 m finds it within a gauge step; counting only the "sand" below, 0.05 m.
TEST(ProbesWriter, TheRunupLineFindsItsHighestWetPoint) {
  TempDir dir("probes-runup");
  World w;
  const double dp = 0.01;
  sand_under_water(w, dp);
  for (const char* only : {"", "sand"}) {
    const std::string extra = *only ? std::string(R"(, "runup_material": ")") + only + "\"" : "";
    writers::ProbesWriter writer(params_from_json(
        writers::ProbesWriter::describe(),
        R"({"runup_line": [[0.05, 0.02], [0.35, 0.22]], "integrals": [])" + extra + "}", 2));
    writer.open(test::context_for(dir.str()), w);
    writer.write(w);
    writer.close(w);
    const Csv csv = read_csv(dir.file("scene_probes.csv"));
    ASSERT_EQ(csv.rows.size(), 1u);
    EXPECT_NEAR(csv.rows[0][column(csv, "runup_elevation")], *only ? 0.05 : 0.1, 0.1 * dp) << only;
  }
}

// The gauge's elevation of one surface along gravity: the tank of the test
// above, with gravity along +y or along +x; elevations are coordinates.
double gauge_elevation(const std::string& name, Vec3 gravity, Vec3 lattice_lo, int nx, int ny, Vec3 hi,
                       const std::string& gauges) {
  TempDir dir(name);
  World w;
  w.lo = {0, 0, 0};
  w.hi = hi;
  w.gravity = gravity;
  test::fill_lattice(w, 2, lattice_lo, nx, ny, 1, 0.01);
  writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(), gauges, 2));
  writer.open(test::context_for(dir.str()), w);
  writer.write(w);
  const Csv csv = read_csv(dir.file("scene_probes.csv"));
  return csv.rows.at(0).at(column(csv, "G1_elevation"));
}

// Gauges measure along gravity, from the side it points away from: a tank
// lying along +x (surface at x = 0.2, water beyond) reads what the upright
// tank reads, mirrored, to round-off.
TEST(ProbesWriter, WaveGaugeMeasuresAlongGravity) {
  const double dp = 0.01;
  const double upright = gauge_elevation("probes-up", {0, -9.81, 0}, {0, 0, 0}, 20, 10, {0.2, 0.3, 0},
                                         R"({"gauges": [[0.1, 0.0]]})");
  const double lying = gauge_elevation("probes-lying", {9.81, 0, 0}, {0.2, 0, 0}, 10, 20, {0.3, 0.2, 0},
                                       R"({"gauges": [[0.0, 0.1]]})");
  EXPECT_NEAR(upright, 0.1, 0.1 * dp);
  EXPECT_NEAR(0.2 - lying, upright - 0.1, 1e-9 * dp);
  // Gravity along no axis needs the scene to say which axis is vertical.
  EXPECT_THROW(gauge_elevation("probes-oblique", {3.0, -9.0, 0}, {0, 0, 0}, 20, 10, {0.2, 0.3, 0},
                               R"({"gauges": [[0.1, 0.0]]})"),
               InputError);
  EXPECT_EQ(gauge_elevation("probes-stated", {3.0, -9.0, 0}, {0, 0, 0}, 20, 10, {0.2, 0.3, 0},
                            R"({"gauges": [[0.1, 0.0]], "vertical": "y"})"),
            upright);
}

// A gauge over a dry line reads NaN and says so, once.
TEST(ProbesWriter, DryGaugeWarnsOnce) {
  TempDir dir("probes-dry");
  World w;
  w.lo = {0, 0, 0};
  w.hi = {0.4, 0.3, 0};
  w.gravity = {0, -9.81, 0};
  test::fill_lattice(w, 2, w.lo, 20, 10, 1, 0.01);
  const char* gauges = R"({"gauges": [[0.1, 0.0], [0.35, 0.0]], "gauge_names": ["wet", "dry"]})";
  writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(), gauges, 2));
  writer.open(test::context_for(dir.str()), w);
  writer.write(w);
  w.time = 0.5;
  w.step = 1;
  writer.write(w);
  const Csv csv = read_csv(dir.file("scene_probes.csv"));
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_TRUE(std::isnan(csv.rows[1][column(csv, "dry_elevation")]));
  EXPECT_FALSE(std::isnan(csv.rows[1][column(csv, "wet_elevation")]));
  ASSERT_EQ(w.warnings.all().size(), 1u);
  EXPECT_NE(w.warnings.all()[0].find("gauge 'dry' at (0.35, 0) finds no free surface along y at t = 0 s"),
            std::string::npos)
      << w.warnings.all()[0];
}

TEST(ProbesWriter, IntegralsAndLayout) {
  TempDir dir("probes-integrals");
  World w;
  const double dp = 0.05;
  w.lo = {0, 0, 0};
  w.hi = {1, 1, 1};
  w.gravity = {0, 0, -9.81};
  test::fill_lattice(w, 3, w.lo, 6, 5, 4, dp);
  const Vec3 u{2.0, -1.0, 0.5};
  for (auto& v : w.fluid.vector("velocity")) v = u;
  writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(),
                                                R"({"points": [[0.1, 0.1, 0.1]], "point_names": ["A"],
          "integrals": ["mass", "kinetic_energy", "potential_energy", "particles"]})"));
  writer.open(test::context_for(dir.str()), w);
  for (int k = 0; k < 3; ++k) {
    w.step = k;
    w.time = 0.1 * k;
    writer.write(w);
  }
  writer.close(w);
  const Csv csv = read_csv(dir.file("scene_probes.csv"));
  ASSERT_FALSE(csv.comments.empty());
  EXPECT_EQ(csv.comments[0].rfind("# talus probes: scene scene", 0), 0u);
  EXPECT_EQ(csv.header,
            (std::vector<std::string>{"time", "step", "A_pressure", "A_velocity_x", "A_velocity_y", "A_velocity_z",
                                      "mass", "kinetic_energy", "potential_energy", "particles"}));
  ASSERT_EQ(csv.rows.size(), 3u);
  const double n = 6 * 5 * 4, m = 1000.0 * dp * dp * dp;
  const auto& row = csv.rows[2];
  EXPECT_EQ(row[0], 0.2);
  EXPECT_EQ(row[1], 2.0);
  EXPECT_NEAR(row[column(csv, "mass")], n * m, 1e-12 * n * m);
  EXPECT_NEAR(row[column(csv, "kinetic_energy")], 0.5 * n * m * norm2(u), 1e-12 * n * m * norm2(u));
  // Potential energy m g z summed over the lattice: mean height 2 dp.
  EXPECT_NEAR(row[column(csv, "potential_energy")], n * m * 9.81 * 2.0 * dp, 1e-12 * n * m * 9.81);
  EXPECT_EQ(row[column(csv, "particles")], n);
  EXPECT_EQ(row[column(csv, "A_velocity_x")], 2.0);  // Shepard reproduces a constant
}

// A fluid layer at uniform pressure p0 on a flat floor of wall particles,
// periodic along x: the fluid presses on the floor with p0 per unit length.
// In the continuum limit -sum_a sum_j V_a V_j 2 p0 grad_a W is exactly p0 A
// (grad of the fill fraction integrated across the interface); on a lattice
// the sum falls short by the kernel's discretisation error, which shrinks as
// h/dp grows: measured 2.6 % at h = 1.3 dp and 0.08 % at h = 2 dp. The test
// pins both bounds and the convergence; the sideways force cancels by symmetry.
constexpr double kFloorDp = 0.02, kFloorP0 = 1000.0, kFloorLength = 1.0;

// Fluid rows 10 dp deep over a floor of 6 wall rows (0.12 m, deeper than the kernel support 4 dp), periodic along
// x over kFloorLength, fluid and wall particles at the pressure p(x).
template <class Pressure>
void fluid_on_floor(World& w, double h_over_dp, Pressure pressure) {
  const double dp = kFloorDp;
  w.lo = {0, -0.2, 0};
  w.hi = {kFloorLength, 0.5, 0};
  w.periodic = {true, false, false};
  w.bodies.resize(2);
  w.bodies[0].name = "water";
  w.bodies[1].name = "floor";
  w.bodies[1].kind = BodyKind::wall;
  w.bodies[1].dp = dp;
  test::fill_lattice(w, 2, {0, 0, 0}, 50, 10, 1, dp);
  w.h = h_over_dp * dp;
  w.kernel = KernelTable(test::TestWendlandC2{}, 2, w.h);
  for (std::size_t i = 0; i < w.fluid.size(); ++i) w.fluid.scalar("pressure")[i] = pressure(w.fluid.position()[i]);
  test::require_host_fields(w.boundary);
  const int nx = 50, layers = 6;
  w.boundary.append(nx * layers);
  for (int k = 0; k < layers; ++k)
    for (int i = 0; i < nx; ++i) {
      const std::size_t a = k * nx + i;
      w.boundary.position()[a] = {(i + 0.5) * dp, -(k + 0.5) * dp, 0.0};
      w.boundary.scalar("density")[a] = 1000.0;
      w.boundary.scalar("mass")[a] = 1000.0 * dp * dp;
      w.boundary.scalar("pressure")[a] = pressure(w.boundary.position()[a]);
      w.boundary.body()[a] = 1;
    }
}

double floor_force_fraction(double h_over_dp, const std::string& folder) {
  World w;
  const double p0 = kFloorP0, length = kFloorLength;
  fluid_on_floor(w, h_over_dp, [&](const Vec3&) { return p0; });
  writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(),
                                                R"({"wall_forces": ["floor"], "integrals": ["particles"]})", 2));
  writer.open(test::context_for(folder), w);
  writer.write(w);
  writer.close(w);
  const Csv csv = read_csv(folder + "/scene_probes.csv");
  EXPECT_EQ(csv.rows.size(), 1u);
  EXPECT_NEAR(csv.rows[0][column(csv, "floor_fx")], 0.0, 1e-9 * p0 * length);
  return csv.rows[0][column(csv, "floor_fy")] / (-p0 * length);
}

TEST(ProbesWriter, WallForceOfAUniformPressureIsPressureTimesArea) {
  TempDir dir("probes-wall");
  const double coarse = floor_force_fraction(1.3, dir.str());
  const double fine = floor_force_fraction(2.0, dir.str());
  std::cout << "wall force / (p0 L): " << coarse << " (h = 1.3 dp), " << fine << " (h = 2 dp)\n";
  EXPECT_NEAR(coarse, 1.0, 0.04);
  EXPECT_NEAR(fine, 1.0, 0.01);
  EXPECT_LT(std::abs(fine - 1.0), std::abs(coarse - 1.0));

  // Not a wall body: an input error naming the wall bodies.
  World w;
  w.lo = {0, 0, 0};
  w.hi = {1, 1, 0};
  w.bodies.resize(2);
  w.bodies[0].name = "water";
  w.bodies[1].name = "floor";
  w.bodies[1].kind = BodyKind::wall;
  test::fill_lattice(w, 2, {0, 0, 0}, 3, 3, 1, 0.1);
  writers::ProbesWriter bad(params_from_json(writers::ProbesWriter::describe(), R"({"wall_forces": ["water"]})", 2));
  try {
    bad.open(test::context_for(dir.str()), w);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wall bodies: floor"), std::string::npos) << e.what();
  }
}

// Wall pressure sensors on the floor of the set-up above, the fluid's pressure
// now rising linearly along the wall, p = p0 (1 + x / L): a sensor reads the
// normal force on the wall particles behind its patch over the patch's area,
// i.e. the local wall pressure, with the lattice error of the force (2.6 % at
// h = 1.3 dp, above) and the patch's own averaging (exact for a linear p).
// A sensor off the wall, or normals that do not match, are input errors.
TEST(ProbesWriter, WallSensorReadsTheLocalWallPressure) {
  TempDir dir("probes-sensor");
  World w;
  const double p0 = kFloorP0;
  auto pressure = [&](const Vec3& x) { return p0 * (1.0 + x.x / kFloorLength); };
  fluid_on_floor(w, 1.3, pressure);
  // Patches of one wall column each (the default size, dp), away from the periodic seam where p jumps back.
  writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(), R"({
      "wall_sensors": [[0.31, 0.0], [0.71, 0.0]], "wall_sensor_normals": [[0, 1], [0, 2]],
      "wall_sensor_names": ["S1", "S2"], "integrals": ["particles"]})", 2));
  writer.open(test::context_for(dir.str()), w);
  writer.write(w);
  writer.close(w);
  const Csv csv = read_csv(dir.str() + "/scene_probes.csv");
  ASSERT_EQ(csv.rows.size(), 1u);
  const double s1 = csv.rows[0][column(csv, "S1_pressure")], s2 = csv.rows[0][column(csv, "S2_pressure")];
  std::cout << "wall sensors / local pressure: " << s1 / pressure({0.31, 0, 0}) << ", " << s2 / pressure({0.71, 0, 0})
            << "\n";
  EXPECT_NEAR(s1 / pressure({0.31, 0, 0}), 1.0, 0.04);
  EXPECT_NEAR(s2 / pressure({0.71, 0, 0}), 1.0, 0.04);
  EXPECT_GT(s2, s1 + 0.3 * p0);  // follows the gradient: 0.4 p0 apart
  bool described = false;
  for (const auto& c : csv.comments) described = described || c.find("# wall sensors") != std::string::npos;
  EXPECT_TRUE(described);

  auto expect_input_error = [&](const std::string& json, const std::string& pointer) {
    try {
      writers::ProbesWriter bad(params_from_json(writers::ProbesWriter::describe(), json, 2));
      bad.open(test::context_for(dir.str()), w);
      ADD_FAILURE() << "no error for " << json;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(pointer), std::string::npos) << e.what();
    }
  };
  expect_input_error(R"({"wall_sensors": [[0.5, 0.1]], "wall_sensor_normals": [[0, 1]]})", "/wall_sensors");
  expect_input_error(R"({"wall_sensors": [[0.5, 0.0]], "wall_sensor_normals": [[0, -1]]})", "/wall_sensors");
  expect_input_error(R"({"wall_sensors": [[0.5, 0.0]]})", "/wall_sensor_normals");
  expect_input_error(R"({"wall_sensors": [[0.5, 0.0]], "wall_sensor_normals": [[0, 0]]})", "/wall_sensor_normals");
}

TEST(ProbesWriter, BadPointsAndFieldsAreInputErrors) {
  TempDir dir("probes-errors");
  World w;
  w.lo = {0, 0, 0};
  w.hi = {1, 1, 1};
  test::fill_lattice(w, 3, w.lo, 3, 3, 3, 0.1);
  auto expect_input_error = [&](const std::string& json, const std::string& pointer) {
    try {
      writers::ProbesWriter writer(params_from_json(writers::ProbesWriter::describe(), json));
      writer.open(test::context_for(dir.str()), w);
      ADD_FAILURE() << "no error for " << json;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(pointer), std::string::npos) << e.what();
    }
  };
  expect_input_error(R"({"points": [[2, 0.5, 0.5]]})", "/points");
  expect_input_error(R"({"points": [[0.5, 0.5, 0.5]], "fields": ["vorticity"]})", "/fields");
  expect_input_error(R"({"points": [[0.5, 0.5, 0.5]], "fields": ["body"]})", "/fields");
  expect_input_error(R"({"points": [[0.5, 0.5, 0.5]], "point_names": ["a", "b"]})", "/point_names");
}

}  // namespace
}  // namespace talus
