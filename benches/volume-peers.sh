#!/usr/bin/env bash
# Volume meshing benchmark: tetrafoil and Gmsh 4.15 (OCC, default 3-D algorithm, one thread)
# on the same CAD files at the same uniform size (1/20 of the bounding-box diagonal unless
# SIZE_FRACTION says otherwise), in one run, one table: seconds, tets, min dihedral, mean
# radius ratio, and the ratios. Both get the same curvature limit (CURVATURE=12 elements per
# circle, tetrafoil's CAD default; CURVATURE=0 for a uniform size). tetrafoil's proximity limit
# (PROXIMITY=0.5: a face narrower than the spacing spanned by triangles twice as long as it is wide, its default) has no Gmsh
# counterpart: PROXIMITY=0 gives like-for-like element counts.
# Each run is repeated REPEAT times (3 by default) and the fastest kept, for both tools.
# Usage: [CURVATURE=N] [PROXIMITY=N] [SIZE_FRACTION=F] [REPEAT=N] benches/volume-peers.sh [FILE.step ...]
# Needs cargo and python3; Gmsh (pip, into .bench/venv) is installed here when missing.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
CAD=${CAD_DIR:-$ROOT/../shared/cad}
FRACTION=${SIZE_FRACTION:-20}
CURVATURE=${CURVATURE:-12}   # elements per 2π of curvature for both tools; 0 = uniform size
PROXIMITY=${PROXIMITY:-0.5}  # tetrafoil's elements across a narrow face; 0 = off
REPEAT=${REPEAT:-3}
WORK=${VOLUME_BENCH_DIR:-/tmp/tetrafoil-volume-bench}
mkdir -p "$WORK"
FILES=("$@")
if ((${#FILES[@]} == 0)); then
  FILES=("$CAD/nist_ctc_01.stp" "$CAD/gmsh_part.step" "$CAD/onera_m6_halfsphere_domain.stp")
fi

# shellcheck source=benches/peers-common.sh
source "$ROOT/benches/peers-common.sh"


run_tf() { # file size -> "meshing whole tets dmin rr edge"
  local name report start end
  name=$(basename "$1")
  report=$WORK/${name%.*}.json
  start=$(date +%s.%N)
  if "$TF" -q mesh "$1" --size "$2" --curvature-segments "$CURVATURE" --proximity-cells "$PROXIMITY" \
      --threads 1 -o "$WORK/${name%.*}.vtu" --report "$report"; then
    end=$(date +%s.%N)
    "$PY" - "$report" "$start" "$end" <<'PYEOF'
import json, sys
r = json.load(open(sys.argv[1]))
q = r["quality"]
meshing = sum(s["seconds"] for s in r["stages"] if s["stage"] in ("sizing", "curves", "surfaces", "volume"))
whole = float(sys.argv[3]) - float(sys.argv[2])
print(f'{meshing:.3f} {whole:.3f} {q["tets"]} {q["min_dihedral"]:.2f} {q["radius_ratio"]["mean"]:.3f} {q["edge_length"]["mean"]:.4g}')
PYEOF
  else
    echo "fail - - - - -"
  fi
}

run_gmsh() { # file size -> "seconds tets dmin rr edge"
  "$PY" benches/gmsh/mesh.py "$1" "$2" "$CURVATURE" | tail -1 | "$PY" -c "
import json,sys; r=json.load(sys.stdin)
print('fail - - - -' if 'error' in r else f\"{r['seconds']:.3f} {r['tets']} {r['min_dihedral']:.2f} {r['mean_radius_ratio']:.3f} {r['mean_edge']:.4g}\")"
}

printf "%-30s %7s | %7s %7s %8s %6s %6s %6s | %7s %8s %6s %6s %6s | %7s %6s %6s\n" file size \
  "tf s" "(all)" "tf tets" "dmin" "rr" "edge" "gmsh s" "gm tets" "dmin" "rr" "edge" "speedup" "tets/s" "dmin"
for f in "${FILES[@]}"; do
  name=$(basename "$f")
  # tetrafoil's default size is diag/20: scale it so both get the same uniform size.
  h=$("$TF" check "$f" --json | "$VENV/bin/python" -c "import json,sys; print(json.load(sys.stdin)['size'] * 20 / $FRACTION)")
  tf=$(fastest run_tf "$f" "$h")
  gm=$(fastest run_gmsh "$f" "$h")
  read -r ts tall tt td tr te <<<"$tf"
  read -r gs gt gd gr ge <<<"$gm"
  ratio=$("$VENV/bin/python" -c "
try: print(f'{float(\"$gs\")/float(\"$ts\"):.2f}x')
except Exception: print('-')")
  tratio=$("$VENV/bin/python" -c "
try: print(f'{(float(\"$tt\")/float(\"$ts\"))/(float(\"$gt\")/float(\"$gs\")):.2f}x')
except Exception: print('-')")
  dratio=$("$VENV/bin/python" -c "
try: print(f'{float(\"$td\")-float(\"$gd\"):+.1f}')
except Exception: print('-')")
  printf "%-30s %7.4g | %7s %7s %8s %6s %6s %6s | %7s %8s %6s %6s %6s | %7s %6s %6s\n" "$name" "$h" \
    "$ts" "$tall" "$tt" "$td" "$tr" "$te" "$gs" "$gt" "$gd" "$gr" "$ge" "$ratio" "$tratio" "$dratio"
done
echo "tf s: tetrafoil's sizing + curves + surfaces + volume stages (as Gmsh's generate(); CAD loading and writing excluded); fastest of $REPEAT runs each;"
echo "(all): the whole tetrafoil command; edge: mean edge length of the tets; rr: mean radius ratio."
echo "speedup = gmsh s / tetrafoil s; tets/s = tetrafoil's tets per second over Gmsh's; dmin = tetrafoil min dihedral - Gmsh min dihedral (degrees)."
