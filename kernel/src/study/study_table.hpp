// The study's result: one row per variant with its axes' values, its status
// and its measures, written as CSV and JSON (docs/study.md).
#pragma once

#include "talus/config.hpp"

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "study/study_spec.hpp"
#include "study/variants.hpp"

namespace talus::study {

struct Outcome {
  std::string status = "not run";  // done, failed, interrupted, not run
  std::string error;               // failed: the run's error; done: measures it could not read
  std::vector<nlohmann::json> measures;  // done: one per measure (null where unreadable)
};

// The measures of a finished run, from the summary file in `folder` and the
// series files it lists; what cannot be read is null and said in `problems`.
TALUS_API std::vector<nlohmann::json> read_measures(const StudySpec& spec, const std::string& folder,
                                                    std::string& problems);

// One number from a series file's column over the measure's time window;
// throws RunError naming the file when the column or the rows are missing.
TALUS_API double reduce_series(const std::string& csv_path, const Measure& measure);

// Writes `text` to a temporary name and renames it to `path`; throws RunError.
TALUS_API void write_atomically(const std::string& path, const std::string& text);

// Writes DIR/table.csv and DIR/table.json (through temporary names).
TALUS_API void write_table(const StudySpec& spec, const std::vector<Variant>& variants,
                           const std::vector<Outcome>& outcomes, const std::string& directory);

}  // namespace talus::study
