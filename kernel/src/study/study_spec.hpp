// A study file (`talus study`): a base scene, the axes along which its
// variants differ, and the measures collected from each run into one table.
// Its keys are declared like a scene's, so `talus doc study` is its manual.
#pragma once

#include "talus/config.hpp"

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/params.hpp"

namespace talus::study {

struct Axis {
  std::string name;     // the table's column
  std::string pointer;  // JSON pointer into the base scene
  std::vector<nlohmann::json> values;
};

enum class Reduce { max, min, mean, first, last, range, max_abs };

struct Measure {
  std::string name;
  std::string summary;  // a JSON pointer into the run summary, or
  std::string series;   // a time-series column that a writer records
  Reduce reduce = Reduce::max;
  double from = 0.0, to = 0.0;  // series: the window of simulated time [from, to]
  bool bounded = false;         // to given
};

struct StudySpec {
  std::string file;        // the study file, as given
  std::string name;        // its stem
  std::string base_scene;  // resolved against the study file's folder
  std::string out;         // the study's folder
  bool zip = false;        // false: every combination of the axes' values
  std::vector<Axis> axes;
  std::vector<Measure> measures;
  double checkpoint_minutes = 10.0;
};

// More variants than this are refused: each is checked before any runs.
inline constexpr std::size_t max_variants = 10000;

TALUS_API ParamSet study_params();

// Reads and checks a study file; throws InputError listing every problem.
TALUS_API StudySpec load_study(const std::string& path);

// Evenly spaced values from..to, rounded to 12 significant digits so that a
// range written in tenths gives tenths (0.3, not 0.30000000000000004).
TALUS_API std::vector<nlohmann::json> range_values(double from, double to, std::int64_t count);

}  // namespace talus::study
