"""The results page: results/report/index.html (`make report`), built from the committed
results and references, for reading every figure's numbers and looking at its images.

Per paper and figure: the paper's claim, our table rows (with intervals and verdicts), the
convergence plot, and an image comparison (experiments/report/viewer.js) of the reference and
each technique's seed-0 render at the table's equal-sample budget and at its equal-time budget.
The images are the runs' own EXRs where they are on disk (after `make run`), else rendered
again: at the equal-sample budget as the run was, and for equal time at the samples the run
reached in its time (deterministic, so the page is the same on any machine). They go in as
half floats, so exposure is live, one gzip + base64 script per figure (data/<figure>.js),
which the page loads with <script> elements: the page works from file:// with no server and
no network. The viewer's libraries (panzoom, d3-scale-chromatic) are copied from
experiments/report/node_modules (`npm ci`, run by `make report`)."""
from __future__ import annotations

import base64
import functools
import gzip
import html
import json
import re
import shutil
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import (config, exr, jobs, matrix_plot, matrix_tables, paths, provenance, renders,
               tables)
from .config import Experiment, Profile
from .errors import SceneRejected
from .records import SPP, TIME, RunRecord, SummaryEntry, TechniqueBudget
from .results import Results

VIEWER = paths.ROOT / "experiments" / "report"
REPORT = paths.RESULTS / "report"
# The viewer's libraries (UMD builds, which file:// pages can load), in load order.
LIBRARIES = ["panzoom/dist/panzoom.min.js", "d3-color/dist/d3-color.min.js",
             "d3-interpolate/dist/d3-interpolate.min.js",
             "d3-scale-chromatic/dist/d3-scale-chromatic.min.js"]
SEED = 0


@dataclass(frozen=True)
class Shown:
    """An image of a comparison: its label, its technique (or "reference"), its EXR and the
    table row it shows (None: the reference)."""
    label: str
    key: str
    exr: Path
    row: TechniqueBudget | None = None


def _run_of(doc: Results, row: SummaryEntry) -> RunRecord | None:
    return next((r for r in doc.runs if r.key == row.key and r.seed == SEED), None)


def _render_again(exp: Experiment, profile: Profile, run: RunRecord, out: Path) -> Path:
    """The run rendered again into `out`: at its spp budget, or for an equal-time run at the
    samples it reached (a sweep of samples per primary ray, `samples_at`, at its time)."""
    technique = exp.techniques[run.technique]
    if run.kind == SPP:
        renders.render_at_spp(exp, profile, technique, out, SEED, int(run.budget))
    elif technique.samples_at:
        renders.render_technique(exp, profile, technique, out, SEED, seconds=run.budget)
    else:
        renders.render_technique(exp, profile, technique, out, SEED, spp=run.spp)
    return out


def _label(row: SummaryEntry, run: RunRecord) -> str:
    if row.kind == SPP:
        return f"{row.technique}, {row.budget:g} spp"
    return f"{row.technique}, {row.budget:.3g} s ({run.spp} spp)"


def images(exp: Experiment, doc: Results, workers: int) -> list[Shown]:
    """The reference, then each table row's seed-0 render (rendered again where absent)."""
    profile = exp.profiles[doc.profile]
    shown = [Shown("reference", "reference", paths.output(doc.reference.file))]
    missing = []
    scratch = paths.RENDERS / "report" / doc.profile / doc.experiment
    for row in tables.table_rows(doc):
        run = _run_of(doc, row)
        if run is None:
            continue
        file = paths.output(run.file)
        if not file.exists():
            file = scratch / run.file_name()
            file.parent.mkdir(parents=True, exist_ok=True)
            missing.append(functools.partial(_render_again, exp, profile, run, file))
        shown.append(Shown(_label(row, run), row.technique, file, row.key))
    jobs.run_parallel(f"{doc.experiment} report renders", missing, [1.0] * len(missing),
                      workers)
    return shown


def _encoded(file: Path) -> tuple[int, int, str]:
    """Width, height and the RGB pixels as base64 of gzip of little-endian half floats."""
    _, pixels = exr.read_exr(file, channels=3)
    halves = np.clip(pixels, -65504, 65504).astype("<f2")
    return (pixels.shape[1], pixels.shape[0],
            base64.b64encode(gzip.compress(halves.tobytes(), 6, mtime=0)).decode("ascii"))


def figure_id(doc: Results) -> str:
    return figure_id_of(doc.experiment)


def _data_script(doc: Results, shown: list[Shown]) -> str:
    encoded = [(s, _encoded(s.exr)) for s in shown]
    width, height = encoded[0][1][0], encoded[0][1][1]
    for s, (w, h, _) in encoded:
        if (w, h) != (width, height):
            raise ValueError(f"{s.exr}: {w}×{h}, the reference is {width}×{height}")
    items = ",\n".join(f'{{"label": {_js(s.label)}, "key": {_js(s.key)}, "data": "{data}"}}'
                       for s, (_, _, data) in encoded)
    return (f'ReportViewer.register({_js(figure_id(doc))}, {{"width": {width}, '
            f'"height": {height}, "images": [\n{items}]}});\n')


def _js(text: str) -> str:
    """A JSON string literal that is also safe inside a <script> file."""
    return json.dumps(text).replace("</", "<\\/")


def _cell(text: str) -> str:
    """A Markdown table cell as HTML: escaped, `code` and *emphasis* kept."""
    out = html.escape(text.strip())
    out = re.sub(r"`([^`]+)`", r"<code>\1</code>", out)
    return re.sub(r"\*([^*]+)\*", r"<em>\1</em>", out)


def _table_html(doc: Results) -> str:
    lines = tables.main_table([doc])
    head, body = lines[0], lines[2:]
    cells = [[c for c in line.strip().strip("|").split("|")] for line in [head] + body]
    rows = ["<tr>" + "".join(f"<th>{_cell(c)}</th>" for c in cells[0]) + "</tr>"]
    rows += ["<tr>" + "".join(f"<td>{_cell(c)}</td>" for c in r) + "</tr>" for r in cells[1:]]
    return "<table>" + "".join(rows) + "</table>"


def _claim(doc: Results) -> str:
    if not doc.paper:
        return '<p class="claim">The paper reports no number for this figure.</p>'
    parts = []
    for p in doc.paper:
        values = ", ".join(f"{html.escape(t)} {v:g}" for t, v in p.values.items())
        parts.append(f"{html.escape(p.source)} ({p.metric} at {p.spp} spp: {values})")
    return '<p class="claim"><b>The paper:</b> ' + "; ".join(parts) + "</p>"


def _section(doc: Results, stale: bool) -> str:
    fid = figure_id(doc)
    figure = tables.figure_of(doc)
    plot = paths.PLOTS / doc.paper_name / f"{figure}_convergence{paths.suffix(doc.profile)}.png"
    plot_html = (f'<img class="plot" src="plots/{doc.paper_name}/{plot.name}" '
                 f'alt="convergence of {html.escape(doc.experiment)}">' if plot.exists() else "")
    warning = ('<p class="stale">Its config has changed since these results were made.</p>'
               if stale else "")
    prov = doc.provenance
    return f"""
<section class="figure" id="{fid}">
<h3>{html.escape(doc.experiment)}</h3>
{warning}
<details><summary>What is compared ({doc.resolution[0]}×{doc.resolution[1]}, {len(doc.seeds)}
seeds, commit <code>{(prov.git_commit or "unknown")[:10]}</code>)</summary>
<p>{html.escape(doc.description)}</p></details>
{_claim(doc)}
{_table_html(doc)}
{plot_html}
<div class="viewer" data-figure="{fid}" data-src="data/{fid}.js">
loading the images… (keys: 1–9 or ←/→ choose the image, e switches the right pane to its
relative error, +/− exposure; wheel zooms, drag pans, both panes together)</div>
</section>"""


def _matrix_overview(profile_name: str, indices: dict[str, dict[TechniqueBudget, int]]) -> str:
    """The cross-paper matrix as tables of scenes by techniques; each measured cell links to
    its scene's comparison below, showing the technique's equal-time render."""
    parts = ['<p>Each cell: relMSE gain over the scene\'s default technique at equal time '
             '(&gt; 1: better) with its 95 % interval over seeds; bold where it excludes 1. '
             'Click a cell for its images. <code>refused</code>: the renderer\'s reason is in '
             'the tooltip; <code>·</code>: another light transport.</p>']
    rows = [r for r in matrix_tables.rows(profile_name)
            if figure_id_of(r.experiment) in indices]
    for transport, group in matrix_tables.groups(rows):
        names = matrix_tables.columns(group)
        parts.append(f"<h3>{html.escape(matrix_tables.TRANSPORTS[transport])}</h3>"
                     '<div class="matrix"><table class="matrix"><tr><th>scene</th><th>budget</th>'
                     + "".join(f"<th><code>{html.escape(n)}</code></th>" for n in names)
                     + "</tr>")
        for r in group:
            fid = figure_id_of(r.experiment)
            cells = "".join(_matrix_cell(fid, r.cells.get(n), indices[fid]) for n in names)
            parts.append(f'<tr><td><a href="#{fid}">{html.escape(r.scene)}</a></td>'
                         f"<td>{r.budget:g} s</td>{cells}</tr>")
        parts.append("</table></div>")
    return "\n".join(parts)


def _matrix_cell(fid: str, cell: matrix_tables.Cell | None,
                 images: dict[TechniqueBudget, int]) -> str:
    """A matrix cell: its text, a link that shows its equal-time render in its scene's
    comparison, the renderer's reason as a refused cell's tooltip."""
    text = html.escape(matrix_tables.cell_text(cell)).replace("**", "")
    if cell is None:
        return f"<td>{text}</td>"
    if cell.refusal is not None:
        return f'<td class="refused" title="{html.escape(cell.refusal)}">{text}</td>'
    if cell.gain is not None and matrix_tables.excludes_one(cell.gain):
        text = f"<b>{text}</b>"
    style = ""
    if cell.gain is not None:
        colour, dark = matrix_plot.cell_colour(cell.gain.value)
        style = f' style="background: {colour}{"; color: #fff" if dark else ""}"'
    index = (images.get(TechniqueBudget(cell.technique, TIME, cell.seconds))
             if cell.seconds is not None else None)
    if index is None:
        return f"<td{style}>{text}</td>"
    return (f'<td{style}><a href="#{fid}" data-figure="{fid}" data-image="{index}">{text}</a>'
            "</td>")


def figure_id_of(experiment: str) -> str:
    return experiment.replace("/", "__")


def _page(profile_name: str, sections: dict[str, list[tuple[Results, bool]]],
          indices: dict[str, dict[TechniqueBudget, int]]) -> str:
    nav = []
    body = []
    for paper, docs in sections.items():
        nav.append(f'<a class="paper" href="#{paper}">{html.escape(paper)}</a>')
        nav += [f'<a href="#{figure_id(d)}">{html.escape(tables.figure_of(d))}</a>'
                for d, _ in docs]
        body.append(f'<h2 id="{paper}">{html.escape(paper)}</h2>')
        if paper == matrix_tables.PAPER:
            body.append(_matrix_overview(profile_name, indices))
        body += [_section(d, stale) for d, stale in docs]
    scripts = "".join(f'<script src="vendor/{Path(lib).name}"></script>\n' for lib in LIBRARIES)
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>Importance-sampling reproductions: results ({profile_name} profile)</title>
<link rel="stylesheet" href="vendor/viewer.css">
{scripts}<script src="vendor/viewer.js"></script>
</head><body>
<nav>{''.join(nav)}</nav>
<main>
<h1>Results, {profile_name} profile</h1>
<p>Generated by <code>make report</code> from <code>results/&lt;paper&gt;/*.json</code>, the
tables' rows and the references; the tables' legend (<code>results/tables/&lt;paper&gt;.md</code>)
says what the numbers and verdicts mean. Each comparison shows seed 0.</p>
{''.join(body)}
</main></body></html>
"""


def _copy_libraries(out: Path) -> None:
    vendor = out / "vendor"
    vendor.mkdir(parents=True, exist_ok=True)
    for lib in LIBRARIES:
        source = VIEWER / "node_modules" / lib
        if not source.exists():
            raise FileNotFoundError(f"{source}: run `make report` (it runs npm ci in "
                                    f"{paths.relative(VIEWER)})")
        shutil.copyfile(source, vendor / source.name)
    for own in ("viewer.js", "viewer.css"):
        shutil.copyfile(VIEWER / own, vendor / own)


def write(profile_name: str, workers: int, only: list[str] | None = None,
          out: Path | None = None) -> Path:
    """Writes the page (and its data, plots and libraries) into `out` (default
    results/report/); `only`: experiment ids to include. Returns the page."""
    out = out or REPORT
    _copy_libraries(out)
    (out / "data").mkdir(parents=True, exist_ok=True)
    sections: dict[str, list[tuple[Results, bool]]] = {}
    indices: dict[str, dict[TechniqueBudget, int]] = {}  # figure -> its images' rows
    for paper, docs in tables.load_results(profile_name).items():
        for doc in docs:
            if only and doc.experiment not in only:
                continue
            try:
                exp = config.load(paths.ROOT / doc.config.file)
                shown = images(exp, doc, workers)
            except SceneRejected as e:
                if not e.skippable:
                    raise
                print(f"{doc.experiment}: skipped, an asset is absent ({e.message})")
                continue
            provenance.write_text_atomically(out / "data" / f"{figure_id(doc)}.js",
                                             _data_script(doc, shown))
            indices[figure_id(doc)] = {s.row: i for i, s in enumerate(shown) if s.row}
            plot = (paths.PLOTS / paper /
                    f"{tables.figure_of(doc)}_convergence{paths.suffix(profile_name)}.png")
            if plot.exists():
                (out / "plots" / paper).mkdir(parents=True, exist_ok=True)
                shutil.copyfile(plot, out / "plots" / paper / plot.name)
            sections.setdefault(paper, []).append((doc, tables.config_changed(doc)))
    page = out / "index.html"
    provenance.write_text_atomically(page, _page(profile_name, sections, indices))
    return page
