// The probes writer's "waves" section: at the end of a run, the waves its
// gauges recorded (zero up-crossing), the breaker numbers on the seaward
// slope and the breaker type by the Iribarren number (wave_analysis.hpp).
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
  BreakerAnalysis(const ParamValues& params, const std::vector<std::string>& gauges);

  std::vector<std::string> result_names() const;
  // Reads the gauges' records from the probes file; g = |gravity|.
  std::vector<WriterResult> analyse(const std::string& probes_file, double g) const;

 private:
  std::string offshore_;
  std::vector<std::string> surf_;
  static constexpr double nan_ = std::numeric_limits<double>::quiet_NaN();
  double slope_ = nan_, water_depth_ = nan_, from_ = 0.0;  // NaN: not given
};

}  // namespace talus::writers
