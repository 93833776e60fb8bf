#!/usr/bin/env bash
# Regenerates docs/fracture.md's section "What the prior reaches" (between its prior-reach
# markers) and its gallery docs/images/prior-*.png: the fit's prior (Table 3) run on a fit-like
# tile, against every closed network of the shared exemplars (../shared/exemplars, read in place;
# an exemplar whose MANIFEST description says "open:" is left out).
# Usage: scripts/prior-reach.sh [draws] [shared-dir]      (default 300 draws: ≈ 6–10 min, one core)
# Runs pinned to one core (FISSURE_CPU, default 1) with every library held to one thread.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
draws=${1:-300}
shared=${2:-${FISSURE_SHARED_DIR:-$root/../shared}}
build_dir=${FISSURE_BUILD_DIR:-$root/build}
[[ -f $build_dir/build.ninja ]] || cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" --target prior_reach >/dev/null
export FISSURE_THREADS=1 OMP_THREAD_LIMIT=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
exemplars=()
while IFS=$'\t' read -r id _ _ _ _ _ _ description; do
  [[ $id == \#* || $id == id ]] && continue
  [[ $description == *"open:"* ]] && continue
  exemplars+=(--exemplar "$id=$shared/exemplars/$id.png")
done <"$shared/exemplars/MANIFEST.tsv"
out_dir=$build_dir/prior-reach
mkdir -p "$out_dir"
rm -f "$root"/docs/images/prior-*.png
command="scripts/prior-reach.sh${1:+ $1}"
commit=$(git -C "$root" rev-parse --short HEAD)
git -C "$root" diff --quiet HEAD -- src include tests || commit="$commit (with uncommitted changes)"
taskset -c "${FISSURE_CPU:-1}" "$build_dir/tests/bench/prior_reach" --out "$out_dir/runs.jsonl" \
  --images "$root/docs/images" --draws "$draws" "${exemplars[@]}" 2>"$out_dir/progress.log"
python3 "$root/tests/bench/prior_reach_report.py" "$out_dir/runs.jsonl" "$shared/exemplars" \
  "$root/docs/fracture.md" "$command" "$commit"
echo "prior-reach: wrote docs/fracture.md (What the prior reaches) and docs/images/prior-*.png" >&2
