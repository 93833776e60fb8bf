#!/usr/bin/env bash
# Runs every benchmark binary on one core and regenerates docs/BENCHMARKS.md from their JSON.
# Usage: scripts/bench.sh [benchmark-name-filter-regex]   e.g. scripts/bench.sh bench_fem
# Medians of 5 repetitions on one thread: FISSURE_THREADS=1 holds Fissure, CHOLMOD's OpenMP team
# and OpenBLAS to one thread; OMP_THREAD_LIMIT=1 as well, because CHOLMOD asks OpenMP for a team
# of 4 that OMP_NUM_THREADS does not cap (issue 9).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${FISSURE_BUILD_DIR:-$root/build}
"$root/scripts/build.sh" >/dev/null
filter=${1:-.}
out_dir=$build_dir/bench-results
mkdir -p "$out_dir"
export FISSURE_THREADS=1 OMP_THREAD_LIMIT=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
# The commit the figures belong to, recorded before the run.
commit=$(git -C "$root" rev-parse --short HEAD)
git -C "$root" diff --quiet HEAD || commit="$commit (with uncommitted changes)"
for exe in "$build_dir"/tests/bench/bench_*; do
  [[ -x $exe && ! -d $exe ]] || continue
  name=$(basename "$exe")
  [[ $name =~ $filter ]] || continue
  echo "bench: $name" >&2
  # bench_fragments' BM_Race rows run on two threads beside Blender: scripts/race-cell-fracture.sh.
  only=(); [[ $name == bench_fragments ]] && only=(--benchmark_filter=-BM_Race)
  taskset -c 0 "$exe" "${only[@]}" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
    --benchmark_format=json --benchmark_out="$out_dir/$name.json" \
    --benchmark_out_format=json >/dev/null
  echo "$commit" >"$out_dir/$name.commit"
  echo "scripts/bench.sh ${1:-}" >"$out_dir/$name.command"
done
python3 "$root/tests/bench/write_benchmarks_md.py" "$out_dir" "$root/docs/BENCHMARKS.md" \
  "scripts/bench.sh ${1:-}"
echo "bench: wrote docs/BENCHMARKS.md" >&2
