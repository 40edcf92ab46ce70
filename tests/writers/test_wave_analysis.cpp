// Wave analysis on analytic records: zero up-crossing heights and periods of
// sampled sine and skewed (second-harmonic) waves, the breaker numbers and
// classes by hand values, and the probes writer's "waves" section reading a
// gauge file, and the crest speed against the fastest surface particle of a
// travelling wave.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <filesystem>
#include <map>
#include <numbers>
#include <vector>

#include "../common/process.hpp"
#include "breaker_analysis.hpp"
#include "crest_kinematics.hpp"
#include "probes_writer.hpp"
#include "talus/error.hpp"
#include "wave_analysis.hpp"
#include "world_fixture.hpp"

namespace talus {
namespace {

using writers::zero_up_crossing;

// eta(t) = level + a cos(theta) + b cos(2 theta), theta = 2 pi t / T - 1 (not
// starting on a crossing), sampled every T / per_wave.
struct Record {
  std::vector<double> t, eta;
};
Record waves(double level, double a, double b, double period, int per_wave, int count) {
  Record r;
  for (int k = 0; k <= per_wave * count; ++k) {
    const double t = period * k / per_wave, theta = 2.0 * std::numbers::pi * t / period - 1.0;
    r.t.push_back(t);
    r.eta.push_back(level + a * std::cos(theta) + b * std::cos(2.0 * theta));
  }
  return r;
}

TEST(WaveAnalysis, ASampledSineGivesItsHeightAndPeriodWithinOnePercent) {
  const Record r = waves(0.11, 0.01, 0.0, 1.7, 40, 20);
  const auto s = zero_up_crossing(r.t, r.eta, 3.0);
  // 40 samples a wave miss the crest by at most 1 - cos(pi/40) = 0.3 %.
  EXPECT_NEAR(s.height, 0.02, 0.01 * 0.02);
  EXPECT_NEAR(s.max_height, 0.02, 0.01 * 0.02);
  EXPECT_NEAR(s.period, 1.7, 0.01 * 1.7);
  EXPECT_NEAR(s.mean_level, 0.11, 1e-4);
  // From t = 3 s to 34 s: 31 s / 1.7 s = 18.2 waves, 17 or 18 complete between crossings.
  EXPECT_GE(s.waves, 17u);
  EXPECT_LE(s.waves, 18u);
}

TEST(WaveAnalysis, ASkewedWaveGivesCrestToTroughNotTwiceTheAmplitude) {
  // a cos + 0.3 a cos 2: crest 1.3 a, trough -0.71667 a (at cos theta = -1/1.2): H = 2.01667 a.
  const Record r = waves(0.0, 0.02, 0.006, 0.8, 80, 12);
  const auto s = zero_up_crossing(r.t, r.eta, 0.0);
  EXPECT_NEAR(s.height, 2.0166667 * 0.02, 0.01 * 2.0166667 * 0.02);
  EXPECT_NEAR(s.period, 0.8, 0.01 * 0.8);
}

TEST(WaveAnalysis, DrySamplesAreSkippedAndNoCompleteWaveIsNaN) {
  Record r = waves(0.1, 0.01, 0.0, 1.0, 40, 10);
  for (std::size_t k = 0; k < r.eta.size(); k += 7) r.eta[k] = std::nan("");
  const auto s = zero_up_crossing(r.t, r.eta, 0.0);
  EXPECT_NEAR(s.height, 0.02, 0.02 * 0.02);
  EXPECT_NEAR(s.period, 1.0, 0.01);
  const Record short_record = waves(0.1, 0.01, 0.0, 1.0, 40, 1);
  const auto none = zero_up_crossing(short_record.t, short_record.eta, 0.5);
  EXPECT_EQ(none.waves, 0u);
  EXPECT_TRUE(std::isnan(none.height));
  EXPECT_TRUE(std::isnan(none.period));
}

// Run-up: a record that climbs 0.03 m above the still level once a wave (the
// crest half of a sine) gives the highest and the mean of the waves' highest.
TEST(WaveAnalysis, RunupIsTheHighestWetPointAboveTheStillLevel) {
  test::TempDir dir("waves-runup");
  const Record off = waves(0.11, 0.01, 0.0, 2.0, 40, 10);
  std::string csv = "time,step,OFF_elevation,S1_elevation,S1_air_below,S1_surface_u,runup_elevation\n";
  for (std::size_t k = 0; k < off.t.size(); ++k) {
    const double phase = 2.0 * std::numbers::pi * off.t[k] / 2.0 - 1.0;
    csv += std::to_string(off.t[k]) + "," + std::to_string(k) + "," + std::to_string(off.eta[k]) + "," +
           std::to_string(off.eta[k]) + ",0,0," + std::to_string(0.11 + 0.03 * std::max(0.0, std::cos(phase))) + "\n";
  }
  test::write_file(dir.file("probes.csv"), csv);
  const auto params = params_from_json(writers::ProbesWriter::describe(),
                                       R"({"gauges": [[1, 0], [2, 0]], "gauge_names": ["OFF", "S1"], "runup_line": [[1, 0], [2, 1]],
                                           "waves": {"offshore": "OFF", "surf": ["S1"], "from": 2}})",
                                       2);
  writers::BreakerAnalysis analysis(params.object("waves"), {"OFF", "S1"}, true);
  analysis.place(params.object("waves"), {{1, 0, 0}, {2, 0, 0}}, 1);
  std::map<std::string, WriterResult> r;
  for (const auto& result : analysis.analyse(dir.file("probes.csv"), 9.81)) r[result.name] = result;
  // 40 rows a wave miss the top by at most 0.03 (1 - cos(pi/40)) = 1e-4 m; the still level is the record's mean.
  EXPECT_NEAR(r["runup_max"].number, 0.03, 2e-4);
  EXPECT_NEAR(r["runup_mean"].number, 0.03, 2e-4);
}

TEST(WaveAnalysis, LinearWavelengthByTheDispersionRelation) {
  // T = 1 s, d = 0.2 m: k = 5.1825681 (omega^2 = g k tanh kd solved by fixed-point iteration to 1e-15).
  EXPECT_NEAR(writers::linear_wavelength(1.0, 0.2, 9.81), 2.0 * std::numbers::pi / 5.182568147220004, 1e-12);
  // Deep water: g T^2 / 2 pi; shallow water: T sqrt(g d) (1 - (kd)^2 / 6), kd = 0.0665 at T = 10 s, d = 0.11 m.
  EXPECT_NEAR(writers::linear_wavelength(1.0, 100.0, 9.81), 9.81 / (2.0 * std::numbers::pi), 1e-12);
  const double shallow = 10.0 * std::sqrt(9.81 * 0.11);
  EXPECT_NEAR(writers::linear_wavelength(10.0, 0.11, 9.81), shallow * (1.0 - 0.0665 * 0.0665 / 6.0), 2e-4 * shallow);
  EXPECT_TRUE(std::isnan(writers::linear_wavelength(std::nan(""), 0.11, 9.81)));
  EXPECT_TRUE(std::isnan(writers::linear_wavelength(1.0, 0.0, 9.81)));
}

TEST(WaveAnalysis, BreakerNumbersAndClassesByHand) {
  // T = 2 s: L0 = 9.81 * 4 / (2 pi) = 6.245240 m; phi = 20 deg, H = 0.05 m:
  // xi = tan 20 / sqrt(0.05 / 6.245240) = 4.067761; H0 = 0.04 m, d_w = 0.11 m, f = 0.5 Hz:
  // Fn = (0.04 / 6.245240) * 0.11 * 0.5 / sqrt(9.81 / tan 20) = 6.785346e-5.
  const auto n = writers::breaker_numbers(0.05, 0.04, 2.0, 20.0, 0.11, 9.81);
  EXPECT_NEAR(n.wavelength, 6.245240, 1e-6);
  EXPECT_NEAR(n.iribarren, 4.067761, 1e-6);
  EXPECT_NEAR(n.froude, 6.785346e-5, 1e-11);
  EXPECT_EQ(n.type, "surging_or_collapsing");
  EXPECT_EQ(writers::breaker_type(2.01), "surging_or_collapsing");
  EXPECT_EQ(writers::breaker_type(2.0), "plunging");
  EXPECT_EQ(writers::breaker_type(0.4), "plunging");
  EXPECT_EQ(writers::breaker_type(0.39), "spilling");
  EXPECT_EQ(writers::breaker_type(std::nan("")), "unknown");
}

// A progressive wave, eta = level + a cos(2 pi (t - x / c) / T - 1) at the
// gauge at x, sampled every T / per_wave from t = 0; the gauge's surface speed
// is u_crest while its surface is above the level, 0 otherwise.
struct Gauge {
  std::vector<double> eta, u;
};
Gauge passing_wave(double x, double level, double a, double c, double period, double u_crest, int per_wave, int count) {
  Gauge g;
  for (int k = 0; k <= per_wave * count; ++k) {
    const double t = period * k / per_wave, theta = 2.0 * std::numbers::pi * (t - x / c) / period - 1.0;
    g.eta.push_back(level + a * std::cos(theta));
    g.u.push_back(std::cos(theta) > 0.0 ? u_crest : 0.0);
  }
  return g;
}

TEST(WaveAnalysis, TheCrestSpeedAndTheFastestSurfaceParticleOfEachWave) {
  // c = 1.5 m/s between gauges 0.37 m apart (a delay of 4.93 samples), T = 2 s, 40 samples a wave.
  const double c = 1.5, period = 2.0;
  const Record clock = waves(0.0, 0.0, 0.0, period, 40, 10);
  const Gauge before = passing_wave(1.0, 0.11, 0.01, c, period, 0.0, 40, 10),
              here = passing_wave(1.37, 0.11, 0.012, c, period, 1.2 * c, 40, 10);
  const auto stats = zero_up_crossing(clock.t, here.eta, 2.0);
  const auto crest = writers::crest_kinematics(clock.t, before.eta, here.eta, here.u, stats, 0.37, 9.81);
  EXPECT_EQ(crest.waves, stats.waves);
  EXPECT_NEAR(crest.crest_speed, c, 0.01 * c);
  EXPECT_DOUBLE_EQ(crest.particle_speed, 1.2 * c);
  EXPECT_NEAR(crest.ratio, 1.2, 0.012);
  EXPECT_EQ(crest.not_travelling, 0u);
  // The crest time: the vertex of the parabola through the highest sample and its neighbours.
  const double crest_at = 1.37 / c + period * (1.0 / (2.0 * std::numbers::pi));
  EXPECT_NEAR(std::remainder(crest.time - crest_at, period), 0.0, 0.002 * period);
  // A parabola's samples give its vertex exactly, unevenly spaced too.
  const std::vector<double> t = {0.0, 0.3, 0.5}, eta = {1.0 - 0.16, 1.0 - 0.01, 1.0 - 0.01};  // 1 - (t - 0.4)^2
  EXPECT_NEAR(writers::crest_time(t, eta, 1), 0.4, 1e-12);
  // A crest slower than sqrt(g H) (0.2 m/s against sqrt(9.81 * 0.024) = 0.485 m/s) is no travelling wave's.
  const Gauge slow_before = passing_wave(1.0, 0.11, 0.01, 0.2, period, 0.0, 40, 10),
              slow_here = passing_wave(1.05, 0.11, 0.012, 0.2, period, 1.0, 40, 10);
  const auto slow_stats = zero_up_crossing(clock.t, slow_here.eta, 2.0);
  const auto swash = writers::crest_kinematics(clock.t, slow_before.eta, slow_here.eta, slow_here.u, slow_stats, 0.05, 9.81);
  EXPECT_EQ(swash.waves, 0u);
  EXPECT_EQ(swash.not_travelling, slow_stats.waves);
  EXPECT_TRUE(std::isnan(swash.ratio));
  // At 0.5 m/s it is.
  const Gauge fast_here = passing_wave(1.05, 0.11, 0.012, 0.5, period, 1.0, 40, 10),
              fast_before = passing_wave(1.0, 0.11, 0.01, 0.5, period, 0.0, 40, 10);
  EXPECT_EQ(writers::crest_kinematics(clock.t, fast_before.eta, fast_here.eta, fast_here.u, slow_stats, 0.05, 9.81).waves,
            slow_stats.waves);
  // A standing wave (in phase at both gauges) has no crest speed.
  const Gauge beside = passing_wave(1.37, 0.11, 0.01, c, period, 0.0, 40, 10);
  const auto standing = writers::crest_kinematics(clock.t, beside.eta, here.eta, here.u, stats, 0.37, 9.81);
  EXPECT_EQ(standing.waves, 0u);
  EXPECT_TRUE(std::isnan(standing.ratio));
}

TEST(WaveAnalysis, TheWavesSectionReadsTheGaugeRecordsOfAProbesFile) {
  test::TempDir dir("waves-section");
  // Gauges at x = 1, 1.6, 2.2 m; the wave runs along +x at 1.5 m/s. S1's fastest surface particle is
  // at half the crest's speed, S2's at 1.2 times it; S2 also sees air under its surface once, at
  // t = 6 s (row 120); an earlier one, at 1 s, is before the window.
  const double c = 1.5;
  const Record clock = waves(0.0, 0.0, 0.0, 2.0, 40, 10);
  const Gauge off = passing_wave(1.0, 0.11, 0.010, c, 2.0, 0.0, 40, 10),
              s1 = passing_wave(1.6, 0.11, 0.015, c, 2.0, 0.5 * c, 40, 10),
              s2 = passing_wave(2.2, 0.11, 0.012, c, 2.0, 1.2 * c, 40, 10);
  auto probes_file = [&](const std::string& name, bool air) {
    std::string csv =
        "# talus probes: scene test\ntime,step,OFF_elevation,S1_elevation,S2_elevation,S1_air_below,S2_air_below,"
        "S1_surface_u,S2_surface_u\n";
    for (std::size_t k = 0; k < clock.t.size(); ++k)
      csv += std::to_string(clock.t[k]) + "," + std::to_string(k) + "," + std::to_string(off.eta[k]) + "," +
             std::to_string(s1.eta[k]) + "," + std::to_string(s2.eta[k]) + ",0," +
             (air && (k == 120 || k == 20) ? "0.02" : "0") + "," + std::to_string(s1.u[k]) + "," +
             std::to_string(s2.u[k]) + "\n";
    const std::string file = dir.file(name);
    test::write_file(file, csv + "20.05,40");  // a row cut short by a kill: left out
    return file;
  };
  const std::string file = probes_file("probes.csv", true);
  const auto params = params_from_json(writers::ProbesWriter::describe(),
                                       R"({"gauges": [[1, 0], [1.6, 0], [2.2, 0]], "gauge_names": ["OFF", "S1", "S2"],
                                           "waves": {"offshore": "OFF", "surf": ["S1", "S2"], "slope": 20,
                                                     "water_depth": 0.11, "from": 2}})",
                                       2);
  const std::vector<Vec3> at = {{1, 0, 0}, {1.6, 0, 0}, {2.2, 0, 0}};
  writers::BreakerAnalysis analysis(params.object("waves"), {"OFF", "S1", "S2"});
  analysis.place(params.object("waves"), at, 1);
  std::map<std::string, WriterResult> r;
  for (const auto& result : analysis.analyse(file, 9.81)) r[result.name] = result;
  EXPECT_NEAR(r["offshore_height"].number, 0.02, 2e-4);
  EXPECT_NEAR(r["period"].number, 2.0, 0.02);
  EXPECT_NEAR(r["surf_height"].number, 0.03, 3e-4);
  EXPECT_EQ(r["surf_gauge"].text, "S1");
  EXPECT_NEAR(r["S2_height"].number, 0.024, 2.4e-4);
  const double xi = std::tan(20.0 * std::numbers::pi / 180.0) / std::sqrt(0.03 / (9.81 * 4.0 / (2.0 * std::numbers::pi)));
  EXPECT_NEAR(r["iribarren"].number, xi, 0.01 * xi);
  EXPECT_EQ(r["breaker_type"].text, writers::breaker_type(xi));
  EXPECT_EQ(r["overturned"].text, "yes");
  EXPECT_EQ(r["overturn_gauge"].text, "S2");
  EXPECT_NEAR(r["overturn_time"].number, 6.0, 1e-9);
  // The crest speeds from OFF to S1 and to S2; S2's crest is overtaken.
  EXPECT_NEAR(r["S1_kinematic_ratio"].number, 0.5, 0.005);
  EXPECT_NEAR(r["S2_kinematic_ratio"].number, 1.2, 0.012);
  EXPECT_NEAR(r["kinematic_ratio"].number, 1.2, 0.012);
  EXPECT_EQ(r["kinematic_gauge"].text, "S2");
  EXPECT_NEAR(r["crest_speed"].number, c, 0.01 * c);
  EXPECT_NEAR(r["crest_particle_speed"].number, 1.2 * c, 1e-6);
  EXPECT_EQ(r["kinematic_breaking"].text, "yes");
  EXPECT_EQ(r["kinematic_waves"].number, 16.0);  // 8 waves in the window at each surf gauge
  EXPECT_EQ(r["observed_type"].text, "plunging");  // it overturned
  // Every result it announces before the run, it gives.
  std::vector<std::string> given;
  for (const auto& [name, value] : r) given.push_back(name);
  std::vector<std::string> announced = analysis.result_names();
  std::sort(announced.begin(), announced.end());
  EXPECT_EQ(given, announced);
  // No air: S2's crest broke without overturning, spilling.
  std::map<std::string, WriterResult> spilled;
  for (const auto& result : analysis.analyse(probes_file("spilled.csv", false), 9.81)) spilled[result.name] = result;
  EXPECT_EQ(spilled["overturned"].text, "no");
  EXPECT_EQ(spilled["observed_type"].text, "spilling");
  // Another waves section over the same records, by name.
  auto analysed = [&](const char* json, const std::vector<std::string>& names, const std::vector<Vec3>& where,
                      const std::string& records) {
    const auto other = params_from_json(writers::ProbesWriter::describe(), json, 2);
    writers::BreakerAnalysis a(other.object("waves"), names);
    a.place(other.object("waves"), where, 1);
    std::map<std::string, WriterResult> by_name;
    for (const auto& result : a.analyse(records, 9.81)) by_name[result.name] = result;
    return by_name;
  };
  // Without a slope: the waves, but no breaker numbers; S1 alone did not break.
  auto f = analysed(R"({"gauges": [[1, 0], [1.6, 0]], "gauge_names": ["OFF", "S1"],
                        "waves": {"offshore": "OFF", "surf": ["S1"], "from": 2}})",
                    {"OFF", "S1"}, {at[0], at[1]}, file);
  EXPECT_NEAR(f["surf_height"].number, 0.03, 3e-4);
  EXPECT_TRUE(std::isnan(f["iribarren"].number));
  EXPECT_TRUE(std::isnan(f["froude"].number));
  EXPECT_EQ(f["breaker_type"].text, "unknown");
  EXPECT_EQ(f["overturned"].text, "no");  // S1 saw no air
  EXPECT_TRUE(std::isnan(f["overturn_time"].number));
  EXPECT_EQ(f["kinematic_breaking"].text, "no");
  EXPECT_EQ(f["observed_type"].text, "surging_or_collapsing");
  // A higher threshold than the fastest crest's ratio: S2 did not break either.
  EXPECT_EQ(analysed(R"({"gauges": [[1, 0], [1.6, 0], [2.2, 0]], "gauge_names": ["OFF", "S1", "S2"],
                         "waves": {"offshore": "OFF", "surf": ["S1", "S2"], "kinematic_threshold": 1.3}})",
                     {"OFF", "S1", "S2"}, at, dir.file("spilled.csv"))["observed_type"].text,
            "surging_or_collapsing");
  // In 0.02 m of water a 2 s wave is 0.886 m long: S2, 1.2 m out, is beyond a wavelength, and its crests
  // cannot be matched to the offshore gauge's.
  auto beyond = analysed(R"({"gauges": [[1, 0], [1.6, 0], [2.2, 0]], "gauge_names": ["OFF", "S1", "S2"],
                             "waves": {"offshore": "OFF", "surf": ["S1", "S2"], "water_depth": 0.02}})",
                         {"OFF", "S1", "S2"}, at, file);
  EXPECT_NEAR(beyond["S1_kinematic_ratio"].number, 0.5, 0.005);
  EXPECT_TRUE(std::isnan(beyond["S2_kinematic_ratio"].number));
  EXPECT_EQ(beyond["kinematic_gauge"].text, "S1");
  // Names that are not its gauges are refused, naming them.
  try {
    writers::BreakerAnalysis(params.object("waves"), {"OFF", "S2"});
    ADD_FAILURE() << "accepted a surf gauge that is not a gauge";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/waves/surf: 'S1' is not a gauge of this probes writer; its gauges: OFF, S2"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace talus
