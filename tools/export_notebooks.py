#!/usr/bin/env python3
"""Executes the course's notebooks, each in a fresh kernel from a temporary working
directory, and exports each as one standalone HTML page (nothing loaded from another
host, plots embedded, widgets frozen into a note and what they drew).

Called by tools/build-notebooks.sh, in its environment:
    python export_notebooks.py OUT_DIR NOTEBOOK.ipynb...
"""
import base64, html, os, re, sys, tempfile, time
import jinja2, nbclient, nbformat
from nbclient.exceptions import CellExecutionError
from nbconvert import HTMLExporter
from patient_kernel import PatientKernelManager

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
                kernel_manager_class=PatientKernelManager,
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
