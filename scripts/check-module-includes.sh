#!/usr/bin/env bash
# Keeps the module graph honest: each module may include only the Fissure modules below it, and
# each heavy library stays in the one place allowed for it. Run by CTest (test `module_includes`).
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

# module → Fissure modules it may include (itself included)
declare -A allowed=(
  [base]="base"
  [mesh]="base mesh"
  [io]="base mesh io"
  [fem]="base mesh fem"
  [exemplar]="base exemplar"
  [fracture]="base mesh fem fracture exemplar"
  [fit]="base mesh fem fracture exemplar fit"
  [scene]="base mesh fem fracture exemplar fit io scene"
)
# third-party header prefix → the only source folders that may include it
declare -A library_home=(
  ["CGAL/"]="src/mesh"
  ["opencv2/"]="src/exemplar"
  ["assimp/"]="src/io"
  ["gmsh"]="src/io"
  ["cholmod"]="src/fem"
  ["Spectra/"]="src/fem"
  ["Q"]="src/studio"
)

status=0
report() { echo "module-includes: $1"; status=1; }

for module in "${!allowed[@]}"; do
  for dir in "include/fissure/$module" "src/$module"; do
    [[ -d $dir ]] || continue
    while IFS=: read -r file line text; do
      used=$(sed -E 's/.*#include [<"]fissure\/([a-z_]+)\/.*/\1/' <<<"$text")
      [[ " ${allowed[$module]} " == *" $used "* ]] ||
        report "$file:$line: module '$module' may not include fissure/$used"
    done < <(grep -rnE '#include [<"]fissure/' "$dir" || true)
  done
done

# Public headers mention only Eigen, the standard library and Fissure.
while IFS=: read -r file line text; do
  header=$(sed -E 's/.*#include [<"]([^>"]+)[>"].*/\1/' <<<"$text")
  case $header in
    fissure/* | Eigen/*) ;;
    */* | *.h | *.hpp) report "$file:$line: public header includes <$header>" ;;
    *) ;;
  esac
done < <(grep -rnE '#include [<"]' include || true)

for prefix in "${!library_home[@]}"; do
  home=${library_home[$prefix]}
  while IFS=: read -r file line text; do
    [[ $file == "$home"/* ]] || report "$file:$line: <$prefix…> belongs in $home only"
  done < <(grep -rnE "#include <${prefix}" src include || true)
done

exit $status
