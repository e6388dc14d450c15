#!/usr/bin/env bash
# Installs a project-local OpenCASCADE 7.8.1 (headers, shared libraries, CMake config) into
# `.occt/` at the workspace root, plus a `cmake` binary, from PyPI wheels.
#
# Why: opencascade-sys needs OCCT >= 7.8 and finds it through CMake; distributions often ship
# older versions, and building OCCT from source takes most of an hour. The netgen-occt wheels
# carry a ready 7.8.1 build. The wheels ship only versioned `libTK*.so.7.8.1`, so the unversioned
# `libTK*.so` links the linker looks for are created here.
#
# cmake is pinned below 4: opencascade-sys's CMake probe declares cmake_minimum_required 3.1,
# which CMake 4 rejects.
#
# Idempotent: exits at once when the prefix is complete. Usage: scripts/install-occt.sh [PREFIX]
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prefix="${1:-$root/.occt}"
version="7.8.1"
stamp="$prefix/.installed-$version-cmake3"

if [[ -f "$stamp" ]]; then
    exit 0
fi

python="${PYTHON:-python3}"
mkdir -p "$prefix"
"$python" -m pip install --disable-pip-version-check --quiet --prefix "$prefix" \
    "cmake>=3.24,<4" "netgen-occt-devel==$version" "netgen-occt==$version"

# Headers and libraries land under a python-version-dependent path or directly in the prefix,
# depending on the wheel; locate them instead of guessing.
libdir="$(dirname "$(find "$prefix" -name "libTKernel.so.$version" -print -quit)")"
if [[ -z "$libdir" || "$libdir" == "." ]]; then
    echo "install-occt: libTKernel.so.$version not found under $prefix" >&2
    exit 1
fi
for lib in "$libdir"/libTK*.so."$version"; do
    base="${lib%.$version}"
    ln -sf "$(basename "$lib")" "$base"
done

cfg="$(find "$prefix" -name OpenCASCADEConfig.cmake -print -quit)"
if [[ -z "$cfg" ]]; then
    echo "install-occt: OpenCASCADEConfig.cmake not found under $prefix" >&2
    exit 1
fi
cmake_bin="$(find "$prefix" -path '*/cmake/data/bin/cmake' -type f -print -quit)"
if [[ -z "$cmake_bin" ]]; then
    echo "install-occt: cmake binary not found under $prefix" >&2
    exit 1
fi
# A stable place for build scripts to find cmake without knowing the wheel layout.
mkdir -p "$prefix/bin"
if [[ "$cmake_bin" != "$prefix/bin/cmake" ]]; then
    rm -f "$prefix/bin/cmake"
    ln -s "$cmake_bin" "$prefix/bin/cmake"
fi

echo "libdir=$libdir" >"$stamp"
echo "install-occt: OCCT $version in $prefix (libraries in $libdir)"
