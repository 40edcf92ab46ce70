#include "study/study_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "talus/error.hpp"
#include "talus/series_file.hpp"

namespace fs = std::filesystem;

namespace talus::study {

namespace {

bool has_column(const std::string& csv_path, const std::string& column) {
  const auto header = series_header(csv_path);
  return std::find(header.begin(), header.end(), column) != header.end();
}

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}


}  // namespace

void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    if (!out) throw RunError("error: cannot write " + tmp + ": " + std::strerror(errno));
  }
  fs::rename(tmp, path);
}

double reduce_series(const std::string& csv_path, const Measure& m) {
  const auto series = read_series(csv_path, {"time", m.series});
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0, first = 0.0, last = 0.0, max_abs = 0.0;
  std::size_t rows = 0;
  for (std::size_t k = 0; k < series[0].size(); ++k) {
    const double at = series[0][k], x = series[1][k];
    if (at < m.from || (m.bounded && at > m.to)) continue;
    if (!std::isfinite(x)) continue;  // a gauge with no water above it writes nan
    if (rows == 0) first = x;
    last = x;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    max_abs = std::max(max_abs, std::abs(x));
    sum += x;
    ++rows;
  }
  if (rows == 0)
    throw RunError(csv_path + ": column '" + m.series + "' has no finite value in the window t = " +
                   std::to_string(m.from) + (m.bounded ? " to " + std::to_string(m.to) : " to the end") + " s");
  switch (m.reduce) {
    case Reduce::max: return hi;
    case Reduce::min: return lo;
    case Reduce::mean: return sum / static_cast<double>(rows);
    case Reduce::first: return first;
    case Reduce::last: return last;
    case Reduce::range: return hi - lo;
    case Reduce::max_abs: return max_abs;
  }
  return hi;
}

std::vector<nlohmann::json> read_measures(const StudySpec& spec, const std::string& folder, std::string& problems) {
  std::vector<nlohmann::json> values(spec.measures.size());
  nlohmann::json summary;
  {
    std::ifstream in(fs::path(folder) / "summary.json");
    try {
      summary = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception&) {
      problems = "its summary.json cannot be read";
      return values;
    }
  }
  std::vector<std::string> files;
  if (summary.contains("outputs") && summary["outputs"].is_object())
    for (const auto& [type, list] : summary["outputs"].items())
      for (const auto& file : list)
        if (file.is_string() && file.get<std::string>().ends_with(".csv")) files.push_back(file.get<std::string>());

  auto problem = [&](const std::string& text) { problems += (problems.empty() ? "" : "; ") + text; };
  for (std::size_t k = 0; k < spec.measures.size(); ++k) {
    const Measure& m = spec.measures[k];
    if (!m.summary.empty()) {
      const nlohmann::json::json_pointer pointer(m.summary);
      if (!summary.contains(pointer)) problem(m.name + ": the summary has no " + m.summary);
      else if (summary[pointer].is_null()) problem(m.name + ": no value (" + m.summary + " is null in the summary)");
      else values[k] = summary[pointer];
      continue;
    }
    const auto file = std::find_if(files.begin(), files.end(), [&](const auto& f) { return has_column(f, m.series); });
    if (file == files.end()) {
      problem(m.name + ": no series file of the run has a column '" + m.series + "'");
      continue;
    }
    try {
      values[k] = reduce_series(*file, m);
    } catch (const RunError& e) {
      problem(m.name + ": " + e.what());
    }
  }
  return values;
}

void write_table(const StudySpec& spec, const std::vector<Variant>& variants, const std::vector<Outcome>& outcomes,
                 const std::string& directory) {
  std::string csv = "variant";
  for (const auto& axis : spec.axes) csv += "," + csv_cell(axis.name);
  csv += ",status";
  for (const auto& m : spec.measures) csv += "," + csv_cell(m.name);
  csv += ",error\n";

  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t k = 0; k < variants.size(); ++k) {
    const Variant& v = variants[k];
    const Outcome& o = outcomes[k];
    nlohmann::json row = {{"variant", v.id}, {"folder", v.id}, {"status", o.status}};
    csv += v.id;
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      row[spec.axes[a].name] = v.values[a];
      csv += "," + csv_cell(short_text(v.values[a]));
    }
    csv += "," + o.status;
    for (std::size_t m = 0; m < spec.measures.size(); ++m) {
      const nlohmann::json value = m < o.measures.size() ? o.measures[m] : nlohmann::json();
      row[spec.measures[m].name] = value;
      csv += "," + (value.is_null() ? std::string() : csv_cell(cell_text(value)));
    }
    row["error"] = o.error;
    csv += "," + csv_cell(o.error) + "\n";
    rows.push_back(std::move(row));
  }
  nlohmann::json axes = nlohmann::json::array(), measures = nlohmann::json::array();
  for (const auto& axis : spec.axes) axes.push_back({{"name", axis.name}, {"pointer", axis.pointer}});
  for (const auto& m : spec.measures) measures.push_back(m.name);
  const nlohmann::json table = {
      {"study", spec.file}, {"base", spec.base_scene}, {"axes", axes}, {"measures", measures}, {"rows", rows}};
  write_atomically((fs::path(directory) / "table.csv").string(), csv);
  write_atomically((fs::path(directory) / "table.json").string(), table.dump(2) + "\n");
}

}  // namespace talus::study
