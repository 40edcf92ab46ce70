// `talus study` end to end with the test plugins' ballistic stage: every
// variant checked before anything runs, the table's values against the
// analytic flight, resuming, failures, interruption, --jobs; and the study
// file's pieces (ranges, grid and zip expansion, pointers).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "process.hpp"
#include "run_summary.hpp"
#include "study/study_run.hpp"
#include "study/study_spec.hpp"
#include "study/study_table.hpp"
#include "study/variants.hpp"
#include "talus/error.hpp"

namespace fs = std::filesystem;
using talus::test::read_file;
using talus::test::run_command;
using talus::test::write_file;

namespace {

const std::string exe = std::string("TALUS_PLUGIN_PATH=") + TALUS_TEST_PLUGINS + "/good " + TALUS_EXE;
const std::string scenes = TALUS_TEST_SCENES;

// A scratch folder holding a copy of the base scene and the study file given.
std::string scratch(const std::string& name, const std::string& study_text,
                    const std::string& base_text = read_file(scenes + "/study_ballistic.json")) {
  const std::string dir = std::string(TALUS_BINARY_DIR) + "/tests/study_" + name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_file(dir + "/study_ballistic.json", base_text);
  write_file(dir + "/study.json", study_text);
  return dir;
}

std::vector<std::vector<std::string>> csv_rows(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream in(read_file(path));
  std::string line;
  while (std::getline(in, line)) {  // RFC 4180 quoting, no line breaks in cells
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (std::size_t k = 0; k < line.size(); ++k) {
      const char c = line[k];
      if (quoted && c == '"' && k + 1 < line.size() && line[k + 1] == '"') cells.back() += line[++k];
      else if (c == '"') quoted = !quoted;
      else if (c == ',' && !quoted) cells.emplace_back();
      else cells.back() += c;
    }
    rows.push_back(cells);
  }
  return rows;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

const std::string grid_study = read_file(scenes + "/study_ballistic_grid.json");

TEST(Study, GridRunsEveryVariantAndTablesTheFlight) {
  const std::string dir = scratch("grid", grid_study);
  const auto r = run_command(exe + " study " + dir + "/study.json --out " + dir + "/out --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("6 variants of"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the base scene writes no checkpoints"), std::string::npos) << r.output;
  const auto rows = csv_rows(dir + "/out/table.csv");
  ASSERT_EQ(rows.size(), 7u) << read_file(dir + "/out/table.csv");
  EXPECT_EQ(rows[0], (std::vector<std::string>{"variant", "launch", "end", "status", "steps", "t_end", "peak_speed",
                                                "speed_after", "error"}));
  // Grid order: the last axis fastest. Launched upwards at v0 under g = 9.81: the
  // peak speed is v0 (at t = 0) and at the first row from t = 0.015 s on (t = 0.02 s)
  // the speed is v0 - 9.81 * 0.02, exactly in the stage's constant-step Euler.
  const double v0[] = {1.0, 1.0, 1.0, 2.0, 2.0, 2.0}, end[] = {0.02, 0.03, 0.04, 0.02, 0.03, 0.04};
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& row = rows[k + 1];
    ASSERT_EQ(row.size(), 9u);
    EXPECT_EQ(row[0], "00" + std::to_string(k + 1));
    EXPECT_EQ(row[1], "[0.0," + std::to_string(static_cast<int>(v0[k])) + ".0]");
    EXPECT_DOUBLE_EQ(std::stod(row[2]), end[k]);
    EXPECT_EQ(row[3], "done");
    EXPECT_EQ(std::stoi(row[4]), static_cast<int>(std::lround(end[k] / 0.001)));
    EXPECT_NEAR(std::stod(row[5]), end[k], 1e-12);
    EXPECT_NEAR(std::stod(row[6]), v0[k], 1e-6);
    EXPECT_NEAR(std::stod(row[7]), v0[k] - 9.81 * 0.02, 1e-6);
    EXPECT_EQ(row[8], "");
  }
  const auto table = nlohmann::json::parse(read_file(dir + "/out/table.json"));
  ASSERT_EQ(table["rows"].size(), 6u);
  EXPECT_EQ(table["rows"][4]["launch"], nlohmann::json::parse("[0.0, 2.0]"));
  EXPECT_EQ(table["rows"][4]["steps"], 30);
  // Each variant's folder holds a scene that runs on its own.
  EXPECT_TRUE(fs::exists(dir + "/out/005/study_ballistic.json"));
  EXPECT_TRUE(fs::exists(dir + "/out/005/summary.json"));
  EXPECT_EQ(run_command(exe + " validate " + dir + "/out/005/study_ballistic.json").exit_code, 0);
}

TEST(Study, ASecondRunRunsNothingAndAChangedStudyIsRefused) {
  const std::string dir = scratch("resume", grid_study);
  const std::string study = exe + " study " + dir + "/study.json --out " + dir + "/out --threads 1";
  ASSERT_EQ(run_command(study).exit_code, 0);
  const auto before = fs::last_write_time(dir + "/out/003/summary.json");
  const auto again = run_command(study);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("already here: 6 done, 0 failed, 0 to resume"), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find("started"), std::string::npos) << again.output;
  EXPECT_EQ(fs::last_write_time(dir + "/out/003/summary.json"), before);
  EXPECT_EQ(csv_rows(dir + "/out/table.csv").size(), 7u);
  // Other values in the same folder: refused before anything runs.
  write_file(dir + "/study.json", replaced(grid_study, "\"count\": 3", "\"count\": 5"));
  const auto changed = run_command(study);
  EXPECT_EQ(changed.exit_code, 2) << changed.output;
  EXPECT_NE(changed.output.find("/out/002 holds another variant"), std::string::npos) << changed.output;
  EXPECT_EQ(fs::last_write_time(dir + "/out/003/summary.json"), before);
}

TEST(Study, EveryBadInputIsNamedBeforeAnythingRuns) {
  const std::string study = R"({
    "base": "study_ballistic.json",
    "axes": [
      { "pointer": "/time/ends", "values": [0.01] },
      { "pointer": "/pipeline/0/dt", "values": [] }
    ],
    "measures": [ { "name": "steps", "summary": "/stepz" } ]
  })";
  const std::string dir = scratch("bad", study);
  const auto r = run_command(exe + " study " + dir + "/study.json --out " + dir + "/out");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/axes/1/values: this axis has no values"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/measures/0/summary: '/stepz' names nothing the run summary holds"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("did you mean '/steps'?"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out"));

  // With the study file's own errors fixed: the pointer, then the variants.
  write_file(dir + "/study.json", replaced(replaced(study, "\"values\": []", "\"values\": [0.001, -1]"), "/stepz", "/steps"));
  const auto p = run_command(exe + " study " + dir + "/study.json --out " + dir + "/out");
  EXPECT_EQ(p.exit_code, 2) << p.output;
  EXPECT_NE(p.output.find("/axes/0/pointer: '/time/ends' names no key of the base scene"), std::string::npos)
      << p.output;
  EXPECT_NE(p.output.find("keys at /time: end"), std::string::npos) << p.output;

  write_file(dir + "/study.json", R"({
    "base": "study_ballistic.json",
    "axes": [ { "pointer": "/pipeline/0/dt", "values": [0.001, -1] } ],
    "measures": [ { "name": "peak", "series": "max_sped" } ]
  })");
  const auto v = run_command(exe + " study " + dir + "/study.json --out " + dir + "/out");
  EXPECT_EQ(v.exit_code, 2) << v.output;
  // The series no output records, in every variant; the bad value in variant 002 only.
  EXPECT_NE(v.output.find("variant 001 (/pipeline/0/dt=0.001):\nerror: " + dir +
                          "/study.json: /measures/0/series: no output of the scene records 'max_sped'"),
            std::string::npos)
      << v.output;
  EXPECT_NE(v.output.find("variant 002 (/pipeline/0/dt=-1):\nerror: "), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("[variant 002: /pipeline/0/dt=-1]: /pipeline/0/dt: -1 is out of range"), std::string::npos)
      << v.output;
  EXPECT_NE(v.output.find("2 of 2 variants of " + dir + "/study.json cannot run; nothing was run."),
            std::string::npos)
      << v.output;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

// What the study fuzzer found: a NUL byte in a value cut the messages short, and
// in a file name it named the folder before it.
TEST(Study, ANulByteIsShownAndRefusedInAFileName) {
  const std::string dir = scratch("nul", R"({
    "base": "study_ballistic.json",
    "axes": [ { "pointer": "/time/end", "values": [0.01, "a\u0000b"] } ]
  })");
  const auto r = run_command(exe + " study " + dir + "/study.json --dry-run");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("variant 002 (/time/end=a\\u0000b):\nerror: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("/time/end: expected a number, got the string \"a\\u0000b\""), std::string::npos) << r.output;
  write_file(dir + "/study.json", R"({"base": "\u0000", "axes": [ { "pointer": "/time/end", "values": [0.01] } ]})");
  const auto base = run_command(exe + " study " + dir + "/study.json --dry-run");
  EXPECT_EQ(base.exit_code, 2) << base.output;
  EXPECT_NE(base.output.find("/study.json: /base: a file name cannot hold a NUL byte"), std::string::npos)
      << base.output;
}

TEST(Study, AStudyOfMoreThanTenThousandVariantsIsRefusedBeforeAnyIsMade) {
  const std::string dir = scratch("huge", R"({
    "base": "study_ballistic.json",
    "axes": [ { "pointer": "/time/end", "range": { "from": 0.01, "to": 0.02, "count": 200 } },
              { "pointer": "/pipeline/0/dt", "range": { "from": 0.001, "to": 0.002, "count": 9007199254740993 } } ]
  })");
  const auto r = run_command(exe + " study " + dir + "/study.json --dry-run");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("/axes/1/range/count: 9007199254740992 is out of range; must be >= 1 and <= 10000"),
            std::string::npos)
      << r.output;
  write_file(dir + "/study.json", replaced(read_file(dir + "/study.json"), "9007199254740993", "200"));
  const auto grid = run_command(exe + " study " + dir + "/study.json --dry-run");
  EXPECT_EQ(grid.exit_code, 2) << grid.output;
  EXPECT_NE(grid.output.find("/axes: these axes give more than 10000 variants"), std::string::npos) << grid.output;
}

TEST(Study, AFailedVariantIsMarkedAndTheOthersRun) {
  const std::string dir = scratch("failed", R"({
    "base": "study_ballistic.json",
    "axes": [ { "pointer": "/pipeline/0/nan_at", "name": "nan_at", "values": [1.0, 0.01, 2.0] } ],
    "measures": [ { "name": "t_end", "summary": "/time" } ]
  })");
  const std::string study = exe + " study " + dir + "/study.json --out " + dir + "/out --threads 1";
  const auto r = run_command(study);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("002 FAILED: error: "), std::string::npos) << r.output;
  auto rows = csv_rows(dir + "/out/table.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[1][2], "done");
  EXPECT_EQ(rows[2][2], "failed");
  EXPECT_NE(rows[2][4].find("non-finite velocity"), std::string::npos) << rows[2][4];
  EXPECT_EQ(rows[3][2], "done");
  // Kept as failed on a second run; run again with --retry-failed (and failing again).
  const auto kept = run_command(study);
  EXPECT_EQ(kept.exit_code, 1) << kept.output;
  EXPECT_NE(kept.output.find("2 done, 1 failed (kept; --retry-failed runs them again)"), std::string::npos)
      << kept.output;
  EXPECT_EQ(kept.output.find("002 FAILED"), std::string::npos) << kept.output;
  const auto retried = run_command(study + " --retry-failed");
  EXPECT_EQ(retried.exit_code, 1);
  EXPECT_NE(retried.output.find("002 FAILED"), std::string::npos) << retried.output;
}

TEST(Study, AStoppedStudyResumesItsRunsFromTheirCheckpoints) {
  std::string base = read_file(scenes + "/study_ballistic.json");
  base = replaced(base, "\"sleep\": 0.0", "\"sleep\": 0.01");
  base = replaced(base, "\"time\": { \"end\": 0.05 }", "\"time\": { \"end\": 0.05 }, \"checkpoint\": { \"every\": 0.01 }");
  const std::string dir = scratch("stopped", R"({
    "base": "study_ballistic.json",
    "axes": [ { "pointer": "/bodies/0/velocity", "name": "launch", "values": [[0, 1], [0, 3]] } ],
    "measures": [ { "name": "steps", "summary": "/steps" }, { "name": "t_end", "summary": "/time" },
                  { "name": "final_speed", "series": "max_speed", "reduce": "last" } ]
  })", base);
  const std::string study = exe + " study " + dir + "/study.json --out " + dir + "/out --threads 1";
  // Stop the study once the first run has written a checkpoint.
  const auto r = run_command("(" + study + " > " + dir + "/log.txt 2>&1 & pid=$!; "
                             "until ls " + dir + "/out/001/*.checkpoint > /dev/null 2>&1; do sleep 0.02; done; "
                             "kill -TERM $pid; wait $pid; echo exit=$?)");
  const std::string log = read_file(dir + "/log.txt");
  EXPECT_NE(r.output.find("exit=143"), std::string::npos) << r.output << log;
  EXPECT_NE(log.find("stopped by SIGTERM"), std::string::npos) << log;
  EXPECT_NE(log.find("Resume with: talus study"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir + "/out/001/summary.json"));
  EXPECT_FALSE(fs::exists(dir + "/out/002"));

  const auto resumed = run_command(study);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("001 (launch=[0,1]) resumed from study_ballistic_000000"), std::string::npos)
      << resumed.output;
  const auto rows = csv_rows(dir + "/out/table.csv");
  ASSERT_EQ(rows.size(), 3u);
  // The resumed run took fewer steps itself and ended where an uninterrupted one does.
  EXPECT_LT(std::stoi(rows[1][3]), 50) << read_file(dir + "/out/table.csv");
  EXPECT_EQ(std::stoi(rows[2][3]), 50);
  EXPECT_NEAR(std::stod(rows[1][4]), 0.05, 1e-12);
  EXPECT_NEAR(std::stod(rows[1][5]), std::abs(1.0 - 9.81 * 0.05), 1e-6);
  EXPECT_NEAR(std::stod(rows[2][5]), std::abs(3.0 - 9.81 * 0.05), 1e-6);
}

TEST(Study, JobsRunVariantsSideBySideWithTheThreadsSplit) {
  const std::string dir = scratch("jobs", grid_study);
  const auto two = run_command(exe + " study " + dir + "/study.json --out " + dir + "/two --jobs 2 --threads 2");
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_NE(two.output.find("2 at a time with 1 thread each"), std::string::npos) << two.output;
  ASSERT_EQ(run_command(exe + " study " + dir + "/study.json --out " + dir + "/one --threads 1").exit_code, 0);
  // The same table, whatever ran beside what.
  EXPECT_EQ(read_file(dir + "/two/table.csv"), read_file(dir + "/one/table.csv"));
}

TEST(Study, ZipTakesTheKthValuesTogetherAndDryRunWritesNothing) {
  const std::string dir = scratch("zip", R"({
    "base": "study_ballistic.json",
    "combine": "zip",
    "axes": [ { "pointer": "/time/end", "name": "end", "values": [0.01, 0.02] },
              { "pointer": "/pipeline/0/dt", "name": "dt", "values": [0.001, 0.002] } ]
  })");
  const auto dry = run_command(exe + " study " + dir + "/study.json --out " + dir + "/out --dry-run");
  ASSERT_EQ(dry.exit_code, 0) << dry.output;
  EXPECT_NE(dry.output.find("  001  end=0.01, dt=0.001\n  002  end=0.02, dt=0.002\n"), std::string::npos)
      << dry.output;
  EXPECT_FALSE(fs::exists(dir + "/out"));
  // From the study's own folder, with the base beside it (a base path with no folder part).
  const auto here = run_command("cd " + dir + " && " + exe + " study study.json --dry-run");
  EXPECT_EQ(here.exit_code, 0) << here.output;
  write_file(dir + "/study.json", R"({
    "base": "study_ballistic.json", "combine": "zip",
    "axes": [ { "pointer": "/time/end", "values": [0.01, 0.02] }, { "pointer": "/pipeline/0/dt", "values": [0.001] } ]
  })");
  const auto unequal = run_command(exe + " study " + dir + "/study.json --dry-run");
  EXPECT_EQ(unequal.exit_code, 2) << unequal.output;
  EXPECT_NE(unequal.output.find("/axes/1/values: \"combine\": \"zip\" takes the axes' values side by side, but this "
                                "axis has 1 values and the first has 2"),
            std::string::npos)
      << unequal.output;
}

TEST(Study, DocDescribesTheStudyFile) {
  const auto d = run_command(exe + " doc study");
  ASSERT_EQ(d.exit_code, 0) << d.output;
  for (const char* key : {"base", "axes", "combine", "measures", "checkpoint_minutes", "pointer", "reduce"})
    EXPECT_NE(d.output.find(key), std::string::npos) << key;
  // A model's nested sections too: the probes writer's breaker analysis.
  const auto probes = run_command(exe + " doc probes");
  ASSERT_EQ(probes.exit_code, 0) << probes.output;
  EXPECT_NE(probes.output.find("\nwaves:\nwaves (writer): breaker analysis"), std::string::npos) << probes.output;
  EXPECT_NE(probes.output.find("  water_depth  "), std::string::npos) << probes.output;
}

TEST(StudyPieces, RangesGiveTheDecimalsWritten) {
  const auto values = talus::study::range_values(0.1, 1.0, 10);
  ASSERT_EQ(values.size(), 10u);
  EXPECT_EQ(values[2].dump(), "0.3");
  EXPECT_EQ(values[9].dump(), "1.0");
  EXPECT_EQ(talus::study::range_values(5.0, 7.0, 1).front().dump(), "5.0");
}

TEST(StudyPieces, GridPutsTheValuesAtThePointersLastAxisFastest) {
  talus::study::StudySpec spec;
  spec.file = "s.json";
  spec.base_scene = "b.json";
  spec.axes = {{"a", "/x/0", {1, 2}}, {"b", "/y", {"p", "q", "r"}}};
  const auto base = nlohmann::json::parse(R"({"x": [0, 9], "y": "o", "z": true})");
  const auto grid = talus::study::expand_variants(spec, base);
  ASSERT_EQ(grid.size(), 6u);
  EXPECT_EQ(grid[4].id, "005");
  EXPECT_EQ(grid[4].scene, nlohmann::json::parse(R"({"x": [2, 9], "y": "q", "z": true})"));
  EXPECT_EQ(grid[4].label(spec), "a=2, b=q");
  EXPECT_EQ(talus::study::short_text(nlohmann::json::parse(R"([1, 2, 3])")), "[1,2,3]");
  EXPECT_EQ(talus::study::short_text(nlohmann::json(std::vector<int>(30, 7))), "[30 items]");
  EXPECT_EQ(talus::study::short_text(nlohmann::json(std::string(50, 'x'))), std::string(37, 'x') + "...");
  spec.zip = true;
  spec.axes[1].values.pop_back();
  const auto zip = talus::study::expand_variants(spec, base);
  ASSERT_EQ(zip.size(), 2u);
  EXPECT_EQ(zip[1].scene, nlohmann::json::parse(R"({"x": [2, 9], "y": "q", "z": true})"));
  spec.axes[0].pointer = "/x/2";
  EXPECT_THROW(talus::study::expand_variants(spec, base), talus::InputError);
  spec.axes[0].pointer = "x";
  EXPECT_THROW(talus::study::expand_variants(spec, base), talus::InputError);
}

// Measures read back from a finished run's folder: summary values, a null
// result said in the row's error, series reduced over their window.
TEST(StudyPieces, MeasuresComeFromTheSummaryAndTheSeriesFiles) {
  const std::string dir = std::string(TALUS_BINARY_DIR) + "/tests/study_measures";
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_file(dir + "/p.csv", "# units: s,,m\ntime,step,G1_elevation\n0,0,0.1\n1,10,0.3\n2,20,nan\n3,30,-0.2\n4,40,0.");
  write_file(dir + "/summary.json", R"({"steps": 40, "results": {"probes": {"xi": null, "H": 0.02}},
                                        "outputs": {"probes": [")" + dir + R"(/p.csv"], "hdf5": []}})");
  talus::study::StudySpec spec;
  using talus::study::Reduce;
  spec.measures = {{"steps", "/steps"},
                   {"xi", "/results/probes/xi"},
                   {"H", "/results/probes/H"},
                   {"top", "", "G1_elevation", Reduce::max},
                   {"swing", "", "G1_elevation", Reduce::range, 0.5},
                   {"mean_late", "", "G1_elevation", Reduce::mean, 0.5, 3.0, true},
                   {"gone", "", "G2_elevation"}};
  std::string problems;
  const auto values = talus::study::read_measures(spec, dir, problems);
  EXPECT_EQ(values[0], 40);
  EXPECT_TRUE(values[1].is_null());
  EXPECT_EQ(values[2], 0.02);
  EXPECT_EQ(values[3], 0.3);
  EXPECT_DOUBLE_EQ(values[4].get<double>(), 0.5);  // 0.3 - (-0.2); nan skipped, the cut last row left out
  EXPECT_DOUBLE_EQ(values[5].get<double>(), 0.05);
  EXPECT_TRUE(values[6].is_null());
  EXPECT_NE(problems.find("xi: no value (/results/probes/xi is null in the summary)"), std::string::npos) << problems;
  EXPECT_NE(problems.find("gone: no series file of the run has a column 'G2_elevation'"), std::string::npos)
      << problems;
}

// A running variant's progress from its log: the last progress line, not the
// "dt = " inside it nor the "to t = 6 s" of the opening line.
TEST(StudyPieces, ARunsProgressIsItsLastProgressLine) {
  const std::string log = std::string(TALUS_BINARY_DIR) + "/tests/study_progress.log";
  write_file(log, "talus: running a.json: 732 fluid particles, to t = 6 s; output in out\n");
  EXPECT_LT(talus::study::run_fraction(log), 0.0);
  write_file(log, read_file(log) + "t = 1.5 / 6 s ( 25.0%)  dt = 0.000187 s  step 100\n"
                                   "t = 3 / 6 s ( 50.0%)  dt = 0.000188 s  step 200  ETA 2:00\n");
  EXPECT_DOUBLE_EQ(talus::study::run_fraction(log), 0.5);
  EXPECT_LT(talus::study::run_fraction(log + ".none"), 0.0);
}

// The keys a measure may name are the keys the summary has.
TEST(StudyPieces, SummaryKeysAreTheSummaryFilesKeys) {
  const std::string dir = std::string(TALUS_BINARY_DIR) + "/tests/study_summary_keys";
  fs::remove_all(dir);
  const auto r = run_command(exe + " run " + scenes + "/study_ballistic.json --quiet --out " + dir + " --summary " +
                             dir + "/summary.json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<std::string> keys;
  const auto summary = nlohmann::json::parse(read_file(dir + "/summary.json"));
  for (const auto& [key, value] : summary.items()) keys.push_back(key);
  std::vector<std::string> declared = talus::summary_keys();
  std::sort(keys.begin(), keys.end());
  std::sort(declared.begin(), declared.end());
  EXPECT_EQ(keys, declared);
}

}  // namespace
