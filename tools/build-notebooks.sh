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
# ipykernel 7 can leave a request unread on its shell socket and both sides wait for
# ever (ipython/ipykernel#1554: seen here, one notebook in three runs): 6.x.
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

# The wheel as tests/python_package.rs builds it, in python/target (python/ is a
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

read -r -d '' program <<'PY' || true
import base64, html, os, re, sys, tempfile, time
import jinja2, nbclient, nbformat
from nbclient.exceptions import CellExecutionError
from nbconvert import HTMLExporter

TIMEOUT = 600  # seconds for one cell; the slowest notebook takes under a minute in all
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
WIDGET_STATE = "application/vnd.jupyter.widget-state+json"

# nbconvert's lab template without what it takes from other hosts.
TEMPLATE = r"""{%- extends 'lab/index.html.j2' -%}
{%- block html_head_js -%}{%- endblock html_head_js -%}
{%- block jupyter_widgets -%}{%- endblock jupyter_widgets -%}
{%- block html_head_js_mathjax -%}{%- endblock html_head_js_mathjax -%}
{%- block html_head_js_mermaidjs -%}{%- endblock html_head_js_mermaidjs -%}
{%- block extra_css -%}
<style type="text/css">
.lumiere-widget-note { margin: 0.5em 0; padding: 0.4em 0.8em; border-left: 3px solid #888;
  background: #f4f4f4; font-family: var(--jp-ui-font-family); font-size: 13px; }
.lumiere-widget-note code { font-family: var(--jp-code-font-family); }
</style>
{%- endblock extra_css -%}
"""


def control_text(state):
    """One control of a widget as `name = value`, or None for what is not a control."""
    if "_options_labels" in state and state.get("index") is not None:
        value = state["_options_labels"][state["index"]]
    elif "value" in state and not isinstance(state["value"], (dict, list)):
        value = state["value"]
    else:
        return None
    return f"{state.get('description') or state.get('_model_name', 'value')} = {value!r}"


def static_widget(model_id, models, controls, outputs):
    """Walks a widget's models: its controls' values and its Output widgets' outputs."""
    model = models.get(model_id)
    if model is None:
        return
    state = model.get("state", {})
    if model.get("model_name") == "OutputModel":
        outputs.extend(state.get("outputs", []))
        return
    children = state.get("children")
    if isinstance(children, list):
        for child in children:
            if isinstance(child, str) and child.startswith("IPY_MODEL_"):
                static_widget(child[len("IPY_MODEL_"):], models, controls, outputs)
        return
    text = control_text(state)
    if text is not None:
        controls.append(text)


def freeze_widgets(nb):
    """Each widget view replaced by a note and what the widget displayed when it ran."""
    models = nb.metadata.pop("widgets", {}).get(WIDGET_STATE, {}).get("state", {})
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        frozen = []
        for output in cell.outputs:
            view = output.get("data", {}).get(WIDGET_VIEW)
            if view is None:
                frozen.append(output)
                continue
            controls, shown = [], []
            static_widget(view.get("model_id"), models, controls, shown)
            values = ", ".join(f"<code>{html.escape(c)}</code>" for c in controls)
            note = "An interactive widget: it runs in a live notebook (Jupyter, with lumiere installed)."
            if values:
                note += f" Shown here as it ran, with {values}."
            frozen.append(nbformat.v4.new_output(
                "display_data",
                data={"text/html": f'<div class="lumiere-widget-note">{note}</div>',
                      "text/plain": re.sub("<[^>]+>", "", note)}))
            frozen.extend(nbformat.from_dict(o) for o in shown)
        cell.outputs = frozen


def first_heading(nb):
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    return None


def main(stage, paths):
    exporter = HTMLExporter(
        template_name="lab",
        template_file="lumiere-offline.html.j2",
        extra_loaders=[jinja2.DictLoader({"lumiere-offline.html.j2": TEMPLATE})],
        embed_images=True,
    )
    for path in paths:
        name = os.path.basename(path)
        stem = os.path.splitext(name)[0]
        nb = nbformat.read(path, as_version=4)
        start = time.perf_counter()
        # The kernel's own stderr (ipykernel warns there that it talks over TCP on
        # localhost) is kept, and shown when the notebook fails.
        with tempfile.TemporaryDirectory(prefix=f"lumiere-{stem}-") as cwd, \
                tempfile.TemporaryFile("w+") as log:
            client = nbclient.NotebookClient(
                nb, timeout=TIMEOUT, kernel_name="python3",
                resources={"metadata": {"path": cwd}})
            try:
                client.execute(stderr=log)
            except Exception as e:  # a cell's error, a timeout, a dead kernel, ...
                log.seek(0)
                for line in log:
                    if "Kernel is running over TCP without encryption" not in line:
                        sys.stderr.write(line)
                where = ""
                for index, cell in enumerate(nb.cells):
                    if any(o.get("output_type") == "error" for o in cell.get("outputs", [])):
                        where = f" in cell {index}"
                if isinstance(e, CellExecutionError):
                    print(re.sub(r"\x1b\[[0-9;]*m", "", str(e)), file=sys.stderr)
                    what = f"{e.ename}: {e.evalue}"
                else:
                    what = f"{type(e).__name__}: {e}"
                what = " ".join(what.split())
                print(f"build-notebooks.sh: {name} failed{where}: {what}", file=sys.stderr)
                sys.exit(1)
            elapsed = time.perf_counter() - start
            freeze_widgets(nb)
            title = first_heading(nb)
            if title:
                nb.metadata["title"] = title
            # Markdown images relative to the notebook are embedded from notebooks/.
            page, _ = exporter.from_notebook_node(
                nb, resources={"metadata": {"name": stem, "path": os.path.dirname(path)}})
        target = os.path.join(stage, stem + ".html")
        with open(target, "w", encoding="utf-8") as f:
            f.write(page)
        print(f"build-notebooks.sh: {name} executed in {elapsed:.1f} s,"
              f" {len(page.encode()) // 1024} KiB", file=sys.stderr)


main(sys.argv[1], sys.argv[2:])
PY

# The kernel is the environment's Python (jupyter_client runs `python` as the Python
# that starts it); its kernelspec comes first. Run from the work folder, where no
# lumiere/ folder shadows the installed package.
cd "$work"
PATH="$env/bin:$PATH" JUPYTER_PATH="$env/share/jupyter" \
    "$python" -c "$program" "$stage" "$root"/notebooks/*.ipynb

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
