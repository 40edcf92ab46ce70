#include "breaker_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "crest_kinematics.hpp"
#include "talus/series_file.hpp"
#include "wave_analysis.hpp"

namespace talus::writers {

ParamSet BreakerAnalysis::describe() {
  ParamSet w{"waves", "breaker analysis of the gauges' records at the end of the run"};
  w.string("offshore").doc("the gauge offshore of the slope (a gauge name): the offshore height H0 and the period T");
  w.string_list("surf").doc("the gauges in the surf zone: H is the largest of their mean wave heights");
  w.real("slope").unit("deg").greater_than(0.0).less_than(90.0).optional().doc(
      "the seaward slope angle phi (without it: the waves only, no Iribarren or Froude number, type unknown)");
  w.real("water_depth").unit("m").greater_than(0.0).optional().doc(
      "the still water depth d_w offshore (without it: no Froude number)");
  w.real("from").unit("s").min(0.0).default_value(0.0).doc("analyse the records from this time on (skip the start-up)");
  w.real("kinematic_threshold").greater_than(0.0).default_value(1.0).doc(
      "a crest breaks where its fastest surface particle reaches this fraction of the crest's speed, u/c >= "
      "threshold (1: the fluid overtakes the crest; about 0.85 marks the onset)");
  return w;
}

BreakerAnalysis::BreakerAnalysis(const ParamValues& params, const std::vector<std::string>& gauges, bool runup)
    : gauges_(gauges),
      offshore_(params.string("offshore")),
      surf_(params.strings("surf")),
      slope_(params.has("slope") ? params.real("slope") : nan_),
      water_depth_(params.has("water_depth") ? params.real("water_depth") : nan_),
      from_(params.real("from")),
      kinematic_threshold_(params.real("kinematic_threshold")),
      runup_(runup) {
  std::string list;
  for (const auto& g : gauges) list += (list.empty() ? "" : ", ") + g;
  auto known = [&](const std::string& name, const char* key) {
    if (std::find(gauges.begin(), gauges.end(), name) == gauges.end())
      params.fail(key, "'" + name + "' is not a gauge of this probes writer; its gauges: " +
                           (gauges.empty() ? std::string("none (give \"gauges\")") : list));
  };
  known(offshore_, "offshore");
  if (surf_.empty()) params.fail("surf", "name at least one gauge in the surf zone");
  for (const auto& name : surf_) known(name, "surf");
}

void BreakerAnalysis::place(const ParamValues& params, const std::vector<Vec3>& at, int vertical) {
  auto horizontal = [&](const std::string& name) {
    Vec3 p = at[std::find(gauges_.begin(), gauges_.end(), name) - gauges_.begin()];
    p[vertical] = 0.0;
    return p;
  };
  const Vec3 span = horizontal(surf_.front()) - horizontal(offshore_);
  if (!(norm(span) > 0.0))
    params.fail("surf", "the first surf gauge '" + surf_.front() + "' stands on the offshore gauge's vertical line: "
                        "the waves' direction runs from the offshore gauge to it");
  direction_ = span / norm(span);
  ahead_.clear();
  for (const auto& name : surf_) {
    ahead_.push_back(dot(horizontal(name) - horizontal(offshore_), direction_));
    if (!(ahead_.back() > 0.0))
      params.fail("surf", "'" + name + "' is not ahead of the offshore gauge '" + offshore_ +
                              "' along the waves' direction (from it to the first surf gauge)");
  }
}

std::vector<std::string> BreakerAnalysis::result_names() const {
  std::vector<std::string> names = {"offshore_height", "period",        "surf_height",   "surf_gauge",
                                    "waves",           "wavelength",    "iribarren",     "froude",
                                    "breaker_type",    "overturned",    "overturn_gauge", "overturn_time",
                                    "kinematic_waves", "kinematic_ratio", "kinematic_gauge", "kinematic_time", "crest_speed",
                                    "crest_particle_speed", "kinematic_breaking", "observed_type"};
  if (runup_) {
    names.push_back("runup_max");
    names.push_back("runup_mean");
  }
  for (const auto& g : surf_) {
    names.push_back(g + "_height");
    names.push_back(g + "_period");
    names.push_back(g + "_kinematic_ratio");
  }
  return names;
}

std::vector<WriterResult> BreakerAnalysis::analyse(const std::string& probes_file, double g) const {
  std::vector<std::string> columns = {"time", offshore_ + "_elevation"};
  for (const auto& s : surf_) columns.push_back(s + "_elevation");
  for (const auto& s : surf_) columns.push_back(s + "_air_below");
  for (const auto& s : surf_) columns.push_back(s + "_surface_u");
  if (runup_) columns.push_back("runup_elevation");
  const auto series = read_series(probes_file, columns);
  const std::size_t count = surf_.size();
  auto elevation = [&](std::size_t k) -> const std::vector<double>& { return series[1 + k]; };  // 0: offshore
  const WaveStatistics offshore = zero_up_crossing(series[0], series[1], from_);
  const double wavelength = std::isfinite(water_depth_) ? linear_wavelength(offshore.period, water_depth_, g)
                                                        : g * offshore.period * offshore.period / (2.0 * std::numbers::pi);
  std::vector<WriterResult> results;
  double surf_height = std::numeric_limits<double>::quiet_NaN();
  std::string surf_gauge;
  std::vector<WriterResult> per_gauge;
  CrestKinematics fastest;
  std::string fastest_gauge;
  std::size_t travelling = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const WaveStatistics s = zero_up_crossing(series[0], elevation(k + 1), from_);
    // Crests are matched within a period: only a surf gauge within a wavelength of the offshore gauge.
    const CrestKinematics crest =
        ahead_.at(k) < wavelength
            ? crest_kinematics(series[0], series[1], elevation(k + 1), series[2 + 2 * count + k], s, ahead_[k], g)
            : CrestKinematics{};
    per_gauge.push_back({surf_[k] + "_height", s.height, {}});
    per_gauge.push_back({surf_[k] + "_period", s.period, {}});
    per_gauge.push_back({surf_[k] + "_kinematic_ratio", crest.ratio, {}});
    travelling += crest.waves;
    if (crest.waves > 0 && !(crest.ratio <= fastest.ratio)) {
      fastest = crest;
      fastest_gauge = surf_[k];
    }
    if (s.waves > 0 && !(s.height <= surf_height)) {
      surf_height = s.height;
      surf_gauge = surf_[k];
    }
  }
  const BreakerNumbers n =
      breaker_numbers(surf_height, offshore.height, offshore.period, slope_, water_depth_, g);
  results.push_back({"offshore_height", offshore.height, {}});
  results.push_back({"period", offshore.period, {}});
  results.push_back({"surf_height", surf_height, {}});
  results.push_back({"surf_gauge", 0.0, surf_gauge.empty() ? "none" : surf_gauge});
  results.push_back({"waves", static_cast<double>(offshore.waves), {}});
  results.push_back({"wavelength", n.wavelength, {}});
  results.push_back({"iribarren", n.iribarren, {}});
  results.push_back({"froude", n.froude, {}});
  results.push_back({"breaker_type", 0.0, n.type});
  // The first row in the window where a surf gauge found air under the surface.
  double overturn_time = std::numeric_limits<double>::quiet_NaN();
  std::string overturn_gauge;
  for (std::size_t row = 0; row < series[0].size() && overturn_gauge.empty(); ++row)
    for (std::size_t k = 0; k < count; ++k)
      if (series[0][row] >= from_ && series[2 + count + k][row] > 0.0) {
        overturn_time = series[0][row];
        overturn_gauge = surf_[k];
        break;
      }
  const bool overturned = !overturn_gauge.empty();
  results.push_back({"overturned", 0.0, overturned ? "yes" : "no"});
  results.push_back({"overturn_gauge", 0.0, overturned ? overturn_gauge : "none"});
  results.push_back({"overturn_time", overturn_time, {}});
  const bool broke = fastest.ratio >= kinematic_threshold_;
  results.push_back({"kinematic_waves", static_cast<double>(travelling), {}});
  results.push_back({"kinematic_ratio", fastest.ratio, {}});
  results.push_back({"kinematic_gauge", 0.0, fastest_gauge.empty() ? "none" : fastest_gauge});
  results.push_back({"kinematic_time", fastest.time, {}});
  results.push_back({"crest_speed", fastest.crest_speed, {}});
  results.push_back({"crest_particle_speed", fastest.particle_speed, {}});
  results.push_back({"kinematic_breaking", 0.0, fastest_gauge.empty() ? "unknown" : broke ? "yes" : "no"});
  const char* observed = overturned              ? "plunging"
                         : fastest_gauge.empty() ? "unknown"
                         : broke                 ? "spilling"
                                                 : "surging_or_collapsing";
  results.push_back({"observed_type", 0.0, observed});
  if (runup_) {  // above the offshore gauge's mean level, the highest in the window and the mean of each wave's highest
    const auto& t = series[0];
    const auto& r = series.back();
    double highest = std::numeric_limits<double>::quiet_NaN(), sum = 0.0;
    std::size_t waves = 0;
    for (std::size_t w = 0; w + 1 < offshore.crossings.size(); ++w) {
      double top = -std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < t.size(); ++k)
        if (t[k] >= offshore.crossings[w] && t[k] < offshore.crossings[w + 1] && std::isfinite(r[k])) top = std::max(top, r[k]);
      if (!std::isfinite(top)) continue;
      sum += top - offshore.mean_level;
      ++waves;
    }
    for (std::size_t k = 0; k < t.size(); ++k)
      if (t[k] >= from_ && std::isfinite(r[k]) && !(r[k] - offshore.mean_level <= highest)) highest = r[k] - offshore.mean_level;
    results.push_back({"runup_max", highest, {}});
    results.push_back({"runup_mean", waves ? sum / static_cast<double>(waves) : std::numeric_limits<double>::quiet_NaN(), {}});
  }
  for (auto& r : per_gauge) results.push_back(std::move(r));
  return results;
}

}  // namespace talus::writers
