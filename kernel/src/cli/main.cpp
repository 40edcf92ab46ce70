// talus: the command-line front end of the Talus runtime.
#include <cstdio>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "talus/build_info.hpp"
#include "talus/error.hpp"

int main(int argc, char** argv) {
  using namespace talus;
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
    if (command == "run") return cli::run(args);
    if (command == "validate") return cli::validate(args);
    if (command == "plan") return cli::plan(args);
    if (command == "study") return cli::study(args);
    if (command == "plugins") return cli::plugins(args);
    if (command == "doc") return cli::doc(args);
    if (command == "example") return cli::example(args);
    if (command == "schema") return cli::schema(args);
    if (command == "manifest") return cli::manifest(args);
    std::fprintf(stderr, "error: unknown command '%s'\n%s", command.c_str(), cli::usage().c_str());
    return 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const RunError& e) {
    // Stages throw what went wrong; the prefix marks it as the run's end.
    const std::string what = e.what();
    std::fprintf(stderr, "%s%s\n", what.starts_with("error: ") ? "" : "error: ", what.c_str());
    return 1;
  } catch (const std::bad_alloc&) {
    // Past the up-front estimate (or with --allow-large): still a scene too large for this machine.
    std::fprintf(stderr,
                 "error: talus %s: out of memory (std::bad_alloc): the scene needs more memory than this machine "
                 "could give.\n       `talus plan SCENE` shows its estimate; coarsen dp or shrink the domain.\n",
                 command.c_str());
    return 2;
  } catch (const std::length_error& e) {
    std::fprintf(stderr,
                 "error: talus %s: a size beyond what this machine can hold (std::length_error: %s).\n"
                 "       `talus plan SCENE` shows its estimate; coarsen dp or shrink the domain.\n",
                 command.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
