#!/usr/bin/env bash
# Corpus benchmark: every CAD file of ../shared/cad through tetrafoil (default controls, 2
# threads) and Gmsh 4.15 (OCC, one thread, sewing on, 12 elements per circle, MeshSizeMax =
# the same size: tetrafoil's default, 1/20 of the bounding-box diagonal), in one run. Per file:
# success, seconds, tets, min dihedral for both, and the ratios; then the success counts and
# the medians over the files both meshed (tet ratio tetrafoil/Gmsh, speed-up Gmsh s / tf s).
# Seconds are the same work on both sides: reading the file and meshing it (Gmsh's open and
# generate calls; tetrafoil's report stages but the output file), not process start or output.
# Each run is limited to TIMEOUT seconds (600 by default).
# Usage: [TIMEOUT=S] benches/corpus-peers.sh [FILE ...]
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
CAD=${CAD_DIR:-$ROOT/../shared/cad}
TIMEOUT=${TIMEOUT:-600}
WORK=${CORPUS_BENCH_DIR:-/tmp/tetrafoil-corpus-bench}
mkdir -p "$WORK"
FILES=("$@")
if ((${#FILES[@]} == 0)); then
  mapfile -t FILES < <(ls "$CAD"/*.st[ep]* "$CAD"/*.ig[es]* "$CAD"/*.brep 2>/dev/null | sort)
fi

# shellcheck source=benches/peers-common.sh
source "$ROOT/benches/peers-common.sh"

run_tf() { # file -> "ok seconds tets dmin" or "fail seconds - - reason"
  local name report start end
  name=$(basename "$1")
  report=$WORK/${name%.*}.json
  rm -f "$report"
  start=$(date +%s.%N)
  if timeout "$TIMEOUT" "$TF" -q mesh "$1" --threads 2 -o "$WORK/${name%.*}.vtu" --report "$report" \
      2>"$WORK/${name%.*}.err"; then
    end=$(date +%s.%N)
    "$PY" - "$report" "$start" "$end" <<'PYEOF'
import json, sys
r = json.load(open(sys.argv[1]))
q = r["quality"]
# The same work as Gmsh's timed calls (open + generate): every stage but the output file and
# "sizing" (already inside "load"); not the process start.
work = sum(s["seconds"] for s in r["stages"] if s["stage"] not in ("sizing", "write"))
print(f'ok {work:.2f} {q["tets"]} {q["min_dihedral"]:.2f}')
PYEOF
  else
    end=$(date +%s.%N)
    printf 'fail %.2f - - %s\n' "$("$PY" -c "print($end - $start)")" \
      "$(tail -1 "$WORK/${name%.*}.err" | cut -c1-80)"
  fi
}

run_gmsh() { # file size -> "ok seconds tets dmin" or "fail seconds - - reason"
  local out
  out=$(timeout "$TIMEOUT" "$PY" benches/gmsh/mesh.py "$1" "$2" 12 --sew 2>/dev/null | tail -1) || true
  "$PY" -c "
import json, sys
try:
    r = json.loads(sys.argv[1])
except Exception:
    print('fail $TIMEOUT - - timeout or crash'); sys.exit()
if 'error' in r:
    print(f\"fail {r.get('seconds', 0):.2f} - - {r['error'][:60]}\")
else:
    print(f\"ok {r['seconds'] + r['load_seconds']:.2f} {r['tets']} {r['min_dihedral']:.2f}\")" "$out"
}

SUMMARY=$WORK/summary.txt
: >"$SUMMARY"
printf "%-36s %9s | %4s %8s %9s %6s | %4s %8s %9s %6s | %7s %7s\n" file size \
  tf s tets dmin gmsh s tets dmin "tets x" speedup
for f in "${FILES[@]}"; do
  name=$(basename "$f")
  h=$("$TF" check "$f" --json 2>/dev/null | "$PY" -c "import json,sys; print(json.load(sys.stdin)['size'])" \
    2>/dev/null) || h=""
  if [[ -z $h ]]; then
    # tetrafoil cannot load it: Gmsh still gets its try, at 1/20 of its own box diagonal.
    tok=fail ts=- tt=- td=- treason="cannot read it: $( ("$TF" check "$f" 2>&1 || true) | tail -1 | cut -c1-80)"
    read -r gok gs gt gd greason <<<"$(run_gmsh "$f" auto)"
    h=0
  else
    read -r tok ts tt td treason <<<"$(run_tf "$f")"
    read -r gok gs gt gd greason <<<"$(run_gmsh "$f" "$h")"
  fi
  ratios=$("$PY" -c "
try: print(f'{int(\"$tt\")/int(\"$gt\"):.2f} {float(\"$gs\")/float(\"$ts\"):.2f}')
except Exception: print('- -')")
  read -r tx sp <<<"$ratios"
  printf "%-36s %9.4g | %4s %8s %9s %6s | %4s %8s %9s %6s | %7s %7s\n" "$name" "$h" \
    "$tok" "$ts" "$tt" "$td" "$gok" "$gs" "$gt" "$gd" "$tx" "$sp"
  [[ $tok == fail ]] && echo "    tetrafoil: $treason"
  [[ $gok == fail ]] && echo "    gmsh: $greason"
  echo "$name $tok $gok $tx $sp" >>"$SUMMARY"
done
"$PY" - "$SUMMARY" <<'PYEOF'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1]) if len(l.split()) == 5]
tf = sum(r[1] == "ok" for r in rows)
gm = sum(r[2] == "ok" for r in rows)
gm_only = [r[0] for r in rows if r[2] == "ok" and r[1] != "ok"]
both = [r for r in rows if r[1] == "ok" and r[2] == "ok"]
print(f"\nsucceeded: tetrafoil {tf}, Gmsh {gm} of {len(rows)} files read; Gmsh only: {', '.join(gm_only) or 'none'}")
if both:
    tx = statistics.median(float(r[3]) for r in both)
    sp = statistics.median(float(r[4]) for r in both)
    print(f"on the {len(both)} files both meshed: median tets tetrafoil/Gmsh {tx:.2f}, median speed-up {sp:.2f}x"
          f" (Gmsh s / tetrafoil s, reading and meshing)")
PYEOF
