"""The cross-paper matrix's outputs from its experiments' results (results/matrix/<scene>.json):
results/tables/matrix.{md,csv,tex}, the heat map results/plots/matrix/heatmap.png, and the
measured part of results/matrix/analysis.md.

A cell is a technique on a scene at equal time: its relMSE over the scene's default
technique's, as a gain (> 1: the technique is better), with the 95 % interval of the harness's
paired gain over the seeds. A time-capable technique is compared at the default's budget (its
mean render time at the figure's table spp); a fixed-spp one at its own render time for that
spp, where the default was rendered again. A refused cell holds the renderer's reason; a
technique of the other light transport has no cell."""
import csv
import io
import math
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from . import config, paths, provenance, results, stats
from .errors import ConfigError
from .matrix_configs import DEFAULT, PAPER
from .records import TIME, TechniqueBudget, index_by_key
from .results import Results

METRIC = "relmse"
# A cell whose renders took more than this multiple of the budget on average is marked: the
# time limit stops a render between passes, so a pass longer than the budget overshoots it.
OVER_BUDGET = 1.1
ROUNDING = 1e-9
TRANSPORTS = {"direct": "Direct-lighting scenes", "paths": "Path-traced scenes"}
ANALYSIS_FILE = paths.RESULTS / PAPER / "analysis.md"
# The measured part of analysis.md lies between these lines; the reading around it is written
# by hand.
BEGIN, END = "<!-- measured: make matrix writes from here -->", "<!-- measured: to here -->"


@dataclass(frozen=True)
class Cell:
    technique: str
    gain: stats.Gain | None = None  # None: refused, or no equal-time runs
    seconds: float | None = None  # the equal-time budget compared at
    spp: float | None = None  # mean samples per pixel the technique reached there
    refusal: str | None = None
    time_ratio: float | None = None  # its mean render time / the budget

    @property
    def over_budget(self) -> bool:
        """Its shortest render (one pass, or a pilot) took longer than the budget: the cell
        is not at equal time, and its gain flatters it."""
        return self.time_ratio is not None and self.time_ratio > OVER_BUDGET


@dataclass(frozen=True)
class Row:
    scene: str  # the scene's file name
    experiment: str
    transport: str
    budget: float  # the default's time: every time-capable technique's budget
    default_spp: int
    cells: dict[str, Cell]


def rows(profile_name: str) -> list[Row]:
    """One row per matrix results file of the profile, in scene order."""
    out = []
    for file in sorted((paths.RESULTS / PAPER).glob(f"*{paths.suffix(profile_name)}.json")):
        doc = results.read(file)
        if doc.profile == profile_name:
            out.append(row(doc))
    return out


def row(doc: Results) -> Row:
    exp = config.load(paths.ROOT / doc.config.file)
    summary = index_by_key(doc.summary)
    budget = {m.technique: m.seconds for m in doc.matched}
    cells: dict[str, Cell] = {}
    for name in doc.techniques:
        seconds = budget.get(name if doc.fixed_spp(name) else DEFAULT)
        entry = summary.get(TechniqueBudget(name, TIME, seconds)) if seconds else None
        cells[name] = Cell(name, entry.gain.get(METRIC) if entry else None, seconds,
                           entry.spp.mean if entry else None,
                           time_ratio=entry.time.mean / seconds if entry and seconds else None)
    if exp.matrix is None:
        raise ConfigError(exp.file, "/matrix", "required in a matrix experiment")
    for name, reason in exp.matrix.refused.items():
        cells[name] = Cell(name, refusal=reason)
    return Row(Path(doc.scene).name, doc.experiment, exp.matrix.transport, budget[DEFAULT],
               doc.table.spp, cells)


def columns(group: list[Row]) -> list[str]:
    """The techniques of a group of rows, in the order their experiments list them, refused
    ones in the registry's order among them."""
    seen: list[str] = []
    for r in group:
        for name in r.cells:
            if name not in seen:
                seen.append(name)
    rest = sorted(n for n in seen if n != DEFAULT)
    return [DEFAULT, *rest]


def groups(all_rows: list[Row]) -> Iterator[tuple[str, list[Row]]]:
    for transport in TRANSPORTS:
        group = [r for r in all_rows if r.transport == transport]
        if group:
            yield transport, group


def excludes_one(g: stats.Gain) -> bool:
    """Whether the interval lies wholly above or below 1 (rounding apart: two renders of the
    same samples give 1 to 10⁻¹⁵)."""
    return g.ci95[0] > 1 + ROUNDING or g.ci95[1] < 1 - ROUNDING


def cell_text(cell: Cell | None) -> str:
    if cell is None:
        return "·"
    if cell.refusal is not None:
        return "refused"
    if cell.technique == DEFAULT:
        return "1"
    if cell.gain is None:
        return "—"
    lo, hi = cell.gain.ci95
    mark = "**" if excludes_one(cell.gain) else ""
    over = f" † (×{cell.time_ratio:.2g} the time)" if cell.over_budget else ""
    return f"{mark}×{cell.gain.value:.3g}{mark} [{lo:.3g}, {hi:.3g}]{over}"


def markdown(all_rows: list[Row]) -> str:
    lines = ["# The cross-paper matrix: every technique on every figure scene at equal time", "",
             "Each cell: the scene's default technique's relMSE over the technique's, at equal "
             "time (> 1: the technique is better), with the 95 % interval over the seeds "
             "(paired); bold where the interval excludes 1. The default (the scene file's own "
             "integrator) renders the figure's table spp; its mean render time is the budget. "
             "A technique that cannot stop at a time limit (tais) renders the same spp and is "
             "compared with the default rendered again at its time. `refused`: the renderer "
             "refuses the combination (reasons below); `·`: it estimates another image "
             "(direct lighting against paths). † : the technique's renders took more than "
             f"×{OVER_BUDGET:g} the budget on average (a time limit stops a render between "
             "passes, and its first pass or pilot was longer than the budget): not equal time, "
             "and the gain flatters it. Techniques run at their documented defaults "
             "(configs/matrix.json); nothing is tuned per scene. Made by `make matrix` from "
             "results/matrix/*.json.", ""]
    for transport, group in groups(all_rows):
        names = columns(group)
        lines += [f"## {TRANSPORTS[transport]}", "",
                  "| scene | budget | " + " | ".join(f"`{n}`" for n in names) + " |",
                  "|---|---|" + "---|" * len(names)]
        for r in group:
            cells = " | ".join(cell_text(r.cells.get(n)) for n in names)
            lines.append(f"| {r.scene.removesuffix('.json')} | {r.budget:g} s "
                         f"({r.default_spp} spp) | {cells} |")
        lines.append("")
    lines += ["## Refusals", ""]
    reasons: dict[str, list[str]] = {}
    for r in all_rows:
        for c in r.cells.values():
            if c.refusal:
                reasons.setdefault(f"`{c.technique}`: {c.refusal}", []).append(
                    r.scene.removesuffix(".json"))
    lines += [f"- {reason} ({', '.join(scenes)})" for reason, scenes in sorted(reasons.items())]
    return "\n".join(lines) + "\n"


def csv_text(all_rows: list[Row]) -> str:
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["scene", "experiment", "transport", "technique", "status", "seconds", "spp",
                "time_over_budget", "gain", "gain_ci95_lo", "gain_ci95_hi", "refusal"])
    for r in all_rows:
        for name in columns([r]):
            c = r.cells[name]
            status = ("refused" if c.refusal else "baseline" if name == DEFAULT
                      else "measured" if c.gain else "no equal-time runs")
            g = c.gain
            w.writerow([r.scene, r.experiment, r.transport, name, status,
                        "" if c.seconds is None else c.seconds,
                        "" if c.spp is None else f"{c.spp:.6g}",
                        "" if c.time_ratio is None else f"{c.time_ratio:.4g}",
                        "" if g is None else f"{g.value:.6g}",
                        "" if g is None else f"{g.ci95[0]:.6g}",
                        "" if g is None else f"{g.ci95[1]:.6g}", c.refusal or ""])
    return out.getvalue()


def _tex(text: str) -> str:
    return text.replace("_", r"\_").replace("×", r"$\times$")


def latex(all_rows: list[Row]) -> str:
    lines = []
    for transport, group in groups(all_rows):
        names = columns(group)
        lines += [f"% {TRANSPORTS[transport]}: gain in relMSE over the default at equal time",
                  r"\begin{tabular}{l" + "r" * len(names) + "}", r"\toprule",
                  "scene & " + " & ".join(_tex(n) for n in names) + r" \\", r"\midrule"]
        for r in group:
            cells = []
            for n in names:
                c = r.cells.get(n)
                cells.append("--" if c is None or (c.gain is None and c.technique != DEFAULT)
                             else "1" if c.technique == DEFAULT else f"{c.gain.value:.3g}"
                             if c.gain else "--")
            lines.append(_tex(r.scene.removesuffix(".json")) + " & " + " & ".join(cells)
                         + r" \\")
        lines += [r"\bottomrule", r"\end{tabular}", ""]
    return "\n".join(lines)


def _median(values: list[float]) -> float:
    """The median (of an even count, the geometric mean of the middle two: gains are ratios)."""
    v = sorted(values)
    mid = len(v) // 2
    return v[mid] if len(v) % 2 else math.sqrt(v[mid - 1] * v[mid])


def _fair(cell: Cell | None) -> stats.Gain | None:
    """A cell's gain if it was measured at equal time (not over budget)."""
    return cell.gain if cell is not None and not cell.over_budget else None


def measured_summary(all_rows: list[Row]) -> list[str]:
    """For each technique: on how many scenes it is better, worse or indistinguishable at
    equal time (cells over budget left out and counted apart), its median gain, and its best
    and worst scene; then each scene's winner."""
    lines = [BEGIN, "", "### Measured (quick profile; `make matrix` regenerates this part)", ""]
    for transport, group in groups(all_rows):
        lines += [f"**{TRANSPORTS[transport]}** ({len(group)}):", "",
                  "| technique | better | worse | inconclusive | over budget | refused | "
                  "median gain | best | worst |", "|---|---|---|---|---|---|---|---|---|"]
        for name in columns(group)[1:]:
            cells = [(r.scene.removesuffix(".json"), r.cells.get(name)) for r in group]
            gains = [(scene, g) for scene, c in cells if (g := _fair(c)) is not None]
            over = sum(1 for _, c in cells if c is not None and c.over_budget)
            refused = sum(1 for _, c in cells if c is not None and c.refusal)
            better = sum(excludes_one(g) and g.value > 1 for _, g in gains)
            worse = sum(excludes_one(g) and g.value < 1 for _, g in gains)
            if not gains:
                lines.append(f"| `{name}` | 0 | 0 | 0 | {over} | {refused} | — | — | — |")
                continue
            best = max(gains, key=lambda p: p[1].value)
            worst = min(gains, key=lambda p: p[1].value)
            lines.append(f"| `{name}` | {better} | {worse} | {len(gains) - better - worse} | "
                         f"{over} | {refused} | ×{_median([g.value for _, g in gains]):.3g} | "
                         f"{best[0]} ×{best[1].value:.3g} | {worst[0]} ×{worst[1].value:.3g} |")
        lines += ["", "| scene | best technique at equal time | its gain |", "|---|---|---|"]
        for r in group:
            fair = [(c.technique, g) for c in r.cells.values() if (g := _fair(c)) is not None]
            scene = r.scene.removesuffix(".json")
            winner = max(fair, key=lambda p: p[1].value) if fair else None
            if winner is None or not (excludes_one(winner[1]) and winner[1].value > 1):
                lines.append(f"| {scene} | the default (none better beyond its interval) | 1 |")
            else:
                lo, hi = winner[1].ci95
                lines.append(f"| {scene} | `{winner[0]}` | ×{winner[1].value:.3g} [{lo:.3g}, "
                             f"{hi:.3g}] |")
        lines.append("")
    return lines + [END]


def write_analysis(all_rows: list[Row]) -> Path:
    """Replaces the measured part of analysis.md, keeping the hand-written reading."""
    text = ANALYSIS_FILE.read_text(encoding="utf-8") if ANALYSIS_FILE.exists() else (
        "# The cross-paper matrix: a reading\n\n" + BEGIN + "\n" + END + "\n")
    head, _, rest = text.partition(BEGIN)
    _, _, tail = rest.partition(END)
    provenance.write_text_atomically(
        ANALYSIS_FILE, head + "\n".join(measured_summary(all_rows)) + tail)
    return ANALYSIS_FILE


def write_all(profile_name: str) -> list[Path]:
    """The tables (and, for the quick profile, the analysis's measured part) of a profile's
    matrix results; nothing when there are none."""
    all_rows = rows(profile_name)
    if not all_rows:
        return []
    written = []
    for ext, text in (("md", markdown(all_rows)), ("csv", csv_text(all_rows)),
                      ("tex", latex(all_rows))):
        out = paths.TABLES / f"{PAPER}{paths.suffix(profile_name)}.{ext}"
        provenance.write_text_atomically(out, text)
        written.append(out)
    if profile_name == "quick":
        written.append(write_analysis(all_rows))
    return written
