#!/usr/bin/env bash
# The peer benchmark: lumiere, POV-Ray 3.7 and Mitsuba 3 on the same scenes, timed
# as whole processes, each image measured against Mitsuba's converged render; and
# lumiere's cost growth with image size, polygon count and lights. Writes
# BENCHMARKS.md. Installs the peers when missing.
#
#   bench/peers.sh            # the whole run (512 x 512, 5 runs each)
#   bench/peers.sh --quick    # a few minutes (256 x 256, 3 runs, smaller references)
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-peers.sh
cargo build --release --quiet
exec python3 bench/peers.py "$@"
