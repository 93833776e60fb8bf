# Sourced by the Cell Fracture races (scripts/race-cell-fracture.sh, scripts/race-street-cell-
# fracture.sh): installs Blender through apt-get if missing, builds Fissure, and sets root,
# build_dir, out_dir (where the benchmark JSON goes) and work (a scratch directory removed at exit).
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${FISSURE_BUILD_DIR:-$root/build}
if ! command -v blender >/dev/null; then
  echo "race: installing Blender (Debian's package)" >&2
  sudo_cmd=(); [[ $(id -u) == 0 ]] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get install -y --no-install-recommends blender python3-numpy >&2
fi
"$root/scripts/build.sh" >/dev/null
out_dir=$build_dir/bench-results
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out_dir"
