#!/usr/bin/env bash
# Directional refinement benchmark: tetrafoil's own wall layers against MMG3D 5.8 (mmgpy,
# anisotropic remeshing, one thread) of tetrafoil's isotropic mesh to the metric of the same
# 1-D distribution (benches/mmg_refine.py), on the native wing sample, at aspect ratios
# δ/first of 25 and 100. One table: seconds, tets, largest dihedral angle of the stretched tets
# (centroid within the distribution's thickness of the wall) and first-layer height over the
# requested first spacing at the wall nodes (scripts/refine_stats.py, same wall, same thickness).
# Times: "s" is each tool's whole way from the case file — tetrafoil's meshing stages (load and
# write excluded) with refinement; for MMG, tetrafoil's isotropic meshing stages plus the remesh
# call — and "remesh" MMG's call alone.
# Usage: [SIZE=δ] [GROWTH=G] [CONSTANT=C] [ASPECTS="25 100"] benches/refine-peers.sh
# SIZE (0.05 by default) is δ of the aspect ratio and the distribution's largest spacing; the
# wing's wall triangles have edges of 0.008–0.06 (median 0.023) and the layers of both tools
# stop where they reach the local spacing.
# Needs cargo and python3; Gmsh, mmgpy, meshio and scipy (pip, into .bench/venv) are installed
# when missing.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
CASE=${CASE:-$ROOT/samples/wing/case.toml}
WALL=${WALL:-wing_upper,wing_lower,wing_tip}
SIZE=${SIZE:-0.05}
GROWTH=${GROWTH:-1.2}
CONSTANT=${CONSTANT:-3}
ASPECTS=${ASPECTS:-25 100}
WORK=${REFINE_BENCH_DIR:-/tmp/tetrafoil-refine-bench}
mkdir -p "$WORK"

# shellcheck source=benches/peers-common.sh
source "$ROOT/benches/peers-common.sh"
if ! "$PY" -c "import mmgpy, meshio, scipy" 2>/dev/null; then
  echo "installing mmgpy, meshio and scipy into $VENV" >&2
  "$VENV/bin/pip" install -q mmgpy meshio scipy
fi

meshing() { # report.json -> seconds of its stages but loading and writing
  "$PY" -c "import json,sys; r=json.load(open(sys.argv[1]))
print(f\"{sum(s['seconds'] for s in r['stages'] if s['stage'] not in ('load', 'write')):.3f}\")" "$1"
}

stats() { # mesh first thickness wall-option... -> "p50 p90 p99 max median p10 p90"
  "$PY" scripts/refine_stats.py "$1" --first "$2" --thickness "$3" "${@:4}" | "$PY" -c "
import json,sys; r=json.load(sys.stdin); d=r['max_dihedral']; f=r['first_layer']
print(' '.join(f'{d[k]:.1f}' for k in ('p50','p90','p99','max')), ' '.join(f'{f[k]:.2f}' for k in ('median','p10','p90')))"
}

row() { # tool aspect seconds remesh tets stats...
  printf "%-10s %6s %8s %8s %9s | %6s %6s %6s %6s | %6s %6s %6s\n" "$@"
}

"$TF" -q mesh "$CASE" --threads 1 -o "$WORK/iso.mesh" --report "$WORK/iso.json"
iso_s=$(meshing "$WORK/iso.json")
# MMG's output keeps the triangle refs but not the names of tetrafoil's MEDIT header comments
# (ref = marker index + 1, markers in order of first appearance: src/io/medit.rs)
WALL_REFS=$("$PY" -c "import sys; sys.path.insert(0, 'scripts'); import refine_stats as r
print(','.join(map(str, r.refs_of_names(sys.argv[1], sys.argv[2].split(',')))))" "$WORK/iso.mesh" "$WALL")

row tool aspect s remesh tets p50 p90 p99 max median p10 p90
declare -A ratio
for aspect in $ASPECTS; do
  first=$("$PY" -c "print($SIZE / $aspect)")
  thick=$("$PY" -c "import sys; sys.path.insert(0, 'scripts'); import refine_stats as r
print(r.thickness($first, $GROWTH, $CONSTANT, $SIZE))")

  mmg=$("$PY" benches/mmg_refine.py "$WORK/iso.mesh" --wall-names "$WALL" --first "$first" \
    --growth "$GROWTH" --constant "$CONSTANT" --size "$SIZE" -o "$WORK/mmg$aspect.mesh" | tail -1)
  read -r mmg_remesh mmg_tets <<<"$("$PY" -c "import json,sys; r=json.loads(sys.argv[1]); print(f\"{r['seconds']:.3f} {r['tets']}\")" "$mmg")"
  mmg_s=$("$PY" -c "print(f'{$iso_s + $mmg_remesh:.3f}')")
  read -r -a ms <<<"$(stats "$WORK/mmg$aspect.mesh" "$first" "$thick" --wall-ref "$WALL_REFS")"
  row mmg "$aspect" "$mmg_s" "$mmg_remesh" "$mmg_tets" "${ms[@]}"

  if "$TF" -q mesh "$CASE" --threads 1 --refine-faces "$WALL" --first "$first" --growth "$GROWTH" \
      --constant "$CONSTANT" -o "$WORK/tf$aspect.vtu" -o "$WORK/tf$aspect.mesh" \
      --report "$WORK/tf$aspect.json" 2>"$WORK/tf$aspect.err"; then
    tf_s=$(meshing "$WORK/tf$aspect.json")
    tf_tets=$("$PY" -c "import json,sys; print(json.load(open(sys.argv[1]))['quality']['tets'])" "$WORK/tf$aspect.json")
    read -r -a ts <<<"$(stats "$WORK/tf$aspect.mesh" "$first" "$thick" --wall-names "$WALL")"
    row tetrafoil "$aspect" "$tf_s" - "$tf_tets" "${ts[@]}"
    ratio[$aspect]=$("$PY" -c "print(f'time {$tf_s / $mmg_s:.2f}x, p99 max dihedral {${ts[2]} / ${ms[2]}:.2f}x')")
  else
    if grep -q "unexpected argument" "$WORK/tf$aspect.err"; then
      echo "tetrafoil: refinement not available"
    else
      echo "tetrafoil $aspect: failed: $(head -c 300 "$WORK/tf$aspect.err" | tr '\n' ' ')"
    fi
  fi
done
for aspect in $ASPECTS; do
  if [[ -n ${ratio[$aspect]:-} ]]; then echo "aspect $aspect: tetrafoil/MMG ${ratio[$aspect]}"; fi
done
echo "aspect = SIZE/first (SIZE=$SIZE, growth $GROWTH, $CONSTANT constant layers); s: from the case file (MMG: tetrafoil's"
echo "isotropic mesh, ${iso_s}s, + remesh); p50..max: largest dihedral angle (degrees) of the tets within the distribution's"
echo "thickness of the wall; median/p10/p90: first-layer height at the wall nodes over first."
