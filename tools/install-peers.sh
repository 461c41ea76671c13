#!/usr/bin/env bash
# Installs the peer renderers when missing: POV-Ray 3.7 (Debian's povray) and
# Mitsuba 3 with NVIDIA's FLIP (PyPI's mitsuba and flip-evaluator, with numpy),
# and Debian's LLVM 19 (libllvm19), which Mitsuba's JIT-vectorised CPU variants
# (llvm_ad_rgb) load at run time: PyPI's wheels do not ship it. They find it through
# DRJIT_LIBLLVM_PATH (bench/peers.py sets it to the library this package installs).
# The exporters' tests render with them; bench/peers.sh times them.
set -euo pipefail
. "$(dirname "$0")/install-lock.sh"
command -v povray >/dev/null 2>&1 || "$(dirname "$0")/apt-install.sh" povray
"$(dirname "$0")/apt-install.sh" libllvm19
python3 -c "import mitsuba, flip_evaluator, numpy" 2>/dev/null ||
    python3 -m pip install --quiet mitsuba flip-evaluator numpy
