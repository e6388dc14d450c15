#!/usr/bin/env bash
# Outside readers the writer tests open our files with (tests/io.rs, tests/prisms.rs): meshio
# and Gmsh's Python API (scripts/check-msh.py), from PyPI, in a project-local virtual
# environment (.readers/venv). Called by `make test`; does nothing when both are there.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.readers/venv
if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c "import meshio, gmsh" 2>/dev/null; then
    exit 0
fi
echo "install-readers: meshio and gmsh into $venv (for the writer tests)"
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install --disable-pip-version-check --quiet "meshio>=5.3" numpy "gmsh>=4.11"
"$venv/bin/python" -c "import meshio, gmsh"
