#!/usr/bin/env bash
# Installs Debian's Chromium when missing: the gallery's tests open the generated
# site in it, headless.
set -euo pipefail
. "$(dirname "$0")/install-lock.sh"
command -v chromium >/dev/null 2>&1 || "$(dirname "$0")/apt-install.sh" chromium
