"""Plots from results/<paper>/<figure>.json: log-log convergence (error against samples and
against render time, one line per technique, 95 % seed intervals as bands, fitted slope in
the legend) and side-by-side crops (reference | baseline | techniques) at the table budget.
A fixed-spp technique's points against time are its equal-sample runs at their mean render
time."""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.axes import Axes  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from . import matrix_configs, paths, records, tables  # noqa: E402
from .exr import read_exr  # noqa: E402
from .records import SPP, TIME, SummaryEntry, TechniqueBudget  # noqa: E402
from .results import Results  # noqa: E402


def _axis(entry: SummaryEntry, kind: str) -> float:
    """An entry's position along the axis of `kind`: its mean spp or its mean render time."""
    return (entry.spp if kind == SPP else entry.time).mean


def _series(doc: Results, technique: str, kind: str) -> tuple[np.ndarray, ...]:
    """(x, mean, lo, hi) over a technique's budgets of one kind, x = mean spp or time. Against
    time, a fixed-spp technique's points are its equal-sample budgets (its equal-time entries
    at matched budgets are copies of some of them)."""
    metric = doc.primary_metric
    entries_kind = kind
    if kind == TIME and doc.fixed_spp(technique):
        entries_kind = SPP
    rows = sorted((s for s in doc.summary
                   if s.technique == technique and s.kind == entries_kind),
                  key=lambda s: _axis(s, kind))
    m = [e for s in rows if (e := s.metrics[metric]) is not None]
    return (np.array([_axis(s, kind) for s in rows]), np.array([e.mean for e in m]),
            np.array([e.ci95[0] for e in m]), np.array([e.ci95[1] for e in m]))


def _panel(ax: Axes, doc: Results, kind: str) -> None:
    metric = doc.primary_metric
    for i, technique in enumerate(doc.techniques):
        x, mean, lo, hi = _series(doc, technique, kind)
        if len(x) == 0:
            continue
        colour = f"C{i}"
        slopes = doc.slopes.get(technique)
        fit = None if slopes is None else slopes.vs_spp if kind == SPP else slopes.vs_time
        label = technique + (f"  slope {fit.slope:.3f} ± {fit.slope_stderr:.3f}" if fit
                             else "")
        ax.fill_between(x, np.maximum(lo, mean * 1e-3), hi, color=colour, alpha=0.2, lw=0)
        ax.plot(x, mean, "o-", color=colour, label=label, ms=4)
    if kind == SPP:
        x0 = min(doc.budgets.spp)
        first = [s for s in doc.summary if s.kind == SPP and s.budget == x0]
        y0 = max(m.mean for s in first if (m := s.metrics[metric]) is not None)
        xs = np.array([x0, max(doc.budgets.spp)], dtype=float)
        ax.plot(xs, y0 * (xs / x0) ** -0.5, "k:", lw=1, label="N^-0.5")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("samples per pixel" if kind == SPP else "render time (s, 1 thread)")
    ax.set_ylabel(tables.METRIC_NAMES[metric])
    ax.set_title("equal samples" if kind == SPP else "equal time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)


def convergence(doc: Results, out: Path) -> None:
    has_time = any(s.kind == TIME for s in doc.summary)
    fig, axes = plt.subplots(1, 2 if has_time else 1, figsize=(11 if has_time else 6, 4.2),
                             squeeze=False)
    _panel(axes[0][0], doc, SPP)
    if has_time:
        _panel(axes[0][1], doc, TIME)
    fig.suptitle(f"{doc.experiment} ({doc.profile} profile, {len(doc.seeds)} seeds, "
                 f"{doc.resolution[0]}×{doc.resolution[1]})")
    fig.tight_layout()
    save(fig, out)


def read_rgb(file: Path) -> np.ndarray:
    return read_exr(file, channels=3)[1]


def _display(rgb: np.ndarray) -> np.ndarray:
    """Clamp and encode with the sRGB transfer curve, as the renderer's PNG previews do."""
    x = np.clip(rgb, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def crops(doc: Results, out: Path) -> bool:
    """Reference | baseline | each technique, seed 0 at the table's sample budget. Returns
    False when the renders are not on disk (results from another machine)."""
    budget = doc.table.spp
    panels = [("reference", paths.output(doc.reference.file))]
    techniques = [doc.baseline] + [t for t in doc.techniques if t != doc.baseline]
    runs = records.group_by_key(doc.runs)
    metric = doc.primary_metric
    for t in techniques:
        run = next(r for r in runs[TechniqueBudget(t, SPP, budget)] if r.seed == 0)
        panels.append((f"{t}, {budget:g} spp\n{tables.METRIC_NAMES[metric]} "
                       f"{run.metrics[metric]:.3g}", paths.output(run.file)))
    if not all(file.exists() for _, file in panels):
        return False
    fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels), 3.8), squeeze=False,
                             layout="constrained")
    for ax, (title, file) in zip(axes[0], panels):
        rgb = read_rgb(file)
        if doc.crop:
            x, y, w, h = doc.crop
            rgb = rgb[y:y + h, x:x + w]
        ax.imshow(_display(rgb), interpolation="nearest")
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    save(fig, out)
    return True


def save(fig: Figure, out: Path) -> None:
    """Writes the figure to a temporary file and renames it into place, then closes it."""
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(f".{out.stem}.tmp.png")
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    tmp.replace(out)


def write_all(profile_name: str) -> list[Path]:
    written = []
    suffix = paths.suffix(profile_name)
    for paper, docs in tables.load_results(profile_name).items():
        if paper == matrix_configs.PAPER:  # one budget per technique: the heat map instead
            continue
        for doc in docs:
            figure = tables.figure_of(doc)
            out = paths.PLOTS / paper / f"{figure}_convergence{suffix}.png"
            convergence(doc, out)
            written.append(out)
            out = paths.PLOTS / paper / f"{figure}_crops{suffix}.png"
            if crops(doc, out):
                written.append(out)
            else:
                print(f"skipped {paths.relative(out)}: the renders of this run are not on disk",
                      file=sys.stderr)
    return written
