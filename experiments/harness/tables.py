"""Tables per paper from results/<paper>/*.json: Markdown (main table, secondary metrics,
convergence slopes), CSV (every number) and LaTeX (the main table, booktabs)."""
import csv
import io
import json
import math
import sys

from . import config, paths, provenance, stats
from .errors import ConfigError

METRIC_NAMES = {"sigma_over_mu": "σ/µ", "rmse": "RMSE", "mse": "MSE", "relmse": "relMSE",
                "tvi_err": "Err (tvi)", "p_eff": "P-Eff", "mse_eff": "1/(T·MSE)"}


def load_results(profile_name):
    """{paper: [results document, ...]} of one profile, in figure order."""
    by_paper = {}
    for file in sorted(paths.RESULTS.glob(f"*/*{paths.suffix(profile_name)}.json")):
        if file.parent.name in ("tables", "plots", "renders", "previews"):
            continue
        doc = json.loads(file.read_text())
        if doc["profile"] == profile_name:
            by_paper.setdefault(file.parent.name, []).append(doc)
    return by_paper


def _fixed_spp(doc, technique):
    return doc["techniques"][technique].get("fixed_spp", False)


def _matched_to(doc, row):
    """"tais at 16 spp" when the row's equal-time budget is a fixed-spp technique's measured
    render time (several joined by ", "); "" otherwise."""
    if row["kind"] != "time":
        return ""
    return ", ".join(f"{m['technique']} at {m['spp']} spp" for m in doc.get("matched", [])
                     if m["seconds"] == row["budget"])


def _rows(doc):
    """The table's rows: each technique (baseline first) at the equal-sample budget of the
    paper's number for the primary metric (else the table's), and, when the profile has one,
    at the table's equal-time budget (fixed-spp techniques have none). With "matched" as the
    table's seconds, the equal-time rows follow the equal-sample ones: for each fixed-spp
    technique, the time-capable techniques (baseline first) at its matched time for the
    table's spp, then the technique itself at that time (its own renders at that spp)."""
    techniques = [doc["baseline"]] + [t for t in doc["techniques"] if t != doc["baseline"]]
    summary = {(s["technique"], s["kind"], s["budget"]): s for s in doc["summary"]}
    paper = _paper_entry(doc, doc["metrics"][0])
    spp = paper["spp"] if paper else doc["table"]["spp"]
    seconds = doc["table"]["seconds"]
    if seconds == "matched":
        rows = [summary[(t, "spp", spp)] for t in techniques]
        capable = [t for t in techniques if not _fixed_spp(doc, t)]
        for m in doc["matched"]:
            if m["spp"] == doc["table"]["spp"]:
                rows += [summary[(t, "time", m["seconds"])] for t in capable + [m["technique"]]]
        return rows
    rows = []
    for t in techniques:
        rows.append(summary[(t, "spp", spp)])
        if seconds is not None and (t, "time", seconds) in summary:
            rows.append(summary[(t, "time", seconds)])
    return rows


def _paper_entry(doc, metric, spp=None):
    """The paper's numbers for a metric (at an equal-sample budget, when given)."""
    for p in doc["paper"]:
        if p["metric"] == metric and (spp is None or p["spp"] == spp):
            return p
    return None


def _paper_cells(doc, row, metric):
    """(paper's value, its spp, paper's gain, verdict) for a row, where the paper reports the
    metric at the row's equal-sample budget; Nones and '—' elsewhere."""
    paper = _paper_entry(doc, metric, row["budget"]) if row["kind"] == "spp" else None
    if paper is None:
        return None, None, None, "—"
    higher = config.METRICS[metric]
    value = paper["values"].get(row["technique"])
    if row["technique"] == doc["baseline"]:
        return value, paper["spp"], None, "—"
    paper_gain = stats.paper_gain(paper["values"], doc["baseline"], row["technique"], higher)
    ours = _gain_estimate(row["gain"].get(metric))
    return value, paper["spp"], paper_gain, stats.verdict(ours, paper_gain)


def _gain_estimate(g):
    return stats.Gain(g["value"], g["stderr"], tuple(g["ci95"])) if g else None


def _row_values(doc, row, metric=None):
    metric = metric or doc["metrics"][0]
    m = row["metrics"][metric]
    paper_value, paper_spp, paper_gain, verdict = _paper_cells(doc, row, metric)
    gain = _gain_estimate(row["gain"].get(metric))
    budget = f"{row['budget']:g} {'spp' if row['kind'] == 'spp' else 's'}"
    if _matched_to(doc, row):
        budget += f" (time of {_matched_to(doc, row)})"
    return {
        "figure": doc["experiment"].split("/")[1],
        "technique": row["technique"],
        "budget": budget,
        "spp": row["spp"]["mean"],
        "time": row["time"]["mean"],
        "metric": metric,
        "mean": m["mean"] if m else None,
        "half_width": (m["ci95"][1] - m["mean"]) if m else None,
        "paper_value": paper_value,
        "paper_spp": paper_spp,
        "gain": gain,
        "paper_gain": paper_gain,
        "verdict": verdict,
    }


def _fmt(x, digits=4):
    return "—" if x is None else f"{x:.{digits}g}"


def _gain_text(g):
    return "—" if g is None else f"×{g.value:.3g} [{g.ci95[0]:.3g}, {g.ci95[1]:.3g}]"


def _comparison_cells(v):
    """The cells shared by both Markdown tables, from `_row_values`."""
    paper = "—" if v["paper_value"] is None else f"{v['paper_value']:.4g} ({v['paper_spp']} spp)"
    paper_gain = "—" if v["paper_gain"] is None else f"×{v['paper_gain']:.3g}"
    ours = "—" if v["mean"] is None else f"{_fmt(v['mean'])} ± {_fmt(v['half_width'], 2)}"
    return f"{ours} | {paper} | {_gain_text(v['gain'])} | {paper_gain} | {v['verdict']} |"


def _main_table(docs):
    head = ("| figure | technique | budget | spp | time (s) | metric | ours (mean ± 95 %) | paper "
            "| gain over baseline (95 %) | paper's gain | verdict |")
    lines = [head, "|" + "---|" * 11]
    for doc in docs:
        for row in _rows(doc):
            v = _row_values(doc, row)
            lines.append(f"| {v['figure']} | {v['technique']} | {v['budget']} | {v['spp']:.4g} | "
                         f"{v['time']:.3g} | {METRIC_NAMES[v['metric']]} | "
                         + _comparison_cells(v))
    return lines


def _secondary_table(docs):
    lines = ["| figure | technique | budget | metric | ours (mean ± 95 %) | paper | gain over "
             "baseline (95 %) | paper's gain | verdict |", "|" + "---|" * 9]
    for doc in docs:
        for row in _rows(doc):
            for metric in doc["metrics"][1:]:
                v = _row_values(doc, row, metric)
                lines.append(f"| {v['figure']} | {v['technique']} | {v['budget']} | "
                             f"{METRIC_NAMES[metric]} | " + _comparison_cells(v))
    return lines


def _slope_table(docs):
    lines = ["| figure | technique | metric | slope vs spp (± s.e.) | R² | slope vs time (± s.e.) "
             "| R² | points |", "|---|---|---|---|---|---|---|---|"]
    for doc in docs:
        for technique, s in doc["slopes"].items():
            a, b = s["vs_spp"], s.get("vs_time")
            time_cells = (f"{b['slope']:.3f} ± {b['slope_stderr']:.3f} | {b['r2']:.3f}" if b
                          else "— | —")
            lines.append(f"| {doc['experiment'].split('/')[1]} | {technique} | "
                         f"{METRIC_NAMES[doc['metrics'][0]]} | "
                         f"{a['slope']:.3f} ± {a['slope_stderr']:.3f} | {a['r2']:.3f} | "
                         f"{time_cells} | {a['n']} |")
    return lines


def _equivalent_baseline_spp(doc, error):
    """Samples per pixel at which the baseline's fitted convergence line (log error against log
    spp, over all its runs) reaches `error`; None without a fit."""
    fit = doc["slopes"].get(doc["baseline"], {}).get("vs_spp")
    if not fit or fit["slope"] >= 0 or not error or error <= 0:
        return None
    return math.exp((math.log(error) - fit["intercept"]) / fit["slope"])


def _cost_table(docs):
    """Per technique at the table's equal-sample budget: render time per sample relative to the
    baseline's (same spp, same seeds), the equal-sample gain next to the equal-time one, and
    how many samples the baseline needs for the technique's error (from its fitted line)."""
    lines = ["| figure | technique | spp | time per sample / baseline's | gain, equal samples | "
             "gain, equal time | baseline spp for this error (× this spp) |",
             "|---|---|---|---|---|---|---|"]
    metric = None
    for doc in docs:
        metric = doc["metrics"][0]
        summary = {(s["technique"], s["kind"], s["budget"]): s for s in doc["summary"]}
        paper = _paper_entry(doc, metric)
        spp = paper["spp"] if paper else doc["table"]["spp"]
        base = summary.get((doc["baseline"], "spp", spp))
        if base is None:
            continue
        for t in doc["techniques"]:
            row = summary.get((t, "spp", spp))
            if t == doc["baseline"] or row is None:
                continue
            cost = row["time"]["mean"] / base["time"]["mean"]
            timed = [s for s in doc["summary"] if s["technique"] == t and s["kind"] == "time"
                     and s.get("duplicate_of", {}).get("budget") == spp]
            equal_time = _gain_estimate(timed[0]["gain"].get(metric)) if timed else None
            error = row["metrics"][metric]["mean"] if row["metrics"][metric] else None
            n = _equivalent_baseline_spp(doc, error)
            lines.append(f"| {doc['experiment'].split('/')[1]} | {t} | {spp} | ×{cost:.3g} | "
                         f"{_gain_text(_gain_estimate(row['gain'].get(metric)))} | "
                         f"{_gain_text(equal_time)} | "
                         f"{'—' if n is None else f'{n:.4g} (×{n / spp:.3g})'} |")
    return lines


def _analysis(paper):
    """The hand-written analysis of a paper's results, `results/<paper>/analysis.md`, if any."""
    file = paths.RESULTS / paper / "analysis.md"
    return file.read_text().rstrip("\n").split("\n") if file.exists() else []


def config_changed(doc):
    """True when the experiment's config (thresholds aside) differs from the one that made
    these results, or is gone."""
    try:
        return config.load(paths.ROOT / doc["config"]["file"]).config_sha256 != doc["config"][
            "sha256"]
    except ConfigError:
        return True


def _experiment_notes(docs):
    lines = []
    for doc in docs:
        if config_changed(doc):
            lines.append(f"- **{doc['experiment'].split('/')[1]}: its config has changed since "
                         "this run; run it again.**")
        ref = doc["reference"]
        prov = doc["provenance"]
        matched = "".join(f" Equal time matched to {m['technique']} at {m['spp']} spp: "
                          f"{m['seconds']:g} s." for m in doc.get("matched", []))
        lines.append(
            f"- **{doc['experiment'].split('/')[1]}** ({doc['profile']} profile, "
            f"{doc['resolution'][0]}×{doc['resolution'][1]}, {len(doc['seeds'])} seeds, "
            f"{prov['parallel_jobs']} parallel renders × {prov['threads_per_job']} thread, "
            f"commit `{(prov['git_commit'] or 'unknown')[:10]}`"
            f"{' (uncommitted changes)' if prov['git_dirty'] else ''}): {doc['description']} "
            f"Reference: `{ref['integrator']['type']}`, {ref['spp']} spp, own noise σ/µ "
            f"{ref['noise_sigma_over_mu']:.2g} = {ref['noise_ratio_to_smallest_error']:.2f} of "
            f"the smallest error measured.{matched}")
    return lines


def markdown(paper, docs):
    lines = [f"# {paper}: results", "",
             "Generated by `make tables` from `results/" + paper + "/*.json`; do not edit. Errors "
             "are means over seeds with Student-t 95 % intervals; a gain is how many times "
             "better than the baseline (error ratio, or efficiency ratio for P-Eff) with a "
             "delta-method 95 % interval. Verdict: *reproduced* when our gain is within ×"
             f"{stats.REPRODUCED_FACTOR} of the paper's or the paper's lies in our interval, "
             "else *weaker* / *stronger*; — where the paper reports no number."
             + (" A budget of \"T s (time of X at N spp)\" is X's mean render time at N spp: "
                "X renders a fixed number of samples, so the other techniques are given its "
                "time, and X's row there is its N-spp renders."
                if any(doc.get("matched") for doc in docs) else ""), ""]
    lines += _main_table(docs)
    lines += ["", "## Other metrics", ""] + _secondary_table(docs)
    lines += ["", "## Convergence", "",
              "Least-squares slope of log error against log samples and log render time over "
              "every run (all seeds and budgets), from `metrics slope`; plain Monte Carlo "
              "converges as −0.5.", ""] + _slope_table(docs)
    if any(doc.get("matched") for doc in docs):
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


def csv_text(docs):
    out = io.StringIO()
    w = csv.writer(out)
    w.writerow(["experiment", "profile", "technique", "budget_kind", "budget", "metric", "mean",
                "ci95_lo", "ci95_hi", "sd", "seeds", "spp_mean", "time_mean", "gain",
                "gain_ci95_lo", "gain_ci95_hi", "paper_value", "paper_gain", "verdict",
                "matched_to"])
    for doc in docs:
        for s in doc["summary"]:
            for metric in doc["metrics"]:
                m, g = s["metrics"][metric], s["gain"].get(metric)
                paper_value, _, paper_gain, verdict = _paper_cells(doc, s, metric)
                w.writerow([doc["experiment"], doc["profile"], s["technique"], s["kind"],
                            s["budget"], metric,
                            *(m and [m["mean"], *m["ci95"], m.get("sd", ""), m["n"]] or [""] * 5),
                            s["spp"]["mean"], s["time"]["mean"],
                            *(g and [g["value"], *g["ci95"]] or [""] * 3),
                            "" if paper_value is None else paper_value,
                            "" if paper_gain is None else paper_gain,
                            "" if verdict == "—" else verdict, _matched_to(doc, s)])
    return out.getvalue()


def _tex_escape(text):
    return (text.replace("\\", r"\textbackslash{}").replace("_", r"\_").replace("%", r"\%")
            .replace("&", r"\&").replace("#", r"\#"))


def latex(paper, docs):
    lines = [r"% Generated by make tables; needs \usepackage{booktabs}.",
             r"\begin{tabular}{llllrrlll}", r"\toprule",
             r"figure & technique & budget & metric & ours & $\pm$95\,\% & paper & gain & "
             r"paper gain \\", r"\midrule"]
    for doc in docs:
        for row in _rows(doc):
            v = _row_values(doc, row)
            cells = [v["figure"], v["technique"], v["budget"],
                     {"sigma_over_mu": r"$\sigma/\mu$"}.get(v["metric"], v["metric"]),
                     _fmt(v["mean"]), _fmt(v["half_width"], 2), _fmt(v["paper_value"]),
                     "--" if v["gain"] is None else f"{v['gain'].value:.3g}",
                     _fmt(v["paper_gain"], 3)]
            lines.append(" & ".join(_tex_escape(str(c)) if not c.startswith("$") else c
                                    for c in cells) + r" \\")
    lines += [r"\bottomrule", r"\end{tabular}"]
    return "\n".join(lines).replace("—", "--") + "\n"


def write_all(profile_name):
    written = []
    for paper, docs in load_results(profile_name).items():
        for doc in docs:
            if config_changed(doc):
                print(f"warning: {doc['experiment']}: the config has changed since these "
                      "results were made; the tables say so", file=sys.stderr)
        for ext, text in (("md", markdown(paper, docs)), ("csv", csv_text(docs)),
                          ("tex", latex(paper, docs))):
            out = paths.TABLES / f"{paper}{paths.suffix(profile_name)}.{ext}"
            provenance.write_text_atomically(out, text)
            written.append(out)
    return written

