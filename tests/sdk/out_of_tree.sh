#!/usr/bin/env bash
# Installs Talus into a scratch prefix, builds the out-of-tree example plugin
# (share/examples/carreau_rheology) against that prefix alone, runs its unit
# test, and loads it with the installed `talus`.
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
