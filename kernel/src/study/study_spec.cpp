#include "study/study_spec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "run_summary.hpp"
#include "scene.hpp"
#include "talus/error.hpp"
#include "text.hpp"
#include "validator.hpp"

namespace fs = std::filesystem;

namespace talus::study {

namespace {

ParamSet range_params() {
  ParamSet r{"range", "evenly spaced numbers"};
  r.real("from").doc("first value");
  r.real("to").doc("last value");
  r.integer("count").min(1).max(static_cast<double>(max_variants)).doc("how many values, both ends included");
  return r;
}

ParamSet axis_params() {
  ParamSet a{"axis", "one value of the base scene, varied"};
  a.string("pointer").doc("JSON pointer (RFC 6901) to the value this axis sets, e.g. /time/end or /outputs/0/every; "
                          "it must name a key the base scene has");
  a.string("name").optional().doc("the axis' column in the table (default: the pointer)");
  a.json_list("values").optional().doc("the values, any JSON (numbers, text, arrays, objects); or give a range");
  a.object("range", range_params()).optional().doc("evenly spaced numbers instead of values");
  return a;
}

ParamSet measure_params() {
  ParamSet m{"measure", "one number (or text) collected from every run"};
  m.string("name").doc("the measure's column in the table");
  m.string("summary").optional().doc("a JSON pointer into the run summary (docs/output-formats.md), e.g. /time, "
                                     "/steps, /wall_seconds, /peak_memory_mib");
  m.string("series").optional().doc("or a time-series column a writer records, e.g. a probes column such as "
                                    "G1_elevation or max_speed");
  m.choice("reduce", {"max", "min", "mean", "first", "last", "range", "max_abs"})
      .default_value("max")
      .doc("how a series becomes one number (mean: over the rows, range: max - min)");
  m.real("from").unit("s").default_value(0.0).doc("series: rows at simulated time >= from (skip the start-up)");
  m.real("to").unit("s").optional().doc("series: rows at simulated time <= to (default: to the end)");
  return m;
}

Reduce reduce_of(const std::string& name) {
  if (name == "min") return Reduce::min;
  if (name == "mean") return Reduce::mean;
  if (name == "first") return Reduce::first;
  if (name == "last") return Reduce::last;
  if (name == "range") return Reduce::range;
  if (name == "max_abs") return Reduce::max_abs;
  return Reduce::max;
}

std::string read_text(const std::string& path) {
  std::string text;
  if (!text::read_file(path, text))
    throw InputError("error: " + path + ": cannot open study file: " + std::strerror(errno));
  return text;
}

}  // namespace

ParamSet study_params() {
  ParamSet s{"study", "a parameter study (`talus study STUDY.json`): one base scene run once per variant, "
                      "one table of measures"};
  s.path("base").doc("the base scene; a variant is this scene with the axes' values put in");
  s.string("out").optional().doc("the study's folder: one sub-folder per variant and the table "
                                 "(default out/STUDY_NAME; --out overrides)");
  s.object_list("axes", axis_params()).doc("what varies: each axis sets one value of the base scene");
  s.choice("combine", {"grid", "zip"})
      .default_value("grid")
      .doc("grid: every combination of the axes' values; zip: the k-th values of all axes together "
           "(a list of explicit combinations; the axes must be equally long)");
  s.object_list("measures", measure_params()).optional().doc("the table's measure columns");
  s.real("checkpoint_minutes")
      .unit("min")
      .greater_than(0.0)
      .default_value(10.0)
      .doc("a base scene without \"checkpoint\" gets one every this many wall-clock minutes, so that an "
           "interrupted study resumes its runs where they stopped (printed when added)");
  return s;
}

std::vector<nlohmann::json> range_values(double from, double to, std::int64_t count) {
  std::vector<nlohmann::json> values;
  for (std::int64_t k = 0; k < count; ++k) {
    const double x = count == 1 ? from : from + (to - from) * static_cast<double>(k) / static_cast<double>(count - 1);
    char text[40];
    std::snprintf(text, sizeof text, "%.12g", x);
    values.emplace_back(std::strtod(text, nullptr));
  }
  return values;
}

StudySpec load_study(const std::string& path) {
  const std::string text = read_text(path);
  const nlohmann::json json = parse_json(text, path);
  Diagnostics d;
  std::string base_dir = fs::path(path).parent_path().string();
  if (base_dir.empty()) base_dir = ".";
  ValidationContext context{path, base_dir, 3, nullptr, &d};
  const ParamValues v = validate(study_params(), json, "", context);
  if (!d.empty()) throw InputError(d.format() + error_summary(d.size(), path));

  StudySpec spec;
  spec.file = path;
  spec.name = fs::path(path).stem().string();
  spec.base_scene = v.string("base");
  spec.out = v.has("out") ? v.string("out") : "out/" + spec.name;
  spec.zip = v.string("combine") == "zip";
  spec.checkpoint_minutes = v.real("checkpoint_minutes");

  std::set<std::string> columns;
  auto claim = [&](const ParamValues& where, const char* key, const std::string& column) {
    if (column == "variant" || column == "status" || column == "error" || column == "folder")
      d.error(where, key, "'" + column + "' is a column the table has already; choose another name");
    else if (!columns.insert(column).second)
      d.error(where, key, "a second column named '" + column + "'; names in the table must differ");
  };

  if (v.objects("axes").empty()) d.error(v, "axes", "a study needs at least one axis");
  for (const ParamValues& a : v.objects("axes")) {
    Axis axis;
    axis.pointer = a.string("pointer");
    axis.name = a.has("name") ? a.string("name") : axis.pointer;
    if (a.has("range")) {
      if (!a.json_texts("values").empty()) d.error(a, "range", "give values or a range, not both");
      const ParamValues& r = a.object("range");
      axis.values = range_values(r.real("from"), r.real("to"), r.integer("count"));
    } else {
      for (const auto& item : a.json_texts("values")) axis.values.push_back(nlohmann::json::parse(item));
      if (axis.values.empty()) d.error(a, "values", "this axis has no values (give values or a range)");
    }
    claim(a, a.has("name") ? "name" : "pointer", axis.name);
    spec.axes.push_back(std::move(axis));
  }
  std::size_t variants = 1;  // of the grid, counted up to one past the limit
  for (const auto& axis : spec.axes) variants = std::min(variants * std::min(axis.values.size(), max_variants + 1), max_variants + 1);
  if (spec.zip && !spec.axes.empty()) variants = spec.axes.front().values.size();
  if (variants > max_variants)
    d.error(v, "axes", "these axes give more than " + std::to_string(max_variants) +
                           " variants; split the study or use fewer values");
  if (spec.zip)
    for (std::size_t k = 1; k < spec.axes.size(); ++k)
      if (spec.axes[k].values.size() != spec.axes[0].values.size())
        d.error(v.objects("axes")[k], "values",
                "\"combine\": \"zip\" takes the axes' values side by side, but this axis has " +
                    std::to_string(spec.axes[k].values.size()) + " values and the first has " +
                    std::to_string(spec.axes[0].values.size()));

  const std::vector<std::string>& known = summary_keys();
  for (const ParamValues& m : v.objects("measures")) {
    Measure measure;
    measure.name = m.string("name");
    claim(m, "name", measure.name);
    if (m.has("summary") == m.has("series")) {
      d.error(m, "name", "a measure takes its value from \"summary\" or from \"series\": give exactly one");
      continue;
    }
    if (m.has("summary")) {
      measure.summary = m.string("summary");
      const bool rooted = !measure.summary.empty() && measure.summary[0] == '/';
      const std::string head = rooted ? measure.summary.substr(1, measure.summary.find('/', 1) - 1) : measure.summary;
      if (!rooted || std::find(known.begin(), known.end(), head) == known.end()) {
        const std::string guess = text::closest(head, known);
        d.error(m, "summary", "'" + measure.summary + "' names nothing the run summary holds",
                (guess.empty() ? "" : "did you mean '/" + guess + "'?  ") + "the summary's keys: " + text::join(known));
      }
    } else {
      measure.series = m.string("series");
      measure.reduce = reduce_of(m.string("reduce"));
      measure.from = m.real("from");
      measure.bounded = m.has("to");
      if (measure.bounded) {
        measure.to = m.real("to");
        if (!(measure.to >= measure.from)) d.error(m, "to", "the window ends before it starts (from > to)");
      }
    }
    spec.measures.push_back(std::move(measure));
  }
  if (!d.empty()) throw InputError(d.format() + error_summary(d.size(), path));
  return spec;
}

}  // namespace talus::study
