#!/usr/bin/env bash
# Delaunay kernel benchmark: tetrafoil (1 thread and all threads) vs CGAL and TetGen, one run,
# one table. Usage: benches/delaunay-peers.sh [--quick]
#   --quick   smaller sets (10^4 and 10^5 uniform, 30^3 lattice, 10^4 on a sphere)
# Needs: cargo, g++, and (installed here when missing) tetgen and libcgal-dev.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
QUICK=0
[[ "${1:-}" == "--quick" ]] && QUICK=1
WORK=${DELAUNAY_BENCH_DIR:-/tmp/tetrafoil-delaunay-bench}
mkdir -p "$WORK"

# --- peers -------------------------------------------------------------------------------
need=()
command -v tetgen >/dev/null || need+=(tetgen)
[[ -f /usr/include/CGAL/Delaunay_triangulation_3.h ]] || need+=(libcgal-dev)
command -v g++ >/dev/null || need+=(g++)
if ((${#need[@]})); then
  echo "installing: ${need[*]}" >&2
  SUDO=""; [[ $(id -u) -ne 0 ]] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
fi
CGAL_BIN=$WORK/cgal_delaunay
if [[ ! -x $CGAL_BIN || benches/cgal/delaunay.cpp -nt $CGAL_BIN ]]; then
  echo "compiling CGAL driver" >&2
  g++ -O3 -DNDEBUG -std=c++17 benches/cgal/delaunay.cpp -o "$CGAL_BIN" -lgmp -lmpfr
fi

# --- tetrafoil ---------------------------------------------------------------------------
cargo build --release --example delaunay_bench -q
TF=$ROOT/target/release/examples/delaunay_bench
THREADS=${TETRAFOIL_THREADS:-$(nproc)}   # the "all threads" run: rayon pool size

# --- point sets --------------------------------------------------------------------------
if ((QUICK)); then
  SETS=("uniform 10000" "uniform 100000" "lattice 27000" "sphere 10000")
else
  SETS=("uniform 100000" "uniform 1000000" "lattice 1000000" "sphere 100000")
fi
SETS+=("uniform 300")   # small set: exact tet count comparison with CGAL

name_of() { local k=$1 n=$2; echo "${k}-${n}"; }
for s in "${SETS[@]}"; do
  read -r kind n <<<"$s"
  f=$WORK/$(name_of "$kind" "$n").xyz
  [[ -f $f ]] || "$TF" gen "$kind" "$n" "$f" 7
  [[ -f ${f%.xyz}.node ]] || "$TF" node "$f" "${f%.xyz}.node"
done

# --- runs --------------------------------------------------------------------------------
field() { sed -n "s/.*\b$1 \([0-9.e+-]*\).*/\1/p" <<<"$2"; }
ROWS=()
row() { ROWS+=("$1|$2|$3|$4|$5|${6:--}"); }   # set tool tets seconds bytes/tet cpu-seconds
for s in "${SETS[@]}"; do
  read -r kind n <<<"$s"
  set=$(name_of "$kind" "$n")
  f=$WORK/$set.xyz
  echo "running $set" >&2
  out=$("$TF" run "$f" --threads 1 $([[ $n -le 100000 ]] && echo --check))
  [[ $out == *FAILED* ]] && echo "CHECK FAILED on $set: $out" >&2
  row "$set" "tetrafoil-1t" "$(field tets "$out")" "$(field seconds "$out")" "$(field bytes_per_tet "$out")" "$(field cpu_seconds "$out")"
  if ((THREADS > 1)); then
    out=$("$TF" run "$f" --threads "$THREADS" $([[ $n -le 100000 ]] && echo --check))
    [[ $out == *FAILED* ]] && echo "CHECK FAILED on $set ($THREADS threads): $out" >&2
    row "$set" "tetrafoil-${THREADS}t" "$(field tets "$out")" "$(field seconds "$out")" "$(field bytes_per_tet "$out")" "$(field cpu_seconds "$out")"
  fi
  out=$("$CGAL_BIN" "$f")
  row "$set" "cgal" "$(field tets "$out")" "$(field seconds "$out")" "-"
  # TetGen: -V verbose prints "Delaunay seconds:  X"; -N -E -F skip writing nodes/elements/faces.
  tg=$(cd "$WORK" && tetgen -V -N -E -F -I "$set.node" 2>&1 || true)
  tsec=$(sed -n 's/.*Delaunay seconds: *\([0-9.]*\).*/\1/p' <<<"$tg" | head -1)
  ttets=$(sed -n 's/.*Mesh tetrahedra: *\([0-9]*\).*/\1/p' <<<"$tg" | head -1)
  row "$set" "tetgen" "${ttets:-?}" "${tsec:-?}" "-"
done

# --- table -------------------------------------------------------------------------------
echo "machine: $(nproc) cores, load average at the end of the runs:$(uptime | sed 's/.*load average://')"
printf '%-16s %-14s %10s %9s %7s %12s %9s %9s\n' set tool tets seconds cpu-s tets/s bytes/tet vs-cgal
declare -A CG
for r in "${ROWS[@]}"; do
  IFS='|' read -r set tool tets secs bpt cpu <<<"$r"
  [[ $tool == cgal ]] && CG[$set]=$secs
done
for r in "${ROWS[@]}"; do
  IFS='|' read -r set tool tets secs bpt cpu <<<"$r"
  rate=$(awk -v t="$tets" -v s="$secs" 'BEGIN{ if (s+0>0 && t+0>0) printf "%.3g", t/s; else print "-" }')
  ratio=$(awk -v c="${CG[$set]:-0}" -v s="$secs" 'BEGIN{ if (s+0>0 && c+0>0) printf "%.2fx", c/s; else print "-" }')
  printf '%-16s %-14s %10s %9s %7s %12s %9s %9s\n' "$set" "$tool" "$tets" "$secs" "$cpu" "$rate" "$bpt" "$ratio"
done
echo "(vs-cgal = CGAL seconds / tool seconds: >1 is faster than CGAL; tets/s counts finite tets;"
echo " cpu-s = tetrafoil's CPU seconds over all threads: on a loaded machine a wall time well above"
echo " cpu-s / threads means the threads did not get their cores)"
# Tet counts must agree with CGAL where the Delaunay triangulation is unique (points in
# general position); on degenerate sets (lattice) each tool may pick a different valid one.
# The parallel run must give the serial run's triangulation (same tet count) on every set.
declare -A TFC TFP CGC
for r in "${ROWS[@]}"; do
  IFS='|' read -r set tool tets secs bpt cpu <<<"$r"
  [[ $tool == tetrafoil-1t ]] && TFC[$set]=$tets
  [[ $tool == "tetrafoil-${THREADS}t" && $THREADS -gt 1 ]] && TFP[$set]=$tets
  [[ $tool == cgal ]] && CGC[$set]=$tets
done
for set in "${!TFC[@]}"; do
  if [[ ${TFC[$set]} == "${CGC[$set]}" ]]; then m=same; else m=different; fi
  p=""
  if [[ -n ${TFP[$set]:-} ]]; then
    if [[ ${TFP[$set]} == "${TFC[$set]}" ]]; then p=", ${THREADS} threads same as 1"; else p=", ${THREADS} threads DIFFERENT (${TFP[$set]})"; fi
  fi
  echo "tet count $set: tetrafoil ${TFC[$set]}, cgal ${CGC[$set]} ($m)$p"
done | sort
