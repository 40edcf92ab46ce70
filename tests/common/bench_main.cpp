// main() of every benchmark program: Google Benchmark's, with the build the
// figures come from in the report's context (compiler, flags, -march), so
// that figures from different builds are never compared unknowingly.
#include <benchmark/benchmark.h>

int main(int argc, char** argv) {
  benchmark::AddCustomContext("compiler", TALUS_BENCH_COMPILER);
  benchmark::AddCustomContext("flags", TALUS_BENCH_FLAGS);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
