// `talus study`: checks every variant of a study before anything runs, runs
// what is not finished yet (each variant a `talus run` of its own, side by
// side with --jobs), and writes the table as variants finish.
#pragma once

#include "talus/config.hpp"

#include <string>

#include "study/study_spec.hpp"

namespace talus::study {

struct StudyOptions {
  std::string out;            // overrides the study's "out"
  int jobs = 1;               // variants run at once
  int threads = 0;            // threads in all, split between the jobs (0: OpenMP's default)
  bool retry_failed = false;  // run again the variants that failed before
  bool allow_large = false;
  bool dry_run = false;       // check and list the variants; write nothing
  bool quiet = false;
};

// How far a run is: the simulated-time fraction of the last progress line
// ("t = 1.2 / 4 s (...") in its log; < 0 if it has none yet.
TALUS_API double run_fraction(const std::string& log);

// Returns the exit code: 0 every variant done, 1 some failed (the table says
// which and why), 130/143 stopped by a signal (the study resumes), and throws
// InputError for a study or variant that cannot run (nothing written).
TALUS_API int run_study(const StudySpec& spec, const StudyOptions& options);

}  // namespace talus::study
