#!/usr/bin/env bash
# Headless Chromium for the web page's browser test (tests/service_page.rs): Debian's
# `chromium` package, installed when missing. Called by `make test`; CI runs on a clean
# machine where this is the only thing that brings the browser.
set -euo pipefail
if command -v chromium >/dev/null 2>&1; then
    exit 0
fi
if ! command -v apt-get >/dev/null 2>&1; then
    echo "install-chromium: no chromium and no apt-get: install Chromium and put it on PATH" >&2
    exit 1
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
    SUDO="sudo"
fi
echo "install-chromium: installing Debian's chromium (for the web page test)"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends chromium
command -v chromium >/dev/null
