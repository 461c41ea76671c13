#!/usr/bin/env bash
# Installs what the viewer's tests need when missing: a virtual X server (Xvfb),
# xdotool to send it keys and mouse events, ImageMagick's `import` to take
# screenshots of a window, and the X libraries winit opens at run time. Needs
# root (or sudo) and Debian's package archive.
set -euo pipefail
packages=(xvfb xdotool imagemagick libx11-6 libxcursor1 libxrandr2 libxi6 libxkbcommon-x11-0)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
as_root=()
if [ "$(id -u)" -ne 0 ]; then
    as_root=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
