#!/usr/bin/env bash
# Builds the seed corpora from files the repository already has (tests/data/, assets/), so no
# binary blobs are committed: make_corpus.sh OUT_DIR  ->  OUT_DIR/scene/, OUT_DIR/script/.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$1"
rm -rf "$out/scene" "$out/script"
mkdir -p "$out/scene" "$out/script"
cp "$root"/tests/data/*.json "$root"/assets/*.json "$root"/assets/scenes/*.json "$out/scene/"
cp "$root"/tests/data/*.txt "$root"/assets/*.script "$out/script/"
# Every key the loader knows, in one scene, so mutations start from each of them.
cat >"$out/scene/all_keys.json" <<'JSON'
{"name": "all", "gravity": [0, -9.8], "dt": 0.01, "rotation": true, "integrator": "explicit_euler",
 "broad_phase": "sweep_and_prune", "sleep": false,
 "solver": {"method": "seed", "substeps": 2, "push_out_speed": 1, "iterations": 4,
            "restitution_threshold": 0.5, "slop": 0.01, "position_correction": 0.5},
 "camera": {"center": [0, 1], "width": 10}, "click": {"max_impulse": 3},
 "bodies": [
  {"id": "b", "shape": "box", "size": [1, 2], "position": [0, 1], "velocity": [1, -1], "angle": 0.5,
   "angular_velocity": 1, "mass": 2, "restitution": 0.5, "friction": 0.1, "fixed_rotation": true,
   "bullet": true, "color": "#abc"},
  {"shape": "circle", "radius": 0.25, "position": [0.5, 3], "density": 3, "color": "#a0b0c0"},
  {"shape": "box", "size": [20, 1], "position": [0, -0.5], "static": true}]}
JSON
# Every shape key (polygon, capsule, segment, "shapes" with each part key), in one scene.
cat >"$out/scene/all_shape_keys.json" <<'JSON'
{"rotation": true, "bodies": [
  {"id": "g", "shape": "segment", "points": [[-6, 2], [-5, 0], [5, 0], [6, 2]], "loop": false, "position": [0, 0],
   "static": true},
  {"shape": "segment", "points": [[0, 0], [1, 0], [1, 1]], "loop": true, "position": [3, 3], "static": true},
  {"shape": "polygon", "vertices": [[0, 0], [1, 0], [1, 1], [0.5, 0.4], [0, 1]], "radius": 0.05,
   "position": [-2, 1], "angle": 0.3, "density": 2},
  {"shape": "capsule", "length": 1, "radius": 0.25, "position": [0, 2], "angular_velocity": 1},
  {"position": [2, 2], "mass": 3, "shapes": [
    {"shape": "circle", "radius": 0.3, "offset": [0, 0.5], "density": 2, "friction": 0.1, "restitution": 0.5},
    {"shape": "box", "size": [1, 0.2], "angle": 0.4},
    {"shape": "polygon", "vertices": [[0, 0], [0.5, 0], [0, 0.5]], "offset": [-0.5, 0]},
    {"shape": "capsule", "length": 0.5, "radius": 0.1, "offset": [0.5, -0.3], "angle": 1.2}]},
  {"position": [0, 5], "static": true, "shapes": [
    {"shape": "segment", "points": [[0, 0], [2, 0]]}, {"shape": "box", "size": [0.5, 0.5], "offset": [1, 1]}]}]}
JSON
