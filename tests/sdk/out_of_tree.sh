#!/usr/bin/env bash
# Installs Talus into a scratch prefix, builds the out-of-tree example plugins
# (share/examples/carreau_rheology, share/examples/cohesion_term) against that prefix alone, runs their unit
# tests, and loads them with the installed `talus`.
set -euo pipefail
build_dir=$1      # the Talus build tree
source_dir=$2     # the Talus source tree
work=$build_dir/tests/out_of_tree
rm -rf "$work"
mkdir -p "$work"

cmake --install "$build_dir" --prefix "$work/prefix" > "$work/install.log"
example=$work/example
cp -r "$source_dir/share/examples/carreau_rheology" "$example"
cmake -S "$example" -B "$example/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$example/build" -j2 > "$work/build.log"
(cd "$example/build" && ctest --output-on-failure > "$work/ctest.log")

talus=$work/prefix/bin/talus
test -f "$example/build/plugins/libtalus_carreau.so.talus.json"
TALUS_PLUGIN_PATH=$example/build/plugins "$talus" doc carreau | grep -q zero_shear_viscosity
"$talus" plugins | grep -q carreau && { echo "carreau must not be found without TALUS_PLUGIN_PATH"; exit 1; }
# The example scene names the plugin folder itself ("plugins": ["build/plugins"]).
"$talus" plan "$example/scene.json" | tee "$work/plan.log" | grep -q "example-carreau 1.0.0"
echo "out-of-tree plugin: built, tested and loaded from $example/build/plugins"

# The out-of-tree pair term (share/examples/cohesion_term): built the same way,
# listed as a pass of the wcsph stage, and run.
term=$work/cohesion
cp -r "$source_dir/share/examples/cohesion_term" "$term"
cmake -S "$term" -B "$term/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/term_configure.log"
cmake --build "$term/build" -j2 > "$work/term_build.log"
(cd "$term/build" && ctest --output-on-failure > "$work/term_ctest.log")
"$talus" plan "$term/scene.json" | tee "$work/term_plan.log" | grep -q "pair term pass: cohesion"
"$talus" run "$term/scene.json" --quiet --out "$work/term_run" --summary "$work/term_summary.json"
grep -q '"removed": 0' "$work/term_summary.json"
# Pair terms in a pipeline without an SPH stage: refused at /pair_terms, exit 2, nothing written.
sed 's/"pipeline": \[ { "stage": "wcsph", "alpha": 0.1 } \]/"pipeline": [ { "stage": "dda" } ]/' \
  "$term/scene.json" > "$term/no_sph_stage.json"
set +e
refusal=$("$talus" run "$term/no_sph_stage.json" --quiet --out "$work/term_refused" 2>&1)
code=$?
set -e
test "$code" -eq 2 || { echo "pair terms without a wcsph stage: exit $code, expected 2: $refusal"; exit 1; }
echo "$refusal" | grep -q '/pair_terms: no stage of the pipeline runs pair terms'
test ! -e "$work/term_refused"
echo "out-of-tree pair term: built, tested, planned and run from $term/build/plugins"
