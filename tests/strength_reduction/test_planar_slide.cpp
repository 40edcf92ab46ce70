// Strength reduction on the seed's planar slide through `talus run`: the safety
// factor against the closed form for three slab thicknesses, cohesion only,
// friction only, a softer joint and fixed joints (gate 1 %, the issue's); the per-trial
// table; the same factor for the slope turned and moved far away, and for
// the slab cut in clumped pieces on bases cut apart; and a restart that
// continues the search exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include "planar_slide_scene.hpp"
#include "process.hpp"

namespace fs = std::filesystem;
using namespace talus::test;

namespace {

struct Vec3Like {
  double x, y, z;
};

void expect_closed_form(const SlabJoint& joint, const std::string& name) {
  const FactorRun r = run_scene(planar_slide(joint), name);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double exact = closed_form(joint);
  std::printf("%s: F_s = %.4f, closed form %.4f (%+.3f %%), bracket [%.4f, %.4f]\n", name.c_str(), r.safety_factor,
              exact, 100.0 * (r.safety_factor / exact - 1.0), r.holds, r.fails);
  EXPECT_NEAR(r.safety_factor / exact, 1.0, 0.01);
  EXPECT_LE(r.holds, exact);  // the joint model adds no error the bisection can see
  EXPECT_GE(r.fails, exact);
}

// Rows of a CSV without the last `drop` columns.
std::vector<std::string> rows(const std::string& path, int drop) {
  std::istringstream in(read_file(path));
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) {
    for (int k = 0; k < drop; ++k) line = line.substr(0, line.rfind(','));
    out.push_back(line);
  }
  return out;
}

}  // namespace

TEST(PlanarSlide, SafetyFactorMatchesTheClosedFormForThreeThicknesses) {
  expect_closed_form({.thickness = 4.330127018922193}, "thin");
  expect_closed_form({.thickness = 8.660254037844386}, "seed");
  expect_closed_form({.thickness = 17.32050807568877}, "thick");
}

TEST(PlanarSlide, FixedJointsGiveTheClosedFormToo) {
  // The rigid-block-spring joints (the base face kept from the start, no contact search): the slab's four springs
  // on the slip plane, failure by collapse only.
  nlohmann::json scene = planar_slide({});
  scene["pipeline"][0]["dda"] = {{"joints", "initial_faces"}};
  const FactorRun r = run_scene(scene, "fixed_joints");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double exact = closed_form({});
  std::printf("fixed joints: F_s = %.4f, closed form %.4f (%+.3f %%)\n", r.safety_factor, exact,
              100.0 * (r.safety_factor / exact - 1.0));
  EXPECT_NEAR(r.safety_factor / exact, 1.0, 0.01);
  EXPECT_LE(r.holds, exact);
  EXPECT_GE(r.fails, exact);
}

TEST(PlanarSlide, CohesionOnlyAndFrictionOnlyMatchTheirClosedForms) {
  expect_closed_form({.thickness = 1.0, .friction = 0.0}, "cohesion_only");      // F = 1.0401
  expect_closed_form({.cohesion = 0.0, .friction = 40.0}, "friction_only");      // F = tan 40 / tan 30 = 1.4534
  expect_closed_form({.stiffness = 1e9}, "softer_joint");
}

TEST(PlanarSlide, ASlabStartingARoundingErrorAboveItsJointKeepsItsCohesion) {
  // 1 um above the slip plane (within the contact margin): the joint has no tensile strength, and without an
  // unbreakable gravity-loaded state its bond broke before the springs took the weight (F_s 1.0007: friction only).
  nlohmann::json scene = planar_slide({});
  for (auto& v : scene["bodies"][1]["shape"]["polyhedron"]["vertices"]) v[2] = v[2].get<double>() + 1e-6;
  const FactorRun r = run_scene(scene, "lifted");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NEAR(r.safety_factor / closed_form({}), 1.0, 0.01);
}

namespace {

// The scene with every vertex and monitor turned by `degrees` about the vertical and then moved by `shift`.
nlohmann::json moved(nlohmann::json scene, double degrees, Vec3Like shift) {
  const double c = std::cos(degrees * M_PI / 180.0), s = std::sin(degrees * M_PI / 180.0);
  auto move = [&](nlohmann::json& p) {
    const double x = p[0].get<double>(), y = p[1].get<double>();
    p = {c * x - s * y + shift.x, s * x + c * y + shift.y, p[2].get<double>() + shift.z};
  };
  for (auto& body : scene["bodies"])
    for (auto& v : body["shape"]["polyhedron"]["vertices"]) move(v);
  for (auto& m : scene["pipeline"][0]["monitors"]) move(m);
  const double reach = 60.0;
  scene["domain"]["min"] = {shift.x - reach, shift.y - reach, shift.z - reach};
  scene["domain"]["max"] = {shift.x + reach, shift.y + reach, shift.z + reach};
  return scene;
}

}  // namespace

TEST(PlanarSlide, TheFactorDoesNotDependOnWhereTheSlopeLiesOrWhichWayItFaces) {
  // Turned about the vertical and moved far from the origin the slope is the same slope: F_s within the
  // bisection's resolution of the original (the trials' outcomes, not the geometry's rounding, set it).
  const FactorRun original = run_scene(planar_slide({}), "frame_original");
  ASSERT_EQ(original.exit_code, 0) << original.output;
  const struct {
    const char* name;
    double degrees;
    Vec3Like shift;
  } frames[] = {{"frame_turned", 37.0, {0.0, 0.0, 0.0}}, {"frame_far", 0.0, {5e4, -3e4, 2e3}},
                {"frame_turned_far", 123.0, {-2e4, 7e4, -500.0}}};
  for (const auto& f : frames) {
    const FactorRun r = run_scene(moved(planar_slide({}), f.degrees, f.shift), f.name);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::printf("%s: F_s = %.4f (original %.4f)\n", f.name, r.safety_factor, original.safety_factor);
    EXPECT_NEAR(r.safety_factor, original.safety_factor, 0.5 * 0.005 + 1e-9) << f.name;
    EXPECT_NEAR(r.safety_factor / closed_form({}), 1.0, 0.01) << f.name;
  }
}

TEST(PlanarSlide, ASlabCutInClumpedPiecesHasTheFactorOfTheWholeSlab) {
  // The slab cut across the slope into pieces of one clump, each on its own
  // base, the bases 2 cm apart (so no piece touches another's base): the
  // joint area and the load are the whole slab's, and so is F_s.
  const nlohmann::json whole = planar_slide({});
  for (int pieces : {2, 3}) {
    nlohmann::json s = whole;
    s["bodies"] = nlohmann::json::array();
    const double width = 4.0 / pieces, gap = 0.01;
    for (int k = 0; k < pieces; ++k) {
      nlohmann::json base = whole["bodies"][0], slab = whole["bodies"][1];
      const double y0 = k * width, y1 = (k + 1) * width;
      for (auto& v : base["shape"]["polyhedron"]["vertices"])
        v[1] = v[1].get<double>() < 2.0 ? (k == 0 ? -1.0 : y0 + gap) : (k == pieces - 1 ? 5.0 : y1 - gap);
      for (auto& v : slab["shape"]["polyhedron"]["vertices"]) v[1] = v[1].get<double>() < 2.0 ? y0 : y1;
      base["name"] = "base_" + std::to_string(k);
      slab["name"] = "slab_" + std::to_string(k);
      slab["clump"] = "slab";
      s["bodies"].insert(s["bodies"].begin() + k, base);
      s["bodies"].push_back(slab);
    }
    const FactorRun r = run_scene(s, "clumped_" + std::to_string(pieces));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const double exact = closed_form({});
    std::printf("%d clumped pieces: F_s = %.4f, closed form %.4f (%+.3f %%)\n", pieces, r.safety_factor, exact,
                100.0 * (r.safety_factor / exact - 1.0));
    EXPECT_NEAR(r.safety_factor / exact, 1.0, 0.01);
    const std::string summary = read_file(r.directory + ".summary.json");
    EXPECT_NE(summary.find(std::to_string(pieces) + " block(s) released (100 % of the free mass)"), std::string::npos)
        << summary;
  }
}

TEST(PlanarSlide, AClumpBlockRestingOnItsClumpAloneIsNotRefused) {
  // A 1 m block on the slab, clumped with it: it touches nothing but its own
  // clump (no contacts are sought inside a clump), yet it does not fall.
  nlohmann::json s = planar_slide({});
  const double c = std::sqrt(3.0) / 2.0, sn = 0.5, x0 = 6.0, z0 = 10.0 - x0 * sn / c;
  s["bodies"][1]["clump"] = "slab";
  nlohmann::json rider =
      prism_block("rider", {{x0, z0}, {x0 + c, z0 - sn}, {x0 + c + sn, z0 - sn + c}, {x0 + sn, z0 + c}}, false);
  rider["density"] = 1960.0;
  rider["clump"] = "slab";
  s["bodies"].push_back(rider);
  const FactorRun r = run_scene(s, "clump_rider");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The rider adds 1 m^3 of weight over the slab's 692.8 m^3: the factor moves by well under 1 %.
  std::printf("slab with a clumped rider: F_s = %.4f (closed form without it %.4f)\n", r.safety_factor,
              closed_form({}));
  EXPECT_NEAR(r.safety_factor / closed_form({}), 1.0, 0.01);
}

TEST(PlanarSlide, TheTrialTableShowsHoldingJointsStickingAndFailingOnesSlipping) {
  const FactorRun r = run_scene(planar_slide({}), "table");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto table = rows(r.directory + "/strength_reduction.csv", 0);
  ASSERT_GE(table.size(), 3u);
  EXPECT_EQ(table[0].rfind("trial,factor,outcome,steps,ratio,", 0), 0u) << table[0];
  EXPECT_EQ(table[1].rfind("0,elastic,stable,", 0), 0u) << table[1];
  int stable = 0, failed = 0;
  for (std::size_t k = 2; k < table.size(); ++k) {
    std::vector<std::string> cell;
    std::istringstream line(table[k]);
    for (std::string c; std::getline(line, c, ',');) cell.push_back(c);
    ASSERT_GE(cell.size(), 15u);
    // contacts, open, closed, slip are columns 10..13; the slab rests on 4 contact points.
    EXPECT_EQ(cell[10], "4");
    if (cell[2] == "stable") {
      ++stable;
      EXPECT_EQ(cell[13], "0") << table[k];
    } else {
      ++failed;
      EXPECT_EQ(cell[13], "4") << table[k];
      EXPECT_EQ(cell[8], "1") << "slip path " << table[k];
    }
  }
  EXPECT_GT(stable, 1);
  EXPECT_GT(failed, 1);
  EXPECT_TRUE(fs::exists(r.directory + "/strength_reduction_limit_state.h5"));
}

namespace {

// The search restarted from its first checkpoint writes the same trial table and factor.
void expect_restart_exact(const nlohmann::json& scene, const std::string& name) {
  nlohmann::json s = scene;
  s["checkpoint"] = {{"every", 0.3}, {"keep", 5}};
  const FactorRun whole = run_scene(s, name + "_whole");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  std::vector<fs::path> checkpoints;
  for (const auto& e : fs::directory_iterator(whole.directory))
    if (e.path().extension() == ".checkpoint") checkpoints.push_back(e.path());
  std::sort(checkpoints.begin(), checkpoints.end());
  ASSERT_GE(checkpoints.size(), 2u);
  const FactorRun resumed = run_scene(s, name + "_resumed", "--restart " + checkpoints.front().string());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(resumed.safety_factor, whole.safety_factor);
  // Every column but the wall time is the same.
  EXPECT_EQ(rows(resumed.directory + "/strength_reduction.csv", 1), rows(whole.directory + "/strength_reduction.csv", 1));
}

}  // namespace

TEST(PlanarSlide, ARestartContinuesTheSearchExactly) { expect_restart_exact(planar_slide({}), "restart"); }

TEST(PlanarSlide, ARestartWithMassScaledBodiesContinuesExactly) {
  // A 1 m boulder resting on the slab: two free bodies of unequal frequency, so mass scaling gives them different
  // inertia, which the restart must rebuild as it was.
  nlohmann::json scene = planar_slide({});
  const double c = std::sqrt(3.0) / 2.0, s = 0.5, x0 = 6.0, z0 = 10.0 - x0 * s / c;
  scene["bodies"].push_back(
      prism_block("boulder", {{x0, z0}, {x0 + c, z0 - s}, {x0 + c + s, z0 - s + c}, {x0 + s, z0 + c}}, false));
  expect_restart_exact(scene, "restart_scaled");
}

