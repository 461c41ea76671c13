#!/usr/bin/env bash
# Installs Debian's Chromium when missing: the gallery's tests open the generated
# site in it, headless. Needs root (or sudo) and Debian's package archive.
set -euo pipefail
if command -v chromium >/dev/null 2>&1; then
    exit 0
fi
as_root=()
if [ "$(id -u)" -ne 0 ]; then
    as_root=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends chromium >/dev/null
command -v chromium
