#!/usr/bin/env bash
# OpenCASCADE built in against OpenCASCADE as a geometry plugin (libtetrafoil_occt.so, the
# plugin interface of include/tetrafoil_geometry.h): every CAD file of ../shared/cad meshed by
# the release binary built with `--features occt` both ways in one run (and the plugin through
# the default binary, which links no OCCT, must agree too), and by OLD_BIN too when given (a binary from
# before the plugin interface, to compare with the code as it was). Per file: whether the
# meshes are the same (surface triangles, tets, enclosed volume, dihedral range, or the same
# error), and the fastest of REPEAT runs (3 by default) of each, in seconds of meshing (the
# report's stages: load, estimate, curves, surfaces, volume; not the output file), run in turn
# so a slow spell of the shared machine hits both. Then the summed times and their ratios.
# Usage: [REPEAT=N] [OLD_BIN=path/to/old/tetrafoil] [TIMEOUT=S] benches/plugin-occt.sh [FILE ...]
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
CAD=${CAD_DIR:-$ROOT/../shared/cad}
REPEAT=${REPEAT:-3}
TIMEOUT=${TIMEOUT:-600}
WORK=${PLUGIN_BENCH_DIR:-/tmp/tetrafoil-plugin-bench}
OLD_BIN=${OLD_BIN:-}
mkdir -p "$WORK"
FILES=("$@")
if ((${#FILES[@]} == 0)); then
  mapfile -t FILES < <(ls "$CAD"/*.st[ep]* "$CAD"/*.ig[es]* "$CAD"/*.brep 2>/dev/null | sort)
fi
# The binary with OpenCASCADE inside, kept aside; then the default one and the plugins.
cargo build -q --release --features occt
cp target/release/tetrafoil "$WORK/tetrafoil-occt"
make -s plugins >/dev/null
TF=$WORK/tetrafoil-occt
PLUGIN=$ROOT/target/release/libtetrafoil_occt.so

one() { # binary, file, extra args... -> "seconds signature"
  local bin=$1 file=$2 report=$WORK/r.json
  shift 2
  rm -f "$report"
  if timeout "$TIMEOUT" "$bin" "$@" -q mesh "$file" -o "$WORK/x.vtu" --report "$report" \
      >"$WORK/out.txt" 2>&1; then
    python3 - "$report" <<'PYEOF'
import json, sys
r = json.load(open(sys.argv[1]))
q, v = r["quality"], r["volume"]["validity"]
work = sum(s["seconds"] for s in r["stages"] if s["stage"] not in ("sizing", "write"))
print(f'{work:.3f} tri={r["surface_mesh"]["triangles"]},tets={q["tets"]},vol={v["volume"]:.10g},'
      f'dih={q["min_dihedral"]:.6f}..{q["max_dihedral"]:.6f}')
PYEOF
  else
    echo "- error:$(grep -i 'error' "$WORK/out.txt" | head -1 | md5sum | cut -c1-8)"
  fi
}

fastest() { # binary, file, extra args -> "seconds signature" (fastest of REPEAT)
  local best="" sig="" s g
  for _ in $(seq "$REPEAT"); do
    read -r s g <<<"$(one "$@")"
    sig=$g
    if [[ $s != - ]] && { [[ -z $best ]] || (($(echo "$s < $best" | bc))); }; then best=$s; fi
  done
  echo "${best:--} $sig"
}

printf "%-34s %9s %9s %7s %5s" file built-in plugin ratio same
[[ -n $OLD_BIN ]] && printf " %9s %7s %5s" old ratio same
printf "\n"
sum_b=0 sum_p=0 sum_o=0 differ=0
for f in "${FILES[@]}"; do
  name=$(basename "$f")
  read -r sb gb <<<"$(fastest "$TF" "$f")"
  read -r sp gp <<<"$(fastest "$TF" "$f" --plugin "$PLUGIN")"
  read -r _ gd <<<"$(one "$ROOT/target/release/tetrafoil" "$f")" # default binary, plugin beside it
  same=yes
  [[ $gb == "$gp" && $gb == "$gd" ]] || { same=NO; differ=$((differ + 1)); }
  ratio=-
  if [[ $sb != - && $sp != - ]]; then
    ratio=$(echo "scale=3; $sp / $sb" | bc)
    sum_b=$(echo "$sum_b + $sb" | bc)
    sum_p=$(echo "$sum_p + $sp" | bc)
  fi
  printf "%-34s %9s %9s %7s %5s" "$name" "$sb" "$sp" "$ratio" "$same"
  if [[ -n $OLD_BIN ]]; then
    read -r so go <<<"$(fastest "$OLD_BIN" "$f")"
    osame=yes
    [[ $gb == "$go" ]] || osame=NO
    oratio=-
    if [[ $sb != - && $so != - ]]; then
      oratio=$(echo "scale=3; $sb / $so" | bc)
      sum_o=$(echo "$sum_o + $so" | bc)
    fi
    printf " %9s %7s %5s" "$so" "$oratio" "$osame"
  fi
  printf "\n"
done
echo "summed seconds over files meshed both ways: built-in $sum_b, plugin $sum_p," \
  "plugin/built-in $(echo "scale=3; $sum_p / $sum_b" | bc)"
[[ -n $OLD_BIN ]] && echo "old binary $sum_o: built-in now / old $(echo "scale=3; $sum_b / $sum_o" | bc)"
echo "files whose plugin mesh differs from the built-in one: $differ of ${#FILES[@]}"
