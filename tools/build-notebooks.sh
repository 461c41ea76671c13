#!/usr/bin/env bash
# Executes the course's notebooks (notebooks/*.ipynb), each in a fresh `python3` kernel
# from a temporary working directory, and exports each with its outputs as one
# standalone HTML page, NN-topic.html, into target/web/notebooks/ (or
# $LUMIERE_NOTEBOOKS_OUT), where `lumiere gallery` finds them. Prints the output folder
# on its last line. Installs what is missing first: a virtual environment of its own,
# target/notebooks/env (Jupyter's tools and maturin from PyPI), and the lumiere wheel
# built by maturin (incrementally, in python/target), reinstalled when it changed.
# Safe to call from several tests at once.
#
# The pages load nothing from another host: the template drops require.js, MathJax,
# Mermaid and the widget renderer, which nbconvert's lab template takes from CDNs (the
# notebooks have no math nor diagrams), its CSS is inlined, plots are base64 PNGs, and
# images of the markdown are embedded. A widget cannot run without a kernel: each
# shows as a note with its controls' values, followed by what it displayed when run.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${LUMIERE_NOTEBOOKS_OUT:-$root/target/web/notebooks}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
work="$root/target/notebooks"
env="$work/env"
python="$env/bin/python"
mkdir -p "$work"
# ipykernel 7 can leave a request that arrives while it sends a reply unread on its
# shell socket (ipython/ipykernel#1554), and nbclient sends there during a widget's
# cell: 6.x, which sends its replies through the stream. (The hang seen here was the
# client's own: see PatientChannel below.)
requirements=("maturin>=1.5,<2" nbconvert nbclient nbformat "ipykernel>=6.29,<7" matplotlib ipywidgets)

# The environment, inside the install lock (a caller that waited finds it made).
(
    . "$root/tools/install-lock.sh"
    if [ "$(cat "$env/.requirements" 2>/dev/null)" != "${requirements[*]}" ] ||
        ! "$python" -c 'import maturin, nbconvert, nbclient, nbformat, ipykernel, matplotlib, ipywidgets' \
            >/dev/null 2>&1; then
        echo "build-notebooks.sh: making $env" >&2
        rm -rf "$env"
        python3 -m venv "$env"
        "$python" -m pip install --quiet --upgrade pip >&2
        "$python" -m pip install --quiet "${requirements[@]}" >&2
        echo "${requirements[*]}" >"$env/.requirements"
    fi
)

# One build at a time: the wheel, its install and the pages.
exec 8>"$work/build.lock"
flock 8

# The wheel as tests/suite/project/python_package.rs builds it, in python/target (python/ is a
# workspace of its own) so that a second build is incremental.
wheels="$work/wheels"
rm -rf "$wheels"
CARGO_TARGET_DIR="$root/python/target" "$python" -m maturin build --release \
    --manifest-path "$root/python/Cargo.toml" --out "$wheels" >&2
wheel="$(ls "$wheels"/*.whl)"
# What the wheel holds: its RECORD (each file's hash), less the SBOM, whose serial
# number and date change with every build.
digest="$("$python" -c '
import hashlib, sys, zipfile
z = zipfile.ZipFile(sys.argv[1])
record = next(n for n in z.namelist() if n.endswith(".dist-info/RECORD"))
lines = [l for l in z.read(record).decode().splitlines() if "/sboms/" not in l]
print(hashlib.sha256("\n".join(sorted(lines)).encode()).hexdigest())
' "$wheel")"
if [ "$(cat "$env/.lumiere-wheel" 2>/dev/null)" != "$digest" ] ||
    ! (cd "$work" && "$python" -c 'import lumiere' >/dev/null 2>&1); then
    (
        . "$root/tools/install-lock.sh"
        "$python" -m pip install --quiet --force-reinstall --no-deps "$wheel" >&2
        "$python" -m pip install --quiet "$wheel" >&2 # its dependencies, when missing
    )
    echo "$digest" >"$env/.lumiere-wheel"
fi

# The pages are made beside the output and swapped in whole when all are done.
stage="$(mktemp -d "$out.XXXXXX")"
trap 'rm -rf "$stage" "$out.old"' EXIT
chmod 755 "$stage"


# The kernel is the environment's Python (jupyter_client runs `python` as the Python
# that starts it); its kernelspec comes first. Run from the work folder, where no
# lumiere/ folder shadows the installed package.
cd "$work"
PATH="$env/bin:$PATH" JUPYTER_PATH="$env/share/jupyter" \
    "$python" "$root/tools/export_notebooks.py" "$stage" "$root"/notebooks/*.ipynb

# No page may load anything from another host.
if grep -l -E '<(script|link|img|iframe)[^>]*(src|href)="(https?:)?//' "$stage"/*.html >&2; then
    echo "build-notebooks.sh: the pages above load something from another host" >&2
    exit 1
fi

if ! diff -r -q "$stage" "$out" >/dev/null 2>&1; then
    rm -rf "$out.old"
    mv "$out" "$out.old"
    mv "$stage" "$out"
fi
echo "$out"
