#!/usr/bin/env bash
# Installs what the viewer's tests need when missing: a virtual X server (Xvfb),
# xdotool to send it keys and mouse events, ImageMagick's `import` to take
# screenshots of a window, and the X libraries winit opens at run time.
set -euo pipefail
. "$(dirname "$0")/install-lock.sh"
"$(dirname "$0")/apt-install.sh" xvfb xdotool imagemagick libx11-6 libxcursor1 libxrandr2 libxi6 libxkbcommon-x11-0
