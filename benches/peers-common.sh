# Shared by the peer benchmarks (sourced, with ROOT set): the Gmsh venv, the release build,
# and `fastest` for repeated runs.
VENV=$ROOT/.bench/venv
if [[ ! -x $VENV/bin/python ]] || ! "$VENV/bin/python" -c "import gmsh, numpy" 2>/dev/null; then
  echo "installing gmsh 4.15 and numpy into $VENV" >&2
  python3 -m venv "$VENV"
  "$VENV/bin/pip" install -q "gmsh==4.15.*" numpy
fi
make -s setup
cargo build --release -q
TF=$ROOT/target/release/tetrafoil
PY=$VENV/bin/python

faster() { # line line -> the one with the smaller first field (a failed run's "fail" loses)
  if [[ -z $2 ]]; then
    echo "$1"
  elif [[ -z $1 ]] || "$PY" -c "import sys; a, b = sys.argv[1], sys.argv[2]
try: sys.exit(0 if float(a) < float(b) else 1)
except ValueError: sys.exit(1)" "${2%% *}" "${1%% *}"; then
    echo "$2"
  else
    echo "$1"
  fi
}

fastest() { # command... -> its output line with the smallest first field, over REPEAT runs
  local best=""
  for _ in $(seq "$REPEAT"); do
    best=$(faster "$best" "$("$@")")
  done
  echo "$best"
}
