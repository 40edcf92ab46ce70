#!/usr/bin/env python3
"""The scene JSON Schema kept in share/ is the one `talus schema` generates
from the declarations, and every shipped scene validates against it."""
import glob
import json
import os
import subprocess
import sys

import jsonschema

talus, source = sys.argv[1], sys.argv[2]
kept_path = os.path.join(source, "share", "schema", "scene.schema.json")
generated = json.loads(subprocess.run([talus, "schema"], check=True, capture_output=True, text=True).stdout)
with open(kept_path) as f:
    kept = json.load(f)
if kept != generated:
    sys.exit(f"{kept_path} is out of date: regenerate it with `talus schema --output {kept_path}`")

validator = jsonschema.Draft202012Validator(generated)
scenes = sorted(glob.glob(os.path.join(source, "share", "scenes", "*.json")))
# share/examples/* scenes name out-of-tree plugins the built-in schema cannot know;
# sdk.out_of_tree_plugin validates those with the plugin loaded.
failures = 0
for path in scenes:
    with open(path) as f:
        scene = json.load(f)
    errors = sorted(validator.iter_errors(scene), key=lambda e: list(e.path))
    for e in errors[:3]:
        print(f"{path}: /{'/'.join(map(str, e.path))}: {e.message[:200]}")
    failures += bool(errors)
print(f"{len(scenes) - failures} of {len(scenes)} shipped scenes valid against the schema")
sys.exit(1 if failures or not scenes else 0)
