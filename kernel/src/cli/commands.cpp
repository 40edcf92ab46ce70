#include "commands.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "plugin_registry.hpp"
#include "ranks.hpp"
#include "resource_estimate.hpp"
#include "scene.hpp"
#include "scene_schema.hpp"
#include "schema.hpp"
#include "simulation.hpp"
#include "study/study_run.hpp"
#include "study/study_spec.hpp"
#include "talus/error.hpp"
#include "talus/memory.hpp"
#include "text.hpp"

namespace fs = std::filesystem;

namespace talus::cli {

namespace {

// The scene `talus run` runs when given none: what Talus is for.
constexpr const char* default_scene_file = "scenes/block_impact.json";

struct Options {
  std::vector<std::string> positional;
  std::string out, restart, output_file, summary;
  int threads = 0, jobs = 1;
  bool quiet = false, verbose = false, allow_large = false, retry_failed = false, dry_run = false;
};

int positive_integer(const std::string& option, const std::string& v) {
  std::size_t used = 0;
  int n = -1;
  try {
    n = std::stoi(v, &used);
  } catch (const std::exception&) {
  }
  if (n < 1 || used != v.size()) throw InputError("error: " + option + ": '" + v + "' is not a positive integer");
  return n;
}

Options parse(const Args& args, const std::vector<std::string>& allowed) {
  Options o;
  auto allowed_flag = [&](const std::string& f) { return std::find(allowed.begin(), allowed.end(), f) != allowed.end(); };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) throw InputError("error: option " + a + " needs a value");
      return args[++i];
    };
    if (a.rfind("--", 0) != 0) {
      o.positional.push_back(a);
      continue;
    }
    if (!allowed_flag(a)) {
      const std::string guess = text::closest(a, allowed);
      throw InputError("error: unknown option '" + a + "'" + (guess.empty() ? "" : "; did you mean '" + guess + "'?"));
    }
    if (a == "--out") o.out = value();
    else if (a == "--restart") o.restart = value();
    else if (a == "--output") o.output_file = value();
    else if (a == "--summary") o.summary = value();
    else if (a == "--quiet") o.quiet = true;
    else if (a == "--verbose") o.verbose = true;
    else if (a == "--allow-large") o.allow_large = true;
    else if (a == "--retry-failed") o.retry_failed = true;
    else if (a == "--dry-run") o.dry_run = true;
    else if (a == "--threads") o.threads = positive_integer(a, value());
    else if (a == "--jobs") o.jobs = positive_integer(a, value());
  }
  return o;
}

std::string one_scene(const Options& o, const char* command) {
  if (o.positional.size() != 1)
    throw InputError(std::string("error: talus ") + command + " needs exactly one scene file\n" + usage());
  return o.positional.front();
}

// Refused plugins are warnings until a scene needs one of their models.
void print_warnings(const PluginRegistry& registry, std::size_t from) {
  for (std::size_t k = from; k < registry.warnings().size(); ++k)
    std::fprintf(stderr, "%s\n", registry.warnings()[k].c_str());
}

void open_registry(PluginRegistry& registry) {
  registry.add_default_locations();
  print_warnings(registry, 0);
}

// load_scene, and the warnings of the plugins the scene's own list added.
Scene scene_of(const std::string& path, PluginRegistry& registry) {
  const std::size_t before = registry.warnings().size();
  try {
    Scene scene = load_scene(path, registry);
    print_warnings(registry, before);
    return scene;
  } catch (...) {
    print_warnings(registry, before);
    throw;
  }
}

// The scene, refused before anything is allocated if it needs more memory
// than the machine has (unless --allow-large); its estimate goes to `estimate`.
Scene sized_scene(const std::string& path, PluginRegistry& registry, const Options& o, ResourceEstimate& estimate,
                  bool print_refused = false) {
  Scene scene = scene_of(path, registry);
  set_memory_check(!o.allow_large);
  estimate = estimate_resources(scene, registry);
  try {
    check_resources(scene, estimate);
  } catch (const InputError&) {
    if (print_refused) print_estimate(std::cout, estimate);
    throw;
  }
  return scene;
}

// Writes text to a file atomically, or to stdout when path is empty.
void emit(const std::string& text, const std::string& path) {
  if (path.empty()) {
    std::fputs(text.c_str(), stdout);
    return;
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    if (!out) throw RunError("error: cannot write " + tmp + ": " + std::strerror(errno));
  }
  fs::rename(tmp, path);
}

std::string share_dir() {
  if (const char* env = std::getenv("TALUS_SHARE_DIR")) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path installed = exe.parent_path().parent_path() / "share" / "talus";
  if (!ec && fs::exists(installed / default_scene_file)) return installed.string();
  // In a build tree: the source tree's share/ beside it.
#ifdef TALUS_SOURCE_SHARE_DIR
  return TALUS_SOURCE_SHARE_DIR;
#else
  return installed.string();
#endif
}

// The part of the scene file's declaration named `name`: an object key
// ("time", "bodies") or a one-of alternative ("box_walls", "plane"), searched
// breadth first so a top-level section wins over a nested namesake.
const ParamSet* find_section(const ParamSet& root, const std::string& name) {
  std::vector<const ParamSet*> level{&root};
  while (!level.empty()) {
    std::vector<const ParamSet*> next;
    for (const ParamSet* set : level)
      for (const auto& spec : set->specs()) {
        if (spec.nested) {
          if (spec.name == name) return spec.nested.get();
          next.push_back(spec.nested.get());
        }
        for (const auto& [alternative, alt_set] : spec.alternatives) {
          if (alternative == name) return alt_set.get();
          next.push_back(alt_set.get());
        }
      }
    level = std::move(next);
  }
  return nullptr;
}

// A parameter table, then the table of each nested object (a model's or the
// study file's sections: a probes writer's "waves", a study's "axes").
void print_doc_with_sections(const ParamSet& set, const std::string& what) {
  std::fputs(doc_text(set, what).c_str(), stdout);
  std::vector<const ParamSet*> sections{&set};
  for (std::size_t k = 0; k < sections.size(); ++k)
    for (const auto& spec : sections[k]->specs())
      if (spec.nested && !spec.nested->specs().empty()) {
        std::printf("\n%s:\n", spec.name.c_str());
        std::fputs(doc_text(*spec.nested, what).c_str(), stdout);
        sections.push_back(spec.nested.get());
      }
}

const ModelRecord& find_model(PluginRegistry& registry, const std::string& spec) {
  // "NAME" or "KIND/NAME".
  std::string kind, name = spec;
  if (const auto slash = spec.find('/'); slash != std::string::npos) {
    kind = spec.substr(0, slash);
    name = spec.substr(slash + 1);
  }
  std::vector<const ModelRecord*> matches;
  std::vector<std::string> all;
  for (const auto& m : registry.models()) {
    all.push_back(m.name);
    if (m.name == name && (kind.empty() || m.kind == kind)) matches.push_back(&m);
  }
  if (matches.empty()) {
    const std::string guess = text::closest(name, all);
    throw InputError("error: no model named '" + spec + "'" + (guess.empty() ? "" : "; did you mean '" + guess + "'?") +
                     "\n       `talus plugins` lists them all");
  }
  if (matches.size() > 1) {
    std::vector<std::string> kinds;
    for (auto* m : matches) kinds.push_back(m->kind + "/" + m->name);
    throw InputError("error: '" + spec + "' names several models; say which: " + text::join(kinds));
  }
  return *matches.front();
}

}  // namespace

std::string default_scene() { return (fs::path(share_dir()) / default_scene_file).string(); }

std::string usage() {
  return "usage: talus COMMAND [options]\n"
         "\n"
         "  run [SCENE] [--out DIR] [--threads N] [--restart CHECKPOINT] [--quiet|--verbose]\n"
         "      [--summary FILE]  also write the run summary as JSON\n"
         "      [--allow-large]   run even if the scene's estimated memory exceeds what is available\n"
         "                       run a scene (no SCENE: the default demo scene)\n"
         "  validate SCENE [--allow-large]\n"
         "                       check a scene and report every problem; runs nothing\n"
         "  plan SCENE [--allow-large]\n"
         "                       the resolved pipeline: stages, passes, fields, plugins loaded, and the\n"
         "                       estimate of particles, memory and steps\n"
         "  study STUDY [--out DIR] [--jobs N] [--threads N] [--retry-failed] [--dry-run] [--quiet]\n"
         "                       a parameter study: every variant checked first, then run (N side by side,\n"
         "                       threads split between them) into DIR/ID/, resumable; table DIR/table.csv\n"
         "                       (`talus doc study`: the study file's keys)\n"
         "  plugins              list the plugins found: kind, name, version, library\n"
         "  doc NAME             parameter table of a model (NAME or KIND/NAME, 'scene' or 'study')\n"
         "  example NAME         a JSON snippet using a model with its defaults\n"
         "  schema [--output F]  JSON Schema of scene files, generated from the declarations\n"
         "  manifest LIBRARY     write LIBRARY.talus.json, the index entry of a plugin\n"
         "  --help, --version\n"
         "\n"
         "exit codes: 0 success, 1 the run failed, 2 bad input or plugin, or a scene too large for the memory\n"
         "available (refused before allocating, or out of memory), 130/143 stopped by SIGINT/SIGTERM\n"
         "plugins are searched in the built-in folder, then TALUS_PLUGIN_PATH (':'-separated), then the\n"
         "scene's \"plugins\" list.\n";
}

int run(const Args& args) {
  const Options o =
      parse(args, {"--out", "--threads", "--restart", "--quiet", "--verbose", "--summary", "--allow-large"});
  if (o.positional.size() > 1) throw InputError("error: talus run takes one scene file\n" + usage());
  const std::string path = o.positional.empty() ? default_scene() : o.positional.front();
  PluginRegistry registry;
  open_registry(registry);
  ResourceEstimate estimate;
  Simulation simulation(registry, sized_scene(path, registry, o, estimate));
  RunOptions options;
  options.output_directory = o.out;
  options.threads = o.threads;
  options.quiet = o.quiet;
  options.verbose = o.verbose;
  options.restart = o.restart;
  options.summary_file = o.summary;
  const int code = simulation.run(options);
  if (code == 0 && !o.quiet && ranks::rank() == 0) {
    if (o.positional.empty()) std::printf("\nThis was the default scene, %s.\n", path.c_str());
    for (const auto& file : simulation.output_files())
      if (file.size() > 7 && file.compare(file.size() - 7, 7, ".h5part") == 0) {
        std::printf("Picture of the last frame:  python3 tools/preview.py %s -o preview.png\n", file.c_str());
        break;
      }
  }
  return code;
}

int validate(const Args& args) {
  const Options o = parse(args, {"--allow-large"});
  const std::string path = one_scene(o, "validate");
  PluginRegistry registry;
  open_registry(registry);
  ResourceEstimate estimate;
  Simulation simulation(registry, sized_scene(path, registry, o, estimate));  // setup checks too; writes nothing
  std::printf("%s: valid (%zu fluid particles, %zu wall particles, %zu stages)\n", path.c_str(),
              simulation.world().fluid.size(), simulation.world().boundary.size(),
              simulation.scene().values.model_names("pipeline").size());
  for (const auto& warning : simulation.world().warnings.all())
    std::fprintf(stderr, "talus: warning: %s\n", warning.c_str());
  return 0;
}

int plan(const Args& args) {
  const Options o = parse(args, {"--allow-large"});
  const std::string path = one_scene(o, "plan");
  PluginRegistry registry;
  open_registry(registry);
  ResourceEstimate estimate;
  Simulation simulation(registry, sized_scene(path, registry, o, estimate, true));
  simulation.print_plan(std::cout);
  print_estimate(std::cout, estimate);
  return 0;
}

int study(const Args& args) {
  const Options o = parse(args, {"--out", "--jobs", "--threads", "--retry-failed", "--allow-large", "--dry-run",
                                 "--quiet"});
  if (o.positional.size() != 1) throw InputError("error: talus study needs exactly one study file\n" + usage());
  study::StudyOptions options;
  options.out = o.out;
  options.jobs = o.jobs;
  options.threads = o.threads;
  options.retry_failed = o.retry_failed;
  options.allow_large = o.allow_large;
  options.dry_run = o.dry_run;
  options.quiet = o.quiet;
  return study::run_study(study::load_study(o.positional.front()), options);
}

int plugins(const Args& args) {
  parse(args, {});
  PluginRegistry registry;
  open_registry(registry);
  std::printf("%-10s %-26s %-10s %s\n", "kind", "model", "version", "library");
  for (const char* kind : {"kernel", "eos", "rheology", "boundary", "contact", "writer", "stage"})
    for (const auto& name : registry.model_names(kind)) {
      const ModelRecord* m = registry.find(kind, name);
      const LibraryRecord& l = registry.libraries()[m->library];
      std::printf("%-10s %-26s %-10s %s\n", kind, name.c_str(), l.plugin_version.c_str(),
                  fs::path(l.path).filename().c_str());
    }
  for (const auto& m : registry.models()) {
    static const std::vector<std::string> known = {"kernel", "eos", "rheology", "boundary", "contact", "writer", "stage"};
    if (std::find(known.begin(), known.end(), m.kind) == known.end())
      std::printf("%-10s %-26s %-10s %s\n", m.kind.c_str(), m.name.c_str(),
                  registry.libraries()[m.library].plugin_version.c_str(),
                  fs::path(registry.libraries()[m.library].path).filename().c_str());
  }
  std::size_t refused = 0;
  for (const auto& l : registry.libraries()) refused += l.refused.empty() ? 0 : 1;
  std::printf("\n%zu models in %zu libraries; `talus doc NAME` shows a model's parameters.\n", registry.models().size(),
              registry.libraries().size() - refused);
  if (refused) std::printf("%zu libraries skipped (see the warnings above).\n", refused);
  return 0;
}

int doc(const Args& args) {
  const Options o = parse(args, {});
  if (o.positional.size() != 1) throw InputError("error: talus doc needs one model name\n" + usage());
  if (o.positional.front() == "scene") {
    std::fputs(doc_text(scene_params(), "scene file").c_str(), stdout);
    return 0;
  }
  if (o.positional.front() == "study") {
    print_doc_with_sections(study::study_params(), "study file");
    return 0;
  }
  PluginRegistry registry;
  open_registry(registry);
  try {
    const ModelRecord& m = find_model(registry, o.positional.front());
    print_doc_with_sections(*registry.model_params(m.kind, m.name), m.kind);
  } catch (const InputError&) {
    // Not a model: a section of the scene file (bodies, box_walls, time, ...)?
    const ParamSet* section = find_section(scene_params(), o.positional.front());
    if (!section) throw;
    std::fputs(doc_text(*section, "scene file").c_str(), stdout);
  }
  return 0;
}

int example(const Args& args) {
  const Options o = parse(args, {});
  if (o.positional.size() != 1) throw InputError("error: talus example needs one model name\n" + usage());
  PluginRegistry registry;
  open_registry(registry);
  const ModelRecord& m = find_model(registry, o.positional.front());
  const std::string key = m.kind == "stage" ? "stage" : "type";
  const Example e = runnable_example(*registry.model_params(m.kind, m.name), key, m.name, 3);
  std::printf("%s\n", e.json.dump(2).c_str());
  if (!e.placeholders.empty())
    std::fprintf(stderr, "note: placeholder values (no default; put your own): %s\n",
                 text::join(e.placeholders, ", ").c_str());
  return 0;
}

int schema(const Args& args) {
  const Options o = parse(args, {"--output"});
  PluginRegistry registry;
  open_registry(registry);
  emit(scene_json_schema(registry).dump(2) + "\n", o.output_file);
  return 0;
}

int manifest(const Args& args) {
  const Options o = parse(args, {});
  if (o.positional.size() != 1) throw InputError("error: talus manifest needs one plugin library\n" + usage());
  const std::string& library = o.positional.front();
  emit(PluginRegistry::describe_library(library).dump(2) + "\n", library + ".talus.json");
  return 0;
}

}  // namespace talus::cli
