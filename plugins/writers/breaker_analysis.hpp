// The probes writer's "waves" section: at the end of a run, the waves its
// gauges recorded (zero up-crossing), the breaker numbers on the seaward
// slope and the breaker type by the Iribarren number (wave_analysis.hpp);
// beside it, what the water did: whether a surf gauge saw air under the
// surface (an overturning crest), where and when first.
// Results go to the run summary (results/probes/...) and, beside the probes
// file SCENE_probes.csv, SCENE_probes_results.json.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "talus/params.hpp"
#include "talus/writer.hpp"

namespace talus::writers {

class BreakerAnalysis {
 public:
  static ParamSet describe();
  // `gauges`: the probes writer's gauge names, which the section must name.
  // `runup`: the probes writer records runup_elevation (a runup_line).
  BreakerAnalysis(const ParamValues& params, const std::vector<std::string>& gauges, bool runup = false);

  std::vector<std::string> result_names() const;
  // The gauges whose air under the surface the probes writer records (NAME_air_below).
  const std::vector<std::string>& surf_gauges() const { return surf_; }
  // Reads the gauges' records from the probes file; g = |gravity|.
  std::vector<WriterResult> analyse(const std::string& probes_file, double g) const;

 private:
  std::string offshore_;
  std::vector<std::string> surf_;
  static constexpr double nan_ = std::numeric_limits<double>::quiet_NaN();
  double slope_ = nan_, water_depth_ = nan_, from_ = 0.0;  // NaN: not given
  bool runup_ = false;
};

}  // namespace talus::writers
