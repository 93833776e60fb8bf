#!/usr/bin/env bash
# The race (issue 11): Blender 3.4's Cell Fracture against Fissure on the same 1 x 1 x 0.05 m
# tile at about 50, 200 and 1000 pieces, side by side in one run on this machine, then
# docs/BENCHMARKS.md regenerated with the section `bench_race_cell_fracture`.
#
#   Blender: its add-on from N seeded random points (scripts/race_cell_fracture.py), all cores
#            (-t 0); time = the operator; closed = shards closed after Merge by Distance.
#   Fissure: bench_fragments' BM_Race rows on 2 threads, body prepared (tet mesh, factor, σ⁰,
#            resistance): the simulation of the cracks that give about N closed meshes plus
#            the meshes themselves.
#   Both whole processes as well: `blender -b … --python` start to exit, and
#   `fissure fracture tile:1,1,0.05 --tets T --fragments N -o fragments.glb` start to exit
#   (reading, meshing, preparing, simulating, the closed meshes and the GLB written).
#
# Usage: scripts/race-cell-fracture.sh [SEED]   (installs Blender through apt-get if missing)
set -euo pipefail
seed=${1:-1}
# shellcheck source=race-setup.sh
source "$(dirname "${BASH_SOURCE[0]}")/race-setup.sh"

now() { date +%s.%N; }
# The rows: pieces and the Fissure body's tet count (enough elements per piece to shape it).
rows=("50 7000" "200 24000" "1000 54000")

echo "race: bench_machine" >&2
"$build_dir/tests/bench/bench_machine" --benchmark_format=json --benchmark_out="$work/machine.json" \
  --benchmark_out_format=json >/dev/null

echo "race: Fissure, body prepared (bench_fragments BM_Race, 2 threads)" >&2
FISSURE_THREADS=2 OMP_THREAD_LIMIT=2 OPENBLAS_NUM_THREADS=1 "$build_dir/tests/bench/bench_fragments" \
  --benchmark_filter='BM_Race' --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_format=json --benchmark_out="$work/fissure.json" --benchmark_out_format=json >/dev/null

: >"$work/blender.jsonl"
: >"$work/process.jsonl"
for row in "${rows[@]}"; do
  read -r pieces tets <<<"$row"
  echo "race: Blender Cell Fracture, $pieces points" >&2
  t0=$(now)
  line=$(blender -b --factory-startup -t 0 --python "$root/scripts/race_cell_fracture.py" -- "$pieces" "$seed" 2>&1 |
    sed -n 's/^RACE //p')
  t1=$(now)
  [[ -n $line ]] || { echo "race: Blender's run with $pieces points reported nothing" >&2; exit 1; }
  python3 -c 'import json,sys; d=json.loads(sys.argv[1]); d["process_s"]=float(sys.argv[2]); print(json.dumps(d))' \
    "$line" "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" >>"$work/blender.jsonl"
  echo "race: fissure fracture, $pieces fragments, $tets tets (whole process)" >&2
  t0=$(now)
  "$build_dir/bin/fissure" fracture tile:1,1,0.05 --tets "$tets" --fragments "$pieces" --seed "$seed" \
    --threads 2 -q -o "$work/fragments.glb" --stats "$work/stats.json" 2>"$work/stderr.txt" || {
    cat "$work/stderr.txt" >&2; exit 1; }
  t1=$(now)
  python3 -c 'import json,sys; f=json.load(open(sys.argv[1]))["fracture"]; print(json.dumps({"pieces": int(sys.argv[2]), "tets": f["tets"], "meshes": f["fragment_meshes"], "labelled": f["fragments"], "process_s": float(sys.argv[3]), "seconds": f["seconds"]}))' \
    "$work/stats.json" "$pieces" "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" >>"$work/process.jsonl"
done

python3 "$root/scripts/race_report.py" "$work/fissure.json" "$work/blender.jsonl" "$work/process.jsonl" \
  "$work/machine.json" "$out_dir/bench_race_cell_fracture.json"
git -C "$root" rev-parse --short HEAD >"$out_dir/bench_race_cell_fracture.commit"
git -C "$root" diff --quiet HEAD || sed -i 's/$/ (with uncommitted changes)/' "$out_dir/bench_race_cell_fracture.commit"
echo "scripts/race-cell-fracture.sh ${1:-}" >"$out_dir/bench_race_cell_fracture.command"
python3 "$root/tests/bench/write_benchmarks_md.py" "$out_dir" "$root/docs/BENCHMARKS.md" "scripts/race-cell-fracture.sh"
echo "race: wrote docs/BENCHMARKS.md (section bench_race_cell_fracture)" >&2
