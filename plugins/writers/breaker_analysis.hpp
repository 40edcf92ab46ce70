// The probes writer's "waves" section: at the end of a run, the waves its
// gauges recorded (zero up-crossing), the breaker numbers on the seaward
// slope and the breaker type by the Iribarren number (wave_analysis.hpp);
// beside it, what the water did: whether a surf gauge saw air under the
// surface (an overturning crest), where and when first, and whether the
// fluid at a crest overtook the crest (crest_kinematics.hpp). Observed type:
// plunging where a crest overturned, spilling where it broke without
// overturning, surging_or_collapsing where neither.
// Results go to the run summary (results/probes/...) and, beside the probes
// file SCENE_probes.csv, SCENE_probes_results.json.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "talus/params.hpp"
#include "talus/vec3.hpp"
#include "talus/writer.hpp"

namespace talus::writers {

class BreakerAnalysis {
 public:
  static ParamSet describe();
  // `gauges`: the probes writer's gauge names, which the section must name.
  // `runup`: the probes writer records runup_elevation (a runup_line).
  BreakerAnalysis(const ParamValues& params, const std::vector<std::string>& gauges, bool runup = false);

  // Where the gauges stand (`at`, in the order of the constructor's `gauges`),
  // with `vertical` the gauges' axis: the waves' direction, horizontal from
  // the offshore gauge to the first surf gauge, and how far each surf gauge is
  // ahead of the offshore gauge, which it must be. Fails on `params` (the
  // waves section).
  void place(const ParamValues& params, const std::vector<Vec3>& at, int vertical);
  // Unit, horizontal; once placed.
  const Vec3& direction() const { return direction_; }

  std::vector<std::string> result_names() const;
  // The gauges whose air under the surface (NAME_air_below) and surface speed
  // along direction() (NAME_surface_u) the probes writer records.
  const std::vector<std::string>& surf_gauges() const { return surf_; }
  // Reads the gauges' records from the probes file; g = |gravity|.
  std::vector<WriterResult> analyse(const std::string& probes_file, double g) const;

 private:
  std::vector<std::string> gauges_;
  std::string offshore_;
  std::vector<std::string> surf_;
  Vec3 direction_{};
  std::vector<double> ahead_;  // per surf gauge: its distance from the offshore gauge along direction_
  static constexpr double nan_ = std::numeric_limits<double>::quiet_NaN();
  double slope_ = nan_, water_depth_ = nan_, from_ = 0.0;  // NaN: not given
  double kinematic_threshold_ = 1.0;
  bool runup_ = false;
};

}  // namespace talus::writers
