"""Tables per paper from results/<paper>/*.json: Markdown (main table, secondary metrics,
convergence slopes), CSV (every number) and LaTeX (the main table, booktabs)."""
import csv
import io
import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from . import config, matrix_configs, paths, provenance, records, results, stats
from .config import PaperNumbers
from .errors import ConfigError
from .records import SPP, TIME, SummaryEntry, TechniqueBudget
from .results import Results

METRIC_NAMES = {"sigma_over_mu": "σ/µ", "rmse": "RMSE", "mse": "MSE", "relmse": "relMSE",
                "tvi_err": "Err (tvi)", "p_eff": "P-Eff", "mse_eff": "1/(T·MSE)",
                "relative_bias": "bias (mean / ref. − 1)"}


def load_results(profile_name: str) -> dict[str, list[Results]]:
    """{paper: [results document, ...]} of one profile, in figure order."""
    by_paper: dict[str, list[Results]] = {}
    for file in sorted(paths.RESULTS.glob(f"*/*{paths.suffix(profile_name)}.json")):
        if file.parent.name in ("tables", "plots", "renders", "previews"):
            continue
        doc = results.read(file)
        if doc.profile == profile_name:
            by_paper.setdefault(file.parent.name, []).append(doc)
    return by_paper


def figure_of(doc: Results) -> str:
    return doc.experiment.split("/")[1]


def _matched_to(doc: Results, row: SummaryEntry) -> str:
    """"tais at 16 spp" when the row's equal-time budget is a fixed-spp technique's measured
    render time (several joined by ", "); "" otherwise."""
    if row.kind != TIME:
        return ""
    return ", ".join(f"{m.technique} at {m.spp} spp" for m in doc.matched
                     if m.seconds == row.budget)


def _table_spp(doc: Results) -> int:
    """The equal-sample budget of the paper's number for the primary metric, else the
    table's."""
    paper = _paper_entry(doc, doc.primary_metric)
    return paper.spp if paper else doc.table.spp


def table_rows(doc: Results) -> list[SummaryEntry]:
    """The table's rows: each technique (baseline first) at _table_spp, and, when the profile
    has one, at the table's equal-time budget (fixed-spp techniques have none). With
    "matched" as the table's seconds, the equal-time rows follow the equal-sample ones: for
    each fixed-spp technique, the time-capable techniques (baseline first) at its matched
    time for the table's spp, then the technique itself at that time (its own renders at that
    spp)."""
    techniques = [doc.baseline] + [t for t in doc.techniques if t != doc.baseline]
    summary = records.index_by_key(doc.summary)
    spp, seconds = _table_spp(doc), doc.table.seconds
    if isinstance(seconds, str):  # config.MATCHED
        rows = [summary[TechniqueBudget(t, SPP, spp)] for t in techniques]
        capable = [t for t in techniques if not doc.fixed_spp(t)]
        baselines = {doc.baseline, doc.also_baseline}
        for m in doc.matched:
            if m.spp == doc.table.spp:
                # at a budget only the baselines were rendered at (equal_time "baseline"),
                # only they; a time-capable technique that set it (sets_time) once
                alone = doc.techniques[m.technique].equal_time == config.BASELINE_ONLY
                names = [t for t in capable if t in baselines or not alone]
                names += [m.technique] if m.technique not in names else []
                rows += [summary[TechniqueBudget(t, TIME, m.seconds)] for t in names]
        return rows
    rows = []
    for t in techniques:
        rows.append(summary[TechniqueBudget(t, SPP, spp)])
        if seconds is not None and TechniqueBudget(t, TIME, seconds) in summary:
            rows.append(summary[TechniqueBudget(t, TIME, seconds)])
    return rows


def _paper_entry(doc: Results, metric: str, spp: float | None = None) -> PaperNumbers | None:
    """The paper's numbers for a metric (at an equal-sample budget, when given)."""
    for p in doc.paper:
        if p.metric == metric and (spp is None or p.spp == spp):
            return p
    return None


@dataclass(frozen=True)
class PaperCells:
    """What the paper says about a row: its value, at its spp, its gain, and our verdict."""
    value: float | None = None
    spp: int | None = None
    gain: float | None = None
    verdict: str = "—"


def _paper_cells(doc: Results, row: SummaryEntry, metric: str) -> PaperCells:
    """The paper's cells for a row, where the paper reports the metric at the row's
    equal-sample budget; empty elsewhere."""
    paper = _paper_entry(doc, metric, row.budget) if row.kind == SPP else None
    if paper is None:
        return PaperCells()
    value = paper.values.get(row.technique)
    if row.technique == doc.baseline:
        return PaperCells(value, paper.spp)
    paper_gain = stats.paper_gain(paper.values, doc.baseline, row.technique,
                                  config.METRICS[metric])
    return PaperCells(value, paper.spp, paper_gain,
                      stats.verdict(row.gain.get(metric), paper_gain))


@dataclass(frozen=True)
class RowValues:
    """The cells of one row of a Markdown or LaTeX table."""
    figure: str
    technique: str
    budget: str  # "16 spp", "0.5 s", "0.012 s (time of tais at 16 spp)"
    spp: float
    time: float
    metric: str
    mean: float | None
    half_width: float | None  # of the 95 % interval
    gain: stats.Gain | None
    paper: PaperCells
    also_gain: stats.Gain | None  # over the experiment's also_baseline


def _row_values(doc: Results, row: SummaryEntry, metric: str | None = None) -> RowValues:
    metric = metric or doc.primary_metric
    m = row.metrics[metric]
    budget = f"{row.budget:g} {'spp' if row.kind == SPP else 's'}"
    if _matched_to(doc, row):
        budget += f" (time of {_matched_to(doc, row)})"
    return RowValues(figure_of(doc), row.technique, budget, row.spp.mean, row.time.mean, metric,
                     m.mean if m else None, (m.ci95[1] - m.mean) if m else None,
                     row.gain.get(metric), _paper_cells(doc, row, metric),
                     (row.also_gain or {}).get(metric))


def _fmt(x: float | None, digits: int = 4) -> str:
    return "—" if x is None else f"{x:.{digits}g}"


def gain_text(g: stats.Gain | None) -> str:
    return "—" if g is None else f"×{g.value:.3g} [{g.ci95[0]:.3g}, {g.ci95[1]:.3g}]"


def _comparison_cells(v: RowValues, also: bool) -> str:
    """The cells shared by both Markdown tables; `also`: with the second baseline's column."""
    p = v.paper
    paper = "—" if p.value is None else f"{p.value:.4g} ({p.spp} spp)"
    paper_gain = "—" if p.gain is None else f"×{p.gain:.3g}"
    ours = "—" if v.mean is None else f"{_fmt(v.mean)} ± {_fmt(v.half_width, 2)}"
    also_cell = f" {gain_text(v.also_gain)} |" if also else ""
    return f"{ours} | {paper} | {gain_text(v.gain)} |{also_cell} {paper_gain} | {p.verdict} |"


def _has_also_baseline(docs: list[Results]) -> bool:
    return any(doc.also_baseline for doc in docs)


ALSO_HEAD = " gain over 2nd baseline (95 %) |"


def separator(head: str) -> str:
    """The Markdown row under `head`: one `---` per cell."""
    return "|" + "---|" * (head.count("|") - 1)


def main_table(docs: list[Results]) -> list[str]:
    also = _has_also_baseline(docs)
    head = ("| figure | technique | budget | spp | time (s) | metric | ours (mean ± 95 %) | paper "
            "| gain over baseline (95 %) |" + (ALSO_HEAD if also else "") +
            " paper's gain | verdict |")
    lines = [head, separator(head)]
    for doc in docs:
        for row in table_rows(doc):
            v = _row_values(doc, row)
            lines.append(f"| {v.figure} | {v.technique} | {v.budget} | {v.spp:.4g} | "
                         f"{v.time:.3g} | {METRIC_NAMES[v.metric]} | " +
                         _comparison_cells(v, also))
    return lines


def _secondary_table(docs: list[Results]) -> list[str]:
    also = _has_also_baseline(docs)
    head = ("| figure | technique | budget | metric | ours (mean ± 95 %) | paper | gain over "
            "baseline (95 %) |" + (ALSO_HEAD if also else "") + " paper's gain | verdict |")
    lines = [head, separator(head)]
    for doc in docs:
        for row in table_rows(doc):
            for metric in doc.metrics[1:]:
                v = _row_values(doc, row, metric)
                lines.append(f"| {v.figure} | {v.technique} | {v.budget} | "
                             f"{METRIC_NAMES[metric]} | " + _comparison_cells(v, also))
    return lines


def _slope_table(docs: list[Results]) -> list[str]:
    lines = ["| figure | technique | metric | slope vs spp (± s.e.) | R² | slope vs time (± s.e.) "
             "| R² | points |", "|---|---|---|---|---|---|---|---|"]
    for doc in docs:
        for technique, s in doc.slopes.items():
            a, b = s.vs_spp, s.vs_time
            window = ("" if not s.windowed else " (no common time range: every run)"
                      if s.time_range is None else
                      f" (runs in {s.time_range[0]:.3g}–{s.time_range[1]:.3g} s)")
            lines.append(f"| {figure_of(doc)}{window} | {technique} | "
                         f"{METRIC_NAMES[doc.primary_metric]} | "
                         f"{a.slope:.3f} ± {a.slope_stderr:.3f} | {a.r2:.3f} | "
                         f"{b.slope:.3f} ± {b.slope_stderr:.3f} | {b.r2:.3f} | {a.n} |")
    return lines


def _equivalent_baseline_spp(doc: Results, error: float | None) -> float | None:
    """Samples per pixel at which the baseline's fitted convergence line (log error against log
    spp, over all its runs) reaches `error`; None without a fit."""
    slopes = doc.slopes.get(doc.baseline)
    if slopes is None or slopes.vs_spp.slope >= 0 or not error or error <= 0:
        return None
    return math.exp((math.log(error) - slopes.vs_spp.intercept) / slopes.vs_spp.slope)


def _cost_table(docs: list[Results]) -> list[str]:
    """Per technique at the table's equal-sample budget: render time per sample relative to the
    baseline's (same spp, same seeds), the equal-sample gain next to the equal-time one, and
    how many samples the baseline needs for the technique's error (from its fitted line)."""
    lines = ["| figure | technique | spp | time per sample / baseline's | gain, equal samples | "
             "gain, equal time | baseline spp for this error (× this spp) |",
             "|---|---|---|---|---|---|---|"]
    for doc in docs:
        metric, spp = doc.primary_metric, _table_spp(doc)
        entries = doc.summary
        summary = records.index_by_key(entries)
        base = summary.get(TechniqueBudget(doc.baseline, SPP, spp))
        if base is None:
            continue
        for t in doc.techniques:
            row = summary.get(TechniqueBudget(t, SPP, spp))
            if t == doc.baseline or row is None:
                continue
            cost = row.time.mean / base.time.mean
            timed = [s for s in entries if s.technique == t and s.kind == TIME
                     and s.duplicate_of is not None and s.duplicate_of.budget == spp]
            equal_time = timed[0].gain.get(metric) if timed else None
            summary_metric = row.metrics[metric]
            error = summary_metric.mean if summary_metric else None
            n = _equivalent_baseline_spp(doc, error)
            lines.append(f"| {figure_of(doc)} | {t} | {spp} | ×{cost:.3g} | "
                         f"{gain_text(row.gain.get(metric))} | {gain_text(equal_time)} | "
                         f"{'—' if n is None else f'{n:.4g} (×{n / spp:.3g})'} |")
    return lines


def _analysis(paper: str) -> list[str]:
    """The hand-written analysis of a paper's results, `results/<paper>/analysis.md`, if any."""
    file = paths.RESULTS / paper / "analysis.md"
    return file.read_text().rstrip("\n").split("\n") if file.exists() else []


def config_changed(doc: Results) -> bool:
    """True when the experiment's config, as this profile sees it, differs from the one that
    made these results, or is gone."""
    try:
        exp = config.load(paths.ROOT / doc.config.file)
        return exp.profile_sha256[doc.profile] != doc.config.sha256
    except ConfigError:
        return True


def _experiment_notes(docs: list[Results]) -> list[str]:
    lines = []
    for doc in docs:
        if config_changed(doc):
            lines.append(f"- **{figure_of(doc)}: its config has changed since this run; run it "
                         "again.**")
        ref = doc.reference
        prov = doc.provenance
        matched = "".join(f" Equal time matched to {m.technique} at {m.spp} spp: "
                          f"{m.seconds:g} s." for m in doc.matched)
        cpu = f", {prov.cpu_seconds:.0f} CPU-seconds" if prov.cpu_seconds is not None else ""
        lines.append(
            f"- **{figure_of(doc)}** ({doc.profile} profile, "
            f"{doc.resolution[0]}×{doc.resolution[1]}, {len(doc.seeds)} seeds, "
            f"{prov.parallel_jobs} parallel renders × {prov.threads_per_job} thread, "
            f"commit `{(prov.git_commit or 'unknown')[:10]}`"
            f"{' (uncommitted changes)' if prov.git_dirty else ''}"
            f"{cpu}"
            f"): {doc.description} "
            f"Reference: `{ref.integrator['type']}`, {ref.spp} spp, own noise σ/µ "
            f"{ref.noise_sigma_over_mu:.2g} = {ref.noise_ratio_to_smallest_error:.2f} of "
            f"the smallest error measured.{matched}")
    return lines


def _legend(paper: str, docs: list[Results]) -> str:
    """What the tables' numbers and verdicts (stats.verdict) mean."""
    matched = (" A budget of \"T s (time of X at N spp)\" is X's mean render time at N spp: X "
               "renders a fixed number of samples, so the other techniques are given its time, "
               "and X's row there is its N-spp renders."
               if any(doc.matched for doc in docs) else "")
    also = sorted({f"{figure_of(doc)}: {doc.also_baseline} (baseline {doc.baseline})"
                   for doc in docs if doc.also_baseline})
    also_text = (" The 2nd baseline, against which gains are also given (no verdict): " +
                 "; ".join(also) + "." if also else "")
    return (
        f"Generated by `make tables` from `results/{paper}/*.json`; do not edit. Errors are "
        "means over seeds with Student-t 95 % intervals; a gain is how many times better than "
        "the baseline (error ratio, or efficiency ratio for P-Eff) with a delta-method 95 % "
        f"interval. Verdict: *reproduced* when our gain is within ×{stats.REPRODUCED_FACTOR} of "
        "the paper's; *weaker* / *stronger* when our whole 95 % interval lies below / above "
        "that band; *inconclusive* when our gain is outside the band but its interval reaches "
        "into it; — where the paper reports no number." + matched + also_text)


def _freshness(docs: list[Results]) -> list[str]:
    """For full-profile results, which `make check-results` does not re-render in `make test`:
    the commit each was made at, so that a reader knows what code its numbers are from."""
    full = [doc for doc in docs if doc.profile == "full"]
    if not full:
        return []
    made = "; ".join(f"{figure_of(doc)} at `{(doc.provenance.git_commit or 'unknown')[:10]}` "
                     f"({doc.provenance.started[:10]}"
                     f"{', uncommitted changes' if doc.provenance.git_dirty else ''})"
                     for doc in full)
    return ["**Made at older commits, possibly stale.** Full-profile results take days of CPU "
            "and are not re-run with every change; `make check-results PROFILE=full` re-renders "
            "their fingerprints (results older than fingerprints have none, and are listed as "
            f"stale). Each was made at: {made}.", ""]


def markdown(paper: str, docs: list[Results]) -> str:
    lines = [f"# {paper}: results", "", _legend(paper, docs), ""] + _freshness(docs)
    lines += main_table(docs)
    lines += ["", "## Other metrics", ""] + _secondary_table(docs)
    lines += ["", "## Convergence", "",
              "Least-squares slope of log error against log samples and log render time over "
              "every run (all seeds and budgets), from `metrics slope`; plain Monte Carlo "
              "converges as −0.5.", ""] + _slope_table(docs)
    if any(doc.matched for doc in docs):
        lines += ["", "## Cost and equivalent samples", "",
                  "At each experiment's table budget. The baseline spp for the technique's error "
                  "comes from the baseline's fitted line of log error against log spp (see "
                  "Convergence); beyond the baseline's largest budget it is an extrapolation.",
                  ""] + _cost_table(docs)
    lines += ["", "## Experiments", ""] + _experiment_notes(docs)
    analysis = _analysis(paper)
    if analysis:
        lines += ["", "## Analysis", "",
                  f"Written by hand (`results/{paper}/analysis.md`) from the results above; "
                  "regenerating the tables keeps it, so re-read it when the numbers change.",
                  ""] + analysis
    return "\n".join(lines) + "\n"


def _metric_cells(m: stats.MetricSummary | None) -> list[Any]:
    """mean, ci95_lo, ci95_hi, sd (an efficiency has none), seeds."""
    if m is None:
        return [""] * 5
    return [m.mean, *m.ci95, m.sd if isinstance(m, stats.Estimate) else "", m.n]


def _gain_cells(g: stats.Gain | None) -> list[Any]:
    return [""] * 3 if g is None else [g.value, *g.ci95]


def csv_text(docs: list[Results]) -> str:
    out = io.StringIO()
    w = csv.writer(out)
    w.writerow(["experiment", "profile", "technique", "budget_kind", "budget", "metric", "mean",
                "ci95_lo", "ci95_hi", "sd", "seeds", "spp_mean", "time_mean", "gain",
                "gain_ci95_lo", "gain_ci95_hi", "paper_value", "paper_gain", "verdict",
                "matched_to", "also_baseline", "also_gain", "also_gain_ci95_lo",
                "also_gain_ci95_hi"])
    for doc in docs:
        for s in doc.summary:
            for metric in doc.metrics:
                paper = _paper_cells(doc, s, metric)
                w.writerow([doc.experiment, doc.profile, s.technique, s.kind, s.budget,
                            metric, *_metric_cells(s.metrics[metric]), s.spp.mean, s.time.mean,
                            *_gain_cells(s.gain.get(metric)),
                            "" if paper.value is None else paper.value,
                            "" if paper.gain is None else paper.gain,
                            "" if paper.verdict == "—" else paper.verdict, _matched_to(doc, s),
                            (doc.also_baseline or ""),
                            *_gain_cells((s.also_gain or {}).get(metric))])
    return out.getvalue()


def _tex_escape(text: str) -> str:
    return (text.replace("\\", r"\textbackslash{}").replace("_", r"\_").replace("%", r"\%")
            .replace("&", r"\&").replace("#", r"\#"))


def latex(paper: str, docs: list[Results]) -> str:
    lines = [r"% Generated by make tables; needs \usepackage{booktabs}.",
             r"\begin{tabular}{llllrrlll}", r"\toprule",
             r"figure & technique & budget & metric & ours & $\pm$95\,\% & paper & gain & "
             r"paper gain \\", r"\midrule"]
    for doc in docs:
        for row in table_rows(doc):
            v = _row_values(doc, row)
            cells = [v.figure, v.technique, v.budget,
                     {"sigma_over_mu": r"$\sigma/\mu$"}.get(v.metric, v.metric),
                     _fmt(v.mean), _fmt(v.half_width, 2), _fmt(v.paper.value),
                     "--" if v.gain is None else f"{v.gain.value:.3g}", _fmt(v.paper.gain, 3)]
            lines.append(" & ".join(_tex_escape(str(c)) if not c.startswith("$") else c
                                    for c in cells) + r" \\")
    lines += [r"\bottomrule", r"\end{tabular}"]
    return "\n".join(lines).replace("—", "--") + "\n"


def write_all(profile_name: str) -> list[Path]:
    written = []
    for paper, docs in load_results(profile_name).items():
        if paper == matrix_configs.PAPER:  # one table of scenes by techniques: matrix_tables
            continue
        for doc in docs:
            if config_changed(doc):
                print(f"warning: {doc.experiment}: the config has changed since these "
                      "results were made; the tables say so", file=sys.stderr)
        for ext, text in (("md", markdown(paper, docs)), ("csv", csv_text(docs)),
                          ("tex", latex(paper, docs))):
            out = paths.TABLES / f"{paper}{paths.suffix(profile_name)}.{ext}"
            provenance.write_text_atomically(out, text)
            written.append(out)
    return written
