#!/usr/bin/env bash
# The street race (issue 13): the bundled street scene (assets/scenes/street.glb, 24 sidewalk
# slabs, a curb and a road) fractured end to end by Fissure and by Blender 3.4's Cell Fracture at
# the same piece counts, side by side in one run on this machine; then docs/BENCHMARKS.md
# regenerated with the section `bench_race_street_cell_fracture`.
#
#   Fissure: `fissure scene fracture street.glb --assign concrete=concrete --assign curb=concrete
#            --age 50 --threads 2` (scripts/demo.sh's assignments and age; until 2026-12-07 the
#            race ran at age 12, where ten slabs stayed whole) with
#            an empty cache (cold) and again with the cache that run filled (warm); its --report
#            gives each body's fragments.
#   Blender: opens the same GLB, gives every body Fissure fractured as many seed points as Fissure
#            made fragments of it, breaks them all with one Cell Fracture call and writes a GLB
#            (scripts/race_street_cell_fracture.py, all cores, -t 0).
#   Both: whole processes start to exit, medians of 3; every piece checked closed by Blender
#         (Fissure's export through scripts/blender_check_scene.py).
#
# Usage: scripts/race-street-cell-fracture.sh [SEED]   (installs Blender through apt-get if missing)
set -euo pipefail
seed=${1:-1}
# shellcheck source=race-setup.sh
source "$(dirname "${BASH_SOURCE[0]}")/race-setup.sh"
scene=$root/assets/scenes/street.glb
repetitions=3

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { print b - a }'; }

echo "race: bench_machine" >&2
"$build_dir/tests/bench/bench_machine" --benchmark_format=json --benchmark_out="$work/machine.json" \
  --benchmark_out_format=json >/dev/null

# One Fissure run: $1 = cold|warm, $2 = repetition. A cold run starts from an empty cache.
fissure_run() {
  local cache=$work/cache-$2
  [[ $1 == cold ]] && rm -rf "$cache"
  local t0 t1
  t0=$(now)
  "$build_dir/bin/fissure" scene fracture "$scene" --assign concrete=concrete --assign curb=concrete --age 50 \
    --seed "$seed" --threads 2 --cache-dir "$cache" -q --report "$work/report-$1.json" -o "$work/fissure-$1.glb" \
    2>"$work/stderr.txt" || { cat "$work/stderr.txt" >&2; exit 1; }
  t1=$(now)
  python3 -c 'import json,sys; print(json.dumps({"cache": sys.argv[1], "process_s": float(sys.argv[2]), "report": json.load(open(sys.argv[3]))}))' \
    "$1" "$(elapsed "$t0" "$t1")" "$work/report-$1.json" >>"$work/fissure.jsonl"
}

: >"$work/fissure.jsonl"
for r in $(seq "$repetitions"); do
  echo "race: Fissure, cold and warm cache ($r/$repetitions)" >&2
  fissure_run cold "$r"
  fissure_run warm "$r"
done
cmp -s "$work/fissure-cold.glb" "$work/fissure-warm.glb" ||
  { echo "race: Fissure's cold and warm runs wrote different scenes" >&2; exit 1; }
echo "race: Blender checks Fissure's export (scripts/blender_check_scene.py)" >&2
blender -b --python "$root/scripts/blender_check_scene.py" -- "$work/fissure-warm.glb" "$scene" 2>/dev/null |
  sed -n 's/^RESULT //p' >"$work/fissure-check.json" || true
[[ -s $work/fissure-check.json ]] || { echo "race: Blender's check of Fissure's export failed" >&2; exit 1; }
# A misplaced, open or missing fragment voids the race: its figures would not be of a usable scene.
python3 -c 'import json,sys; sys.exit(json.load(open(sys.argv[1]))["problems"] != 0)' "$work/fissure-check.json" ||
  { echo "race: Blender found problems in Fissure's export: $(cat "$work/fissure-check.json")" >&2; exit 1; }

: >"$work/blender.jsonl"
for r in $(seq "$repetitions"); do
  echo "race: Blender Cell Fracture on the same bodies and piece counts ($r/$repetitions)" >&2
  t0=$(now)
  line=$(blender -b --factory-startup -t 0 --python "$root/scripts/race_street_cell_fracture.py" -- \
    "$scene" "$work/report-warm.json" "$seed" "$work/blender.glb" 2>&1 | sed -n 's/^RACE //p')
  t1=$(now)
  [[ -n $line ]] || { echo "race: Blender's street run reported nothing" >&2; exit 1; }
  python3 -c 'import json,sys; d=json.loads(sys.argv[1]); d["process_s"]=float(sys.argv[2]); print(json.dumps(d))' \
    "$line" "$(elapsed "$t0" "$t1")" >>"$work/blender.jsonl"
done

python3 "$root/scripts/race_street_report.py" "$work/fissure.jsonl" "$work/fissure-check.json" "$work/blender.jsonl" \
  "$work/machine.json" "$out_dir/bench_race_street_cell_fracture.json"
git -C "$root" rev-parse --short HEAD >"$out_dir/bench_race_street_cell_fracture.commit"
git -C "$root" diff --quiet HEAD || sed -i 's/$/ (with uncommitted changes)/' "$out_dir/bench_race_street_cell_fracture.commit"
echo "scripts/race-street-cell-fracture.sh ${1:-}" >"$out_dir/bench_race_street_cell_fracture.command"
python3 "$root/tests/bench/write_benchmarks_md.py" "$out_dir" "$root/docs/BENCHMARKS.md" "scripts/race-street-cell-fracture.sh"
echo "race: wrote docs/BENCHMARKS.md (section bench_race_street_cell_fracture)" >&2
