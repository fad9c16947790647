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
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

from . import config, paths, provenance, results, stats
from .errors import ConfigError
from .matrix_configs import DEFAULT, PAPER
from .records import TIME, TechniqueBudget, index_by_key
from .results import Results

METRIC = "relmse"
# A cell whose mean render time differs from the default's at the same budget by more than
# this factor, either way, is marked and left out of the counts: a time limit stops a render
# between passes, so at a budget of one or a few passes the two cannot match.
TIME_MISMATCH = 1.1
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
    # its mean render time / the default's at the same budget
    time_ratio: float | None = None

    @property
    def unequal_time(self) -> bool:
        """Its renders took more than TIME_MISMATCH times the default's (or less than
        1/TIME_MISMATCH) on average: the cell is not at equal time."""
        return self.time_ratio is not None and not (
            1 / TIME_MISMATCH <= self.time_ratio <= TIME_MISMATCH)


@dataclass(frozen=True)
class Row:
    scene: str  # the scene's file name
    experiment: str
    transport: str
    budget: float  # the default's time: every time-capable technique's budget
    default_spp: int
    cells: dict[str, Cell]
    config_changed: bool  # the config (its refusals, say) changed since the results were made


def rows(profile_name: str) -> list[Row]:
    """One row per matrix results file of the profile, in scene order."""
    out = []
    for file in sorted((paths.RESULTS / PAPER).glob(f"*{paths.suffix(profile_name)}.json")):
        doc = results.read(file)
        if doc.profile == profile_name:
            out.append(row(doc))
    return out


def row(doc: Results) -> Row:
    """A scene's cells: each technique at the budget it is compared at (the default's time, or
    a fixed-spp technique's own), and the refusals its config records."""
    exp = config.load(paths.ROOT / doc.config.file)
    if exp.matrix is None:
        raise ConfigError(exp.file, "/matrix", "required in a matrix experiment")
    changed = exp.profile_sha256[doc.profile] != doc.config.sha256  # tables.config_changed
    if changed:
        print(f"warning: {doc.experiment}: the config has changed since these results were "
              "made; the table marks the row", file=sys.stderr)
    summary = index_by_key(doc.summary)
    budget = {m.technique: m.seconds for m in doc.matched}
    cells: dict[str, Cell] = {}
    for name in doc.techniques:
        seconds = budget.get(name if doc.fixed_spp(name) else DEFAULT)
        if seconds is None:
            cells[name] = Cell(name)
            continue
        entry = summary.get(TechniqueBudget(name, TIME, seconds))
        default = summary.get(TechniqueBudget(DEFAULT, TIME, seconds))
        cells[name] = Cell(name, entry.gain.get(METRIC) if entry else None, seconds,
                           entry.spp.mean if entry else None,
                           time_ratio=entry.time.mean / default.time.mean
                           if entry and default else None)
    for name, reason in exp.matrix.refused.items():
        cells[name] = Cell(name, refusal=reason)
    return Row(Path(doc.scene).name, doc.experiment, exp.matrix.transport, budget[DEFAULT],
               doc.table.spp, cells, changed)


def columns(group: list[Row]) -> list[str]:
    """The techniques of a group of rows: the default, then the rest by name (so an
    estimator's columns stand together: direct-bsdf, direct-light, ...)."""
    return [DEFAULT, *sorted({n for r in group for n in r.cells} - {DEFAULT})]


def groups(all_rows: list[Row]) -> Iterator[tuple[str, list[Row]]]:
    for transport in TRANSPORTS:
        group = [r for r in all_rows if r.transport == transport]
        if group:
            yield transport, group


def excludes_one(g: stats.Gain) -> bool:
    """Whether the interval lies wholly above or below 1 (rounding apart: two renders of the
    same samples give 1 to 10⁻¹⁵)."""
    return g.ci95[0] > 1 + ROUNDING or g.ci95[1] < 1 - ROUNDING


def refusal_notes(all_rows: list[Row]) -> dict[str, int]:
    """Each distinct refusal (technique and reason) -> its note number, in order."""
    reasons = sorted({f"`{c.technique}`: {c.refusal}" for r in all_rows
                      for c in r.cells.values() if c.refusal})
    return {reason: i + 1 for i, reason in enumerate(reasons)}


def cell_text(cell: Cell | None, notes: dict[str, int] | None = None) -> str:
    """A cell as the tables show it: the gain with its interval (bold when it excludes 1, †
    when not at equal time), "refused (n)" with the note of the renderer's reason, "·" for a
    technique of the other transport."""
    if cell is None:
        return "·"
    if cell.refusal is not None:
        note = (notes or {}).get(f"`{cell.technique}`: {cell.refusal}")
        return f"refused ({note})" if note else "refused"
    if cell.technique == DEFAULT:
        return "1"
    if cell.gain is None:
        return "—"
    lo, hi = cell.gain.ci95
    mark = "**" if excludes_one(cell.gain) else ""
    unequal = f" † (×{cell.time_ratio:.2g} the time)" if cell.unequal_time else ""
    return f"{mark}×{cell.gain.value:.3g}{mark} [{lo:.3g}, {hi:.3g}]{unequal}"


LEGEND = (
    "Each cell: the scene's default technique's relMSE over the technique's, at equal time "
    "(> 1: the technique is better), with the 95 % interval over the seeds (paired); bold where "
    "the interval excludes 1. The default (the scene file's own integrator) renders the "
    "figure's table spp; its mean render time is the budget. A technique that cannot stop at a "
    "time limit (tais) renders the same spp and is compared with the default rendered again at "
    "its time. `refused (n)`: the renderer refuses the combination, for reason n below; `·`: "
    "it estimates another image (direct lighting against paths). †: the technique's mean render "
    f"time differs from the default's at that budget by more than ×{TIME_MISMATCH:g} either "
    "way (a time limit stops a render between passes, so at a budget of one or a few passes "
    "the two cannot match): not an equal-time comparison; the analysis counts its verdict only "
    "where the mismatch cannot explain it, with the interval charged for the extra time as if "
    "the error fell in proportion to time. ‡: the scene's config has changed since its results were made. Techniques run at "
    "their documented defaults (configs/matrix.json); nothing is tuned per scene. Made by "
    "`make matrix` from results/matrix/*.json.")


def markdown(all_rows: list[Row]) -> str:
    notes = refusal_notes(all_rows)
    lines = ["# The cross-paper matrix: every technique on every figure scene at equal time", "",
             LEGEND, ""]
    for transport, group in groups(all_rows):
        names = columns(group)
        lines += [f"## {TRANSPORTS[transport]}", "",
                  "| scene | budget | " + " | ".join(f"`{n}`" for n in names) + " |",
                  "|---|---|" + "---|" * len(names)]
        for r in group:
            cells = " | ".join(cell_text(r.cells.get(n), notes) for n in names)
            changed = " ‡" if r.config_changed else ""
            lines.append(f"| {r.scene.removesuffix('.json')}{changed} | {r.budget:g} s "
                         f"({r.default_spp} spp) | {cells} |")
        lines.append("")
    lines += ["## Refusals", ""]
    scenes: dict[str, list[str]] = {}
    for r in all_rows:
        for c in r.cells.values():
            if c.refusal:
                scenes.setdefault(f"`{c.technique}`: {c.refusal}", []).append(
                    r.scene.removesuffix(".json"))
    lines += [f"{n}. {reason} ({', '.join(scenes[reason])})" for reason, n in notes.items()]
    return "\n".join(lines) + "\n"


def csv_text(all_rows: list[Row]) -> str:
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["scene", "experiment", "transport", "technique", "status", "verdict",
                "seconds", "spp", "time_ratio_to_default", "gain", "gain_ci95_lo",
                "gain_ci95_hi", "refusal"])
    for r in all_rows:
        for name in columns([r]):
            c = r.cells[name]
            status = ("refused" if c.refusal else "baseline" if name == DEFAULT
                      else "no equal-time runs" if c.gain is None else "measured")
            g = c.gain
            w.writerow([r.scene, r.experiment, r.transport, name, status,
                        "" if name == DEFAULT else verdict(c) or "",
                        "" if c.seconds is None else c.seconds,
                        "" if c.spp is None else f"{c.spp:.6g}",
                        "" if c.time_ratio is None else f"{c.time_ratio:.4g}",
                        "" if g is None else f"{g.value:.6g}",
                        "" if g is None else f"{g.ci95[0]:.6g}",
                        "" if g is None else f"{g.ci95[1]:.6g}", c.refusal or ""])
    return out.getvalue()


def _tex(text: str) -> str:
    return (text.replace("_", r"\_").replace("×", r"$\times$").replace("†", r"$^\dagger$")
            .replace("·", r"$\cdot$").replace("**", ""))


def latex(all_rows: list[Row]) -> str:
    """The tables as booktabs tabulars, the cells as in the Markdown (gain [interval], †,
    refused (n) with the notes as a comment list after each)."""
    notes = refusal_notes(all_rows)
    lines = []
    for transport, group in groups(all_rows):
        names = columns(group)
        lines += [f"% {TRANSPORTS[transport]}: relMSE gain over the default at equal time",
                  r"\begin{tabular}{l" + "r" * len(names) + "}", r"\toprule",
                  "scene & " + " & ".join(_tex(n) for n in names) + r" \\", r"\midrule"]
        for r in group:
            cells = " & ".join(_tex(cell_text(r.cells.get(n), notes).split(" (×")[0])
                               for n in names)
            lines.append(_tex(r.scene.removesuffix(".json")) + " & " + cells + r" \\")
        lines += [r"\bottomrule", r"\end{tabular}", ""]
    lines += [f"% refused ({n}): {reason}" for reason, n in notes.items()]
    return "\n".join(lines) + "\n"


def _median(values: list[float]) -> float:
    """The median (of an even count, the geometric mean of the middle two: gains are ratios)."""
    v = sorted(values)
    mid = len(v) // 2
    return v[mid] if len(v) % 2 else math.sqrt(v[mid - 1] * v[mid])


def verdict(cell: Cell | None) -> str | None:
    """"better" or "worse" than the default beyond the interval, "inconclusive", or "unequal
    time": a † cell whose time mismatch could explain its verdict. The interval is first
    charged for the mismatch, on the assumption that a Monte Carlo error falls at most in
    proportion to the time (MSE ∝ 1/T): divided by the time ratio where the technique had
    more time than the default, multiplied where it had less would flatter it, so left as it
    is; a loss is charged likewise the other way. None: no measurement."""
    if cell is None or cell.gain is None:
        return None
    ratio = cell.time_ratio if cell.time_ratio is not None else 1.0
    lo, hi = cell.gain.ci95
    if lo / max(ratio, 1.0) > 1 + ROUNDING:
        return "better"
    if hi / min(ratio, 1.0) < 1 - ROUNDING:
        return "worse"
    return "unequal time" if cell.unequal_time else "inconclusive"


def measured_summary(all_rows: list[Row]) -> list[str]:
    """For each technique: on how many scenes it is better, worse or indistinguishable at
    equal time (verdict(): cells whose time mismatch could explain their verdict counted
    apart), its median gain over the others, and its best and worst scene; then each scene's
    winner: the best of the techniques that beat the default."""
    lines = [BEGIN, "", "### Measured (quick profile; `make matrix` regenerates this part)", ""]
    for transport, group in groups(all_rows):
        lines += [f"**{TRANSPORTS[transport]}** ({len(group)}):", "",
                  "| technique | better | worse | inconclusive | unequal time | refused | "
                  "median gain | best | worst |", "|---|---|---|---|---|---|---|---|---|"]
        for name in columns(group)[1:]:
            cells = [(r.scene.removesuffix(".json"), r.cells.get(name)) for r in group]
            verdicts = [verdict(c) for _, c in cells]
            gains = [(scene, c.gain) for (scene, c), v in zip(cells, verdicts)
                     if c is not None and c.gain is not None and v != "unequal time"]
            unequal = verdicts.count("unequal time")
            refused = sum(1 for _, c in cells if c is not None and c.refusal)
            better, worse = verdicts.count("better"), verdicts.count("worse")
            if not gains:
                lines.append(f"| `{name}` | 0 | 0 | 0 | {unequal} | {refused} | — | — | — |")
                continue
            best = max(gains, key=lambda p: p[1].value)
            worst = min(gains, key=lambda p: p[1].value)
            lines.append(f"| `{name}` | {better} | {worse} | {len(gains) - better - worse} | "
                         f"{unequal} | {refused} | ×{_median([g.value for _, g in gains]):.3g} | "
                         f"{best[0]} ×{best[1].value:.3g} | {worst[0]} ×{worst[1].value:.3g} |")
        lines += ["", "| scene | best technique at equal time | its gain |", "|---|---|---|"]
        for r in group:
            winners = [(c.technique, c.gain) for c in r.cells.values()
                       if c.gain is not None and verdict(c) == "better"]
            scene = r.scene.removesuffix(".json")
            winner = max(winners, key=lambda p: p[1].value) if winners else None
            if winner is None:
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
