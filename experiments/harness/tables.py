"""Tables per paper from results/<paper>/*.json: Markdown (main table, secondary metrics,
convergence slopes), CSV (every number) and LaTeX (the main table, booktabs)."""
import csv
import io
import json

from . import config, paths, stats

METRIC_NAMES = {"sigma_over_mu": "σ/µ", "rmse": "RMSE", "mse": "MSE", "relmse": "relMSE",
                "tvi_err": "Err (tvi)", "p_eff": "P-Eff", "mse_eff": "1/(T·MSE)"}


def load_results():
    """{paper: [results document, ...]} in figure order."""
    by_paper = {}
    for file in sorted(paths.RESULTS.glob("*/*.json")):
        if file.parent.name in ("tables", "plots", "renders", "previews"):
            continue
        doc = json.loads(file.read_text())
        by_paper.setdefault(file.parent.name, []).append(doc)
    return by_paper


def _rows(doc):
    """The table's rows: each technique (baseline first) at the table's equal-sample budget
    and, when the profile has one, its equal-time budget."""
    techniques = [doc["baseline"]] + [t for t in doc["techniques"] if t != doc["baseline"]]
    summary = {(s["technique"], s["kind"], s["budget"]): s for s in doc["summary"]}
    rows = []
    for t in techniques:
        rows.append(summary[(t, "spp", doc["table"]["spp"])])
        if doc["table"]["seconds"] is not None:
            rows.append(summary[(t, "time", doc["table"]["seconds"])])
    return rows


def _paper_entry(doc, metric):
    for p in doc["paper"]:
        if p["metric"] == metric:
            return p
    return None


def _gain_estimate(g):
    return stats.Gain(g["value"], g["stderr"], tuple(g["ci95"])) if g else None


def _row_values(doc, row):
    metric = doc["metrics"][0]
    higher = config.METRICS[metric]
    m = row["metrics"][metric]
    paper = _paper_entry(doc, metric)
    paper_value = paper["values"].get(row["technique"]) if paper and row["kind"] == "spp" else None
    paper_gain = (stats.paper_gain(paper["values"], doc["baseline"], row["technique"], higher)
                  if paper and row["kind"] == "spp" and row["technique"] != doc["baseline"]
                  else None)
    gain = _gain_estimate(row["gain"].get(metric))
    return {
        "figure": doc["experiment"].split("/")[1],
        "technique": row["technique"],
        "budget": (f"{row['budget']:g} spp" if row["kind"] == "spp"
                   else f"{row['budget']:g} s"),
        "spp": row["spp"]["mean"],
        "time": row["time"]["mean"],
        "metric": metric,
        "mean": m["mean"] if m else None,
        "half_width": (m["ci95"][1] - m["mean"]) if m else None,
        "paper_value": paper_value,
        "paper_spp": paper["spp"] if paper else None,
        "gain": gain,
        "paper_gain": paper_gain,
        "verdict": stats.verdict(gain, paper_gain) if row["technique"] != doc["baseline"] else "—",
    }


def _fmt(x, digits=4):
    return "—" if x is None else f"{x:.{digits}g}"


def _gain_text(g):
    return "—" if g is None else f"×{g.value:.3g} [{g.ci95[0]:.3g}, {g.ci95[1]:.3g}]"


def _main_table(docs):
    head = ("| figure | technique | budget | spp | time (s) | metric | ours (mean ± 95 %) | paper "
            "| gain over baseline (95 %) | paper's gain | verdict |")
    lines = [head, "|" + "---|" * 11]
    for doc in docs:
        for row in _rows(doc):
            v = _row_values(doc, row)
            paper = ("—" if v["paper_value"] is None
                     else f"{v['paper_value']:.4g} ({v['paper_spp']} spp)")
            paper_gain = "—" if v["paper_gain"] is None else f"×{v['paper_gain']:.3g}"
            lines.append(
                f"| {v['figure']} | {v['technique']} | {v['budget']} | {v['spp']:.4g} | "
                f"{v['time']:.3g} | {METRIC_NAMES[v['metric']]} | "
                f"{_fmt(v['mean'])} ± {_fmt(v['half_width'], 2)} | {paper} | "
                f"{_gain_text(v['gain'])} | {paper_gain} | {v['verdict']} |")
    return lines


def _secondary_table(docs):
    lines = ["| figure | technique | budget | metric | mean ± 95 % | gain over baseline |",
             "|---|---|---|---|---|---|"]
    for doc in docs:
        for row in _rows(doc):
            for metric in doc["metrics"][1:]:
                m = row["metrics"][metric]
                budget = f"{row['budget']:g} {'spp' if row['kind'] == 'spp' else 's'}"
                value = "—" if m is None else f"{m['mean']:.4g} ± {m['ci95'][1] - m['mean']:.2g}"
                lines.append(f"| {doc['experiment'].split('/')[1]} | {row['technique']} | "
                             f"{budget} | {METRIC_NAMES[metric]} | {value} | "
                             f"{_gain_text(_gain_estimate(row['gain'].get(metric)))} |")
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


def _experiment_notes(docs):
    lines = []
    for doc in docs:
        ref = doc["reference"]
        prov = doc["provenance"]
        lines.append(
            f"- **{doc['experiment'].split('/')[1]}** ({doc['profile']} profile, "
            f"{doc['resolution'][0]}×{doc['resolution'][1]}, {len(doc['seeds'])} seeds, "
            f"{prov['parallel_jobs']} parallel renders × {prov['threads_per_job']} thread, "
            f"commit `{(prov['git_commit'] or 'unknown')[:10]}`"
            f"{' (uncommitted changes)' if prov['git_dirty'] else ''}): {doc['description']} "
            f"Reference: `{ref['integrator']['type']}`, {ref['spp']} spp, own noise σ/µ "
            f"{ref['noise_sigma_over_mu']:.2g} = {ref['noise_ratio_to_smallest_error']:.2f} of "
            f"the smallest error measured.")
    return lines


def markdown(paper, docs):
    lines = [f"# {paper}: results", "",
             "Generated by `make tables` from `results/" + paper + "/*.json`; do not edit. Errors "
             "are means over seeds with Student-t 95 % intervals; a gain is how many times "
             "better than the baseline (error ratio, or efficiency ratio for P-Eff) with a "
             "delta-method 95 % interval. Verdict: *reproduced* when our gain is within ×"
             f"{stats.REPRODUCED_FACTOR} of the paper's or the paper's lies in our interval, "
             "else *weaker* / *stronger*; — where the paper reports no number.", ""]
    lines += _main_table(docs)
    lines += ["", "## Other metrics", ""] + _secondary_table(docs)
    lines += ["", "## Convergence", "",
              "Least-squares slope of log error against log samples and log render time over "
              "every run (all seeds and budgets), from `metrics slope`; plain Monte Carlo "
              "converges as −0.5.", ""] + _slope_table(docs)
    lines += ["", "## Experiments", ""] + _experiment_notes(docs)
    return "\n".join(lines) + "\n"


def csv_text(docs):
    out = io.StringIO()
    w = csv.writer(out)
    w.writerow(["experiment", "profile", "technique", "budget_kind", "budget", "metric", "mean",
                "ci95_lo", "ci95_hi", "sd", "seeds", "spp_mean", "time_mean", "gain",
                "gain_ci95_lo", "gain_ci95_hi", "paper_value", "paper_gain", "verdict"])
    for doc in docs:
        primary = doc["metrics"][0]
        paper = _paper_entry(doc, primary)
        for s in doc["summary"]:
            for metric in doc["metrics"]:
                m, g = s["metrics"][metric], s["gain"].get(metric)
                is_paper_row = metric == primary and paper and s["kind"] == "spp"
                paper_value = paper["values"].get(s["technique"]) if is_paper_row else None
                paper_gain = (stats.paper_gain(paper["values"], doc["baseline"], s["technique"],
                                               config.METRICS[metric]) if is_paper_row else None)
                verdict = (stats.verdict(_gain_estimate(g), paper_gain)
                           if is_paper_row and s["technique"] != doc["baseline"] else "")
                w.writerow([doc["experiment"], doc["profile"], s["technique"], s["kind"],
                            s["budget"], metric, *(m and [m["mean"], *m["ci95"], m["sd"], m["n"]]
                                                   or [""] * 5),
                            s["spp"]["mean"], s["time"]["mean"],
                            *(g and [g["value"], *g["ci95"]] or [""] * 3),
                            "" if paper_value is None else paper_value,
                            "" if paper_gain is None else paper_gain, verdict])
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


def write_all():
    written = []
    for paper, docs in load_results().items():
        for ext, text in (("md", markdown(paper, docs)), ("csv", csv_text(docs)),
                          ("tex", latex(paper, docs))):
            out = paths.TABLES / f"{paper}.{ext}"
            out.parent.mkdir(parents=True, exist_ok=True)
            _write_text_atomically(out, text)
            written.append(out)
    return written


def _write_text_atomically(path, text):
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(text)
    tmp.replace(path)
