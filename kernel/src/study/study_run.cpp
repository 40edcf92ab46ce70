#include "study/study_run.hpp"

#include <fcntl.h>
#include <omp.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <thread>

#include "plugin_registry.hpp"
#include "progress.hpp"
#include "stop_signals.hpp"
#include "study/study_table.hpp"
#include "study/variant_check.hpp"
#include "study/variants.hpp"
#include "talus/error.hpp"
#include "talus/memory.hpp"
#include "text.hpp"
#include "validator.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace talus::study {

namespace {

using Clock = std::chrono::steady_clock;

// A file's text; empty if it cannot be read (a missing log or note reads as nothing).
std::string read_file(const fs::path& path) {
  std::string text;
  text::read_file(path.string(), text);
  return text;
}


// What a variant's folder says of it.
enum class State { fresh, done, failed, resumable };

struct Folder {
  fs::path dir, scene_file;
  State state = State::fresh;
  std::string checkpoint;  // resumable: the newest
};

Folder inspect(const fs::path& dir, const std::string& scene_name, const std::string& scene_text,
               const std::string& study_file) {
  Folder f{dir, dir / (scene_name + ".json")};
  if (!fs::exists(f.scene_file)) return f;
  if (read_file(f.scene_file) != scene_text)
    throw InputError("error: " + study_file + ": " + dir.string() +
                     " holds another variant (its scene differs from this study's); the study file changed "
                     "since it ran: give another --out, or remove the folder");
  if (fs::exists(dir / "summary.json")) f.state = State::done;
  else if (fs::exists(dir / "failed.txt")) f.state = State::failed;
  else
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().extension() == ".checkpoint" &&
          (f.checkpoint.empty() || entry.path().filename().string() > fs::path(f.checkpoint).filename().string())) {
        f.checkpoint = entry.path().string();  // names carry the zero-padded step: the largest is the newest
        f.state = State::resumable;
      }
  return f;
}

// The error a failed run printed: from its first "error:" line on.
std::string error_of(const fs::path& log, int status) {
  const std::string text = read_file(log);
  std::string error;
  std::size_t at = text.starts_with("error: ") ? 0 : text.find("\nerror: ");
  if (at != std::string::npos) {
    if (at > 0) ++at;
    error = text.substr(at, 600);
    std::replace(error.begin(), error.end(), '\n', ' ');
    while (error.find("  ") != std::string::npos) error.erase(error.find("  "), 1);
    while (!error.empty() && error.back() == ' ') error.pop_back();
  }
  if (error.empty())
    error = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                                : "exit code " + std::to_string(WEXITSTATUS(status)) + " (see run.log)";
  return error;
}

pid_t spawn(const std::vector<std::string>& argv, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw RunError("error: cannot start " + argv[0] + ": " + std::strerror(rc));
  return pid;
}

std::string talus_executable() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw RunError("error: cannot find the talus executable (/proc/self/exe): " + ec.message());
  return exe.string();
}

}  // namespace

// How far a running variant is: the simulated-time fraction of the last
// progress line ("t = 1.2 / 4 s (...") its run printed to its log; < 0 if none yet.
double run_fraction(const std::string& log) {
  std::ifstream in(log, std::ios::binary);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(std::max<std::streamoff>(0, size - 4096));
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string tail = buffer.str();
  const auto line = tail.rfind("\nt = ");  // a line's start: "dt = " holds "t = " too
  double done = 0.0, end = 0.0;
  if (line == std::string::npos || std::sscanf(tail.c_str() + line + 1, "t = %lf / %lf s", &done, &end) != 2 ||
      !(end > 0.0))
    return -1.0;
  return std::clamp(done / end, 0.0, 1.0);
}

int run_study(const StudySpec& spec, const StudyOptions& options) {
  const Clock::time_point start = Clock::now();
  const nlohmann::json base = parse_json(read_file(spec.base_scene), spec.base_scene);
  std::vector<Variant> variants = expand_variants(spec, base);
  if (!base.contains("checkpoint"))
    for (Variant& v : variants) v.scene["checkpoint"] = {{"every_minutes", spec.checkpoint_minutes}};

  PluginRegistry registry;
  registry.add_default_locations();
  set_memory_check(!options.allow_large);
  const std::vector<CheckedVariant> checked = check_variants(spec, variants, registry);

  const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(variants.size())));
  const int threads_total = options.threads > 0 ? options.threads : omp_get_max_threads();
  const int threads = std::max(1, threads_total / jobs);
  {  // the `jobs` largest variants at once must fit
    std::vector<double> bytes;
    for (const auto& c : checked) bytes.push_back(c.bytes);
    std::sort(bytes.rbegin(), bytes.rend());
    double together = 0.0;
    for (int k = 0; k < jobs && k < static_cast<int>(bytes.size()); ++k) together += bytes[k];
    require_memory(together, spec.file + ": --jobs " + std::to_string(jobs),
                   std::to_string(jobs) + " variants running at once");
  }

  const fs::path out = fs::absolute(options.out.empty() ? spec.out : options.out);
  const std::string scene_name = fs::path(spec.base_scene).stem().string();
  std::vector<Folder> folders;
  for (const Variant& v : variants)
    folders.push_back(inspect(out / v.id, scene_name, checked[v.index].scene_text, spec.file));

  std::size_t done = 0, failed = 0, resumable = 0;
  for (const auto& f : folders) {
    done += f.state == State::done;
    failed += f.state == State::failed;
    resumable += f.state == State::resumable;
  }
  if (!options.quiet || options.dry_run) {
    std::printf("talus study: %s: %zu variants of %s, %d at a time with %d thread%s each; folder %s\n",
                spec.file.c_str(), variants.size(), spec.base_scene.c_str(), jobs, threads, threads == 1 ? "" : "s",
                out.c_str());
    if (!base.contains("checkpoint"))
      std::printf("       the base scene writes no checkpoints: each variant writes one every %g wall-clock minutes "
                  "(checkpoint_minutes), so that a stopped study resumes its runs\n",
                  spec.checkpoint_minutes);
    if (done || failed || resumable)
      std::printf("       already here: %zu done, %zu failed%s, %zu to resume from a checkpoint\n", done, failed,
                  failed && !options.retry_failed ? " (kept; --retry-failed runs them again)" : "", resumable);
  }
  if (options.dry_run) {
    for (const Variant& v : variants)
      std::printf("  %s  %s\n", v.id.c_str(), v.label(spec).c_str());
    std::printf("every variant is valid; nothing was run or written.\n");
    return 0;
  }

  std::vector<Outcome> outcomes(variants.size());
  std::vector<std::size_t> queue;
  for (std::size_t k = 0; k < variants.size(); ++k) {
    const Folder& f = folders[k];
    if (f.state == State::done) {
      outcomes[k].status = "done";
      outcomes[k].measures = read_measures(spec, f.dir.string(), outcomes[k].error);
    } else if (f.state == State::failed && !options.retry_failed) {
      outcomes[k].status = "failed";
      outcomes[k].error = read_file(f.dir / "failed.txt");
    } else {
      queue.push_back(k);
    }
  }
  fs::create_directories(out);
  write_table(spec, variants, outcomes, out.string());

  const std::string exe = talus_executable();
  const StopSignals stop_signals;
  std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
  std::size_t next = 0, finished = 0;
  double run_seconds = 0.0, study_own_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  int stopped_by = 0;
  // Between starts and ends, a line every progress_seconds with how far each running variant is.
  const double progress_seconds = isatty(fileno(stdout)) ? 10.0 : 60.0;
  Clock::time_point last_progress = Clock::now();
  // The time left: what the running variants' own progress says is left of them,
  // and for each waiting one the mean of the finished (or else of the running's projections).
  auto time_left = [&]() {
    const Clock::time_point now = Clock::now();
    double left = 0.0, projected = 0.0;
    std::size_t projections = 0;
    for (const auto& [child, run] : running) {
      const double elapsed = std::chrono::duration<double>(now - run.second).count();
      const double fraction = run_fraction((folders[run.first].dir / "run.log").string());
      if (!(fraction > 0.0)) return -1.0;
      left += elapsed * (1.0 - fraction) / fraction;
      projected += elapsed / fraction;
      ++projections;
    }
    const std::size_t waiting = queue.size() - next;
    const double mean = finished ? run_seconds / static_cast<double>(finished)
                        : projections ? projected / static_cast<double>(projections)
                                      : -1.0;
    if (waiting && mean < 0.0) return -1.0;
    return (left + static_cast<double>(waiting) * std::max(mean, 0.0)) / jobs;
  };
  auto print_progress = [&](const std::string& what) {
    if (options.quiet) return;
    const double left = running.empty() && next == queue.size() ? -1.0 : time_left();
    std::printf("talus study: %s; %zu of %zu done, %zu running, %zu waiting%s\n", what.c_str(),
                finished + (variants.size() - queue.size()), variants.size(), running.size(), queue.size() - next,
                left >= 0.0 ? (", about " + clock_text(left) + " left").c_str() : "");
    std::fflush(stdout);
    last_progress = Clock::now();
  };
  auto print_running = [&]() {
    std::string list;
    for (const auto& [child, run] : running) {
      const double fraction = run_fraction((folders[run.first].dir / "run.log").string());
      list += (list.empty() ? "" : ", ") + variants[run.first].id +
              (fraction >= 0.0 ? " " + std::to_string(static_cast<int>(100.0 * fraction)) + " %" : " (no progress line yet)");
    }
    print_progress("running " + list);
  };

  while ((!stopped_by && next < queue.size()) || !running.empty()) {
    while (!stopped_by && next < queue.size() && static_cast<int>(running.size()) < jobs) {
      const std::size_t k = queue[next++];
      Folder& f = folders[k];
      const Clock::time_point launched = Clock::now();
      fs::create_directories(f.dir);
      fs::remove(f.dir / "failed.txt");
      if (!fs::exists(f.scene_file)) write_atomically(f.scene_file.string(), checked[k].scene_text);
      std::vector<std::string> argv = {exe, "run", f.scene_file.string(), "--out", f.dir.string(),
                                       "--summary", (f.dir / "summary.json").string(),
                                       "--threads", std::to_string(threads)};  // progress lines in run.log
      if (f.state == State::resumable) {
        argv.push_back("--restart");
        argv.push_back(f.checkpoint);
      }
      if (options.allow_large) argv.push_back("--allow-large");
      running[spawn(argv, f.dir / "run.log")] = {k, launched};
      study_own_seconds += std::chrono::duration<double>(Clock::now() - launched).count();
      print_progress(variants[k].id + " (" + variants[k].label(spec) + ") " +
                     (f.state == State::resumable ? "resumed from " + fs::path(f.checkpoint).filename().string()
                                                  : "started"));
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      if (!stopped_by && stop_signals.caught()) {
        stopped_by = stop_signals.caught();
        for (const auto& [child, what] : running) kill(child, stopped_by);  // each writes its checkpoint
      }
      if (!stopped_by && !running.empty() &&
          std::chrono::duration<double>(Clock::now() - last_progress).count() >= progress_seconds) {
        print_running();
        last_progress = Clock::now();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Clock::time_point finish_time = Clock::now();
    const auto [k, launched] = it->second;
    running.erase(it);
    const double seconds = std::chrono::duration<double>(finish_time - launched).count();
    const Folder& f = folders[k];
    Outcome& o = outcomes[k];
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::string what;
    if (code == 0) {
      o.status = "done";
      o.error.clear();
      o.measures = read_measures(spec, f.dir.string(), o.error);
      what = variants[k].id + " done in " + clock_text(seconds);
      ++finished;
      run_seconds += seconds;
    } else if (code == 128 + SIGINT || code == 128 + SIGTERM) {
      o.status = "interrupted";
      what = variants[k].id + " stopped with a checkpoint";
    } else {
      o.status = "failed";
      o.error = error_of(f.dir / "run.log", status);
      write_atomically((f.dir / "failed.txt").string(), o.error);
      what = variants[k].id + " FAILED: " + o.error;
      ++finished;
      run_seconds += seconds;
    }
    const Clock::time_point table_start = Clock::now();
    write_table(spec, variants, outcomes, out.string());
    study_own_seconds += std::chrono::duration<double>(Clock::now() - table_start).count();
    print_progress(what);
  }

  std::size_t failures = 0, complete = 0;
  for (const auto& o : outcomes) {
    failures += o.status == "failed";
    complete += o.status == "done";
  }
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  if (stopped_by) {
    std::printf("talus study: stopped by %s; %zu of %zu variants done. Resume with: talus study %s%s%s\n",
                stopped_by == SIGINT ? "SIGINT" : "SIGTERM", complete, variants.size(), spec.file.c_str(),
                options.out.empty() ? "" : " --out ", options.out.c_str());
    return 128 + stopped_by;
  }
  if (!options.quiet) {
    std::printf("talus study: %zu of %zu variants done, %zu failed, in %s wall; table %s and table.json\n",
                complete, variants.size(), failures, clock_text(wall).c_str(), (out / "table.csv").c_str());
    std::printf("       the study's own work (checking the variants, starting them, the table): %.3g s, "
                "%.2g %% of the runs' %.3g s\n",
                study_own_seconds, run_seconds > 0 ? 100.0 * study_own_seconds / run_seconds : 0.0, run_seconds);
  }
  return failures ? 1 : 0;
}

}  // namespace talus::study
