#!/usr/bin/env bash
# The CGNS library (loaded by `tetrafoil` at run time for .cgns output) and its checker
# `cgnscheck`, for the CGNS writer's test (tests/prisms.rs): Debian's `cgns-convert`, which
# brings libcgns. Called by `make test`; does nothing when both are there.
set -euo pipefail
if [ -x /usr/bin/cgnscheck ] && ls /usr/lib/*/libcgns.so* >/dev/null 2>&1; then
    exit 0
fi
if [ "$(id -u)" != 0 ]; then
    echo "install-cgns: not root; install Debian's cgns-convert (and libcgns-dev) for CGNS output and its test" >&2
    exit 0
fi
echo "install-cgns: apt-get install cgns-convert libcgns-dev (CGNS output and cgnscheck)"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq cgns-convert libcgns-dev >/dev/null
test -x /usr/bin/cgnscheck
