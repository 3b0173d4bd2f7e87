#!/usr/bin/env bash
# Surfaces every sketch of a data folder with the current build and makes the contact sheets:
# what to look at before and after a change to the surfacing.
#   tools/review_data.sh [DATA_DIR (../shared/data)] [OUT_DIR (review)] [-- extra surface args]
# OUT_DIR/results/NAME.ply (+ NAME.report.json, NAME.log), OUT_DIR/index.html, OUT_DIR/NAME.png,
# OUT_DIR/summary.tsv (name, exit code, seconds, regions, genus, beyond, outside_box, crossing
# triangle pairs, warnings).
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cli="${SKETCHSURF_CLI:-$here/build/tools/sketchsurf}"
data="${1:-$here/../shared/data}"
out="${2:-review}"
shift $(( $# > 2 ? 2 : $# ))
[ "${1:-}" = "--" ] && shift
[ -x "$cli" ] || { echo "review_data.sh: $cli not found; run tools/setup.sh first" >&2; exit 2; }
[ -d "$data" ] || { echo "review_data.sh: no data folder '$data'" >&2; exit 2; }

mkdir -p "$out/results" "$out/sketches"
printf "name\texit\tseconds\tregions\tgenus\tbeyond\toutside_box\tcrossing\twarnings\n" > "$out/summary.tsv"
find "$data" -type f \( -name '*.curves' -o -name '*.tilt' -o -path '*/vns/*.obj' -o -name '*.json' \) \
    -not -name '*.report.json' | sort | while read -r sketch; do
  ext="${sketch##*.}"
  name="$(basename "$sketch" ".$ext")"
  folder="$(basename "$(dirname "$sketch")")"
  id="${folder}_${name}"
  ln -sf "$(realpath "$sketch")" "$out/sketches/$id.$ext"
  start=$(date +%s.%N)
  "$cli" surface "$sketch" -o "$out/results/$id.ply" --report "$out/results/$id.report.json" "$@" \
      > "$out/results/$id.log" 2>&1
  rc=$?
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  if [ $rc -eq 0 ]; then
    python3 - "$out/results/$id.report.json" "$id" "$rc" "$seconds" >> "$out/summary.tsv" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); c = r["checks"]
print("\t".join([sys.argv[2], sys.argv[3], "%.1f" % float(sys.argv[4]), str(r["regions"]), str(c["genus"]),
                 "%.3f" % c["beyond"], "%.3f" % c["outside_box"], str(c["self_intersections"]),
                 " | ".join(c["warnings"])]))
PY
  else
    printf "%s\t%s\t%.1f\t\t\t\t\t\t%s\n" "$id" "$rc" "$seconds" "$(tail -1 "$out/results/$id.log")" >> "$out/summary.tsv"
  fi
  echo "review_data.sh: $id exit $rc ($seconds s)" >&2
done
"$cli" review "$out/results" --sketches "$out/sketches" -o "$out"
