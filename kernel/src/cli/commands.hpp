// The `talus` subcommands. Each returns the process exit code:
// 0 success, 1 a run that failed, 2 bad input or plugin.
#pragma once

#include <string>
#include <vector>

namespace talus::cli {

using Args = std::vector<std::string>;

int run(const Args& args);
int validate(const Args& args);
int plan(const Args& args);
int study(const Args& args);
int plugins(const Args& args);
int doc(const Args& args);
int example(const Args& args);
int schema(const Args& args);
int manifest(const Args& args);

std::string usage();
std::string default_scene();

}  // namespace talus::cli
