// talus: the command-line front end of the Talus runtime.
#include <cstdio>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "ranks.hpp"
#include "talus/build_info.hpp"
#include "talus/error.hpp"

namespace {

// On several MPI ranks an error on one must end them all, or the others wait
// for it forever; its message names the rank. A code returned without a
// message (a run stopped by a signal) is one all ranks agreed on.
int finish(int code, const char* message) {
  using namespace talus;
  if (ranks::count() > 1) {
    if (message) std::fprintf(stderr, "talus: rank %d of %d: %s\n", ranks::rank(), ranks::count(), message);
    if (code != 0 && message) ranks::abort_all(code);
  } else if (message) {
    std::fprintf(stderr, "%s\n", message);
  }
  ranks::stop();
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace talus;
  try {
    ranks::start(&argc, &argv);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  cli::Args args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(cli::usage().c_str(), stdout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::printf("talus %s (SDK ABI %d)\n", TALUS_VERSION_STRING, sdk_abi_version);
    return 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    if (command == "run") return finish(cli::run(args), nullptr);
    if (command == "validate") return finish(cli::validate(args), nullptr);
    if (command == "plan") return finish(cli::plan(args), nullptr);
    if (command == "study") return finish(cli::study(args), nullptr);
    if (command == "plugins") return finish(cli::plugins(args), nullptr);
    if (command == "doc") return finish(cli::doc(args), nullptr);
    if (command == "example") return finish(cli::example(args), nullptr);
    if (command == "schema") return finish(cli::schema(args), nullptr);
    if (command == "manifest") return finish(cli::manifest(args), nullptr);
    return finish(2, ("error: unknown command '" + command + "'\n" + cli::usage()).c_str());
  } catch (const InputError& e) {
    return finish(2, e.what());
  } catch (const RunError& e) {
    // Stages throw what went wrong; the prefix marks it as the run's end.
    const std::string what = e.what();
    return finish(1, ((what.starts_with("error: ") ? "" : "error: ") + what).c_str());
  } catch (const std::bad_alloc&) {
    // Past the up-front estimate (or with --allow-large): still a scene too large for this machine.
    const std::string what = "error: talus " + command +
                             ": out of memory (std::bad_alloc): the scene needs more memory than this machine could "
                             "give.\n       `talus plan SCENE` shows its estimate; coarsen dp or shrink the domain.";
    return finish(2, what.c_str());
  } catch (const std::length_error& e) {
    const std::string what = "error: talus " + command +
                             ": a size beyond what this machine can hold (std::length_error: " + e.what() +
                             ").\n       `talus plan SCENE` shows its estimate; coarsen dp or shrink the domain.";
    return finish(2, what.c_str());
  } catch (const std::exception& e) {
    return finish(1, (std::string("error: ") + e.what()).c_str());
  }
}
