#!/usr/bin/env bash
# Outside readers the writer tests open our files with (tests/io.rs): meshio, from PyPI, in a
# project-local virtual environment (.readers/venv). Called by `make test`; does nothing when
# the environment is already there.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.readers/venv
if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c "import meshio" 2>/dev/null; then
    exit 0
fi
echo "install-readers: meshio into $venv (for the writer tests)"
python3 -m venv "$venv"
"$venv/bin/pip" install --disable-pip-version-check --quiet "meshio>=5.3" numpy
"$venv/bin/python" -c "import meshio"
