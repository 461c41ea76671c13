#!/usr/bin/env bash
# Installs the peer renderers when missing: POV-Ray 3.7 (Debian's povray) and
# Mitsuba 3 with NVIDIA's FLIP (PyPI's mitsuba and flip-evaluator, with numpy).
# The exporters' tests render with them; bench/peers.sh times them.
set -euo pipefail
. "$(dirname "$0")/install-lock.sh"
command -v povray >/dev/null 2>&1 || "$(dirname "$0")/apt-install.sh" povray
python3 -c "import mitsuba, flip_evaluator, numpy" 2>/dev/null ||
    python3 -m pip install --quiet mitsuba flip-evaluator numpy
