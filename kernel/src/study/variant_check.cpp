#include "study/variant_check.hpp"

#include <algorithm>
#include <filesystem>

#include "plugin_registry.hpp"
#include "resource_estimate.hpp"
#include "scene.hpp"
#include "simulation.hpp"
#include "talus/error.hpp"
#include "text.hpp"

namespace fs = std::filesystem;

namespace talus::study {

namespace {

// The measures that name a series or a result no writer of this variant gives.
std::string missing_outputs(const StudySpec& spec, const Simulation& simulation) {
  const std::vector<std::string> columns = simulation.output_series();
  const std::vector<std::string> results = simulation.output_results();
  std::string problems;
  auto report = [&](std::size_t k, const char* key, const std::string& what, const char* kind,
                    const std::vector<std::string>& known, const char* none) {
    problems += "error: " + spec.file + ": /measures/" + std::to_string(k) + "/" + key + ": no output of the scene " +
                what + "\n       the scene's " + kind + ": " + (known.empty() ? std::string(none) : text::join(known)) +
                "\n";
  };
  for (std::size_t k = 0; k < spec.measures.size(); ++k) {
    const Measure& m = spec.measures[k];
    if (!m.series.empty() && std::find(columns.begin(), columns.end(), m.series) == columns.end())
      report(k, "series", "records '" + m.series + "'", "series", columns, "none (add a \"probes\" output)");
    const std::string prefix = "/results/";
    if (m.summary.starts_with(prefix)) {
      const std::string name = m.summary.substr(prefix.size());
      if (std::find(results.begin(), results.end(), name) == results.end())
        report(k, "summary", "gives the result '" + name + "'", "results", results, "none");
    }
  }
  return problems;
}

}  // namespace

std::vector<CheckedVariant> check_variants(const StudySpec& spec, const std::vector<Variant>& variants,
                                           PluginRegistry& registry) {
  const fs::path base_dir = fs::absolute(spec.base_scene).parent_path();
  const std::string name = fs::path(spec.base_scene).stem().string();
  std::vector<CheckedVariant> checked(variants.size());
  std::string report;
  std::size_t failing = 0;
  for (const Variant& v : variants) {
    const std::string label = spec.base_scene + " [variant " + v.id + ": " + v.label(spec) + "]";
    std::vector<std::string> path_pointers;
    std::string problems;
    try {
      Scene scene = parse_scene(v.scene.dump(2) + "\n", label, name, base_dir.string(), registry, &path_pointers);
      const ResourceEstimate estimate = estimate_resources(scene, registry);
      check_resources(scene, estimate);
      checked[v.index].bytes = estimate.bytes();
      const Simulation simulation(registry, std::move(scene));
      problems = missing_outputs(spec, simulation);
    } catch (const InputError& e) {
      problems = e.what();
      if (!problems.ends_with("\n")) problems += "\n";
    }
    if (!problems.empty()) {
      ++failing;
      report += "variant " + v.id + " (" + v.label(spec) + "):\n" + problems;
      continue;
    }
    nlohmann::json runnable = v.scene;
    for (const std::string& pointer : path_pointers) {
      const nlohmann::json::json_pointer at(pointer);
      if (!runnable.contains(at) || !runnable[at].is_string()) continue;
      const fs::path file = runnable[at].get<std::string>();
      if (file.is_relative()) runnable[at] = (base_dir / file).lexically_normal().string();
    }
    checked[v.index].scene_text = runnable.dump(2) + "\n";
  }
  if (failing)
    throw InputError(report + std::to_string(failing) + " of " + std::to_string(variants.size()) +
                     " variants of " + spec.file + " cannot run; nothing was run.");
  return checked;
}

}  // namespace talus::study
