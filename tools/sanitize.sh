#!/bin/sh
# AddressSanitizer + UndefinedBehaviorSanitizer build of Talus in its own
# folder (build-asan), then the unit tests and the scene fuzzer's short form
# under it. Any report stops the process that made it (-fno-sanitize-recover)
# with an exit code the tests and the fuzz gate count as a failure.
#
#   tools/sanitize.sh                      # everything: build, unit tests, fuzz
#   tools/sanitize.sh --targets "talus_cli talus_wcsph test_params"   # a subset
#   tools/sanitize.sh --tests 'Validator|BadScenes' --fuzz-count 300
#   tools/sanitize.sh --scenes DIR ...     # fuzz only the scenes in DIR (those the built plugins run)
#
# Options: --build DIR (default build-asan), --jobs N (default 2), --targets
# "T..." (default all), --tests REGEX (ctest -R; default: label unit),
# --fuzz-count N (default 2000, as ctest's fuzz.scenes; 0 skips the fuzzer), --scenes DIR (default
# share/scenes), --no-build.
# A full build takes long on two cores: build a subset first to iterate.
set -eu

root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-asan"
jobs=2
targets=""
tests=""
fuzz_count=2000
scenes="$root/share/scenes"
do_build=1
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --targets) targets=$2; shift 2 ;;
    --tests) tests=$2; shift 2 ;;
    --fuzz-count) fuzz_count=$2; shift 2 ;;
    --scenes) scenes=$2; shift 2 ;;
    --no-build) do_build=0; shift ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "sanitize.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

sanitize="-fsanitize=address,undefined -fsanitize=float-cast-overflow -fno-omit-frame-pointer -fno-sanitize-recover=all"
if [ "$do_build" = 1 ]; then
  # RelWithDebInfo: optimised like the real build (the same code paths), with
  # line numbers in the reports. ccache keeps this folder apart from build/.
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTALUS_BUILD_BENCHMARKS=OFF \
    -DCMAKE_CXX_FLAGS="$sanitize" -DCMAKE_C_FLAGS="$sanitize" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_MODULE_LINKER_FLAGS="-fsanitize=address,undefined"
  if [ -n "$targets" ]; then
    # shellcheck disable=SC2086  # the list is meant to split
    cmake --build "$build" -j"$jobs" --target $targets
  else
    cmake --build "$build" -j"$jobs"
  fi
fi

# Reports exit with their own codes (86 ASan, 87 UBSan): outside what the fuzz
# gate allows, and a failure for ctest. Leak checking is off: LeakSanitizer
# stops the process with ptrace, which containers often forbid ("Tracer caught
# signal 11"); ASAN_OPTIONS=detect_leaks=1 turns it on where it works.
export ASAN_OPTIONS="exitcode=86:detect_leaks=0:abort_on_error=0:allocator_may_return_null=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="exitcode=87:print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
export OMP_NUM_THREADS=1

status=0
cd "$build"
if [ -n "$tests" ]; then
  ctest -R "$tests" --timeout 1800 --output-on-failure || status=1
else
  ctest -L unit --timeout 1800 --output-on-failure || status=1
fi
if [ "$fuzz_count" -gt 0 ]; then
  # No address-space limit: ASan reserves terabytes of shadow memory up front.
  # Its allocator is capped instead (it returns null past the cap, which
  # talus ends as out of memory), so that no mutant takes the machine's memory.
  ASAN_OPTIONS="$ASAN_OPTIONS:malloc_limit_mb=6144:soft_rss_limit_mb=8192" /usr/bin/python3 "$root/tools/fuzz_scenes.py" --short --seed 1 --count "$fuzz_count" --talus "$build/bin/talus" --scenes "$scenes" \
    --memory-mib 0 --timeout 120 --failures "$build/fuzz-failures" || status=1
fi
exit $status
