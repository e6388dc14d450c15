#!/usr/bin/env bash
# OpenFOAM's gmshToFoam and checkMesh, for the hybrid-mesh test (tests/prisms.rs): Debian's
# `openfoam` package (v1912). Called by `make test`; does nothing when checkMesh is there.
# The tests run the tools with WM_PROJECT_DIR=/usr/share/openfoam instead of sourcing
# OpenFOAM's bashrc.
set -euo pipefail
if [ -x /usr/bin/checkMesh ] && [ -x /usr/bin/gmshToFoam ]; then
    exit 0
fi
if [ "$(id -u)" != 0 ]; then
    echo "install-openfoam: not root; install Debian's openfoam package to run the checkMesh test" >&2
    exit 0
fi
echo "install-openfoam: apt-get install openfoam (for the checkMesh test)"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq openfoam >/dev/null
test -x /usr/bin/checkMesh
