"""Two-stage fig. 12: image quality against render time for MIS, RIS 2, two-stage sampling and
simulated wavelet importance sampling (two-stage with many splits), from the results of
configs/experiments/twostage/fig12_time.json. As in the paper, the simulated WaIS is plotted at
MIS's time for the same N (solid diamonds: its sampling assumed as cheap as MIS's, its
preprocessing not charged) and at two-stage's time (hollow diamonds: equal samples); here also
at its own measured time (crosses: the many-split partition charged). The right panel is the
same error against N. Nothing is written when the experiment has not been run."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness import paths, plots, results, tables  # noqa: E402
from harness.records import SPP  # noqa: E402
from harness.results import Results  # noqa: E402

FIGURE = "fig12_time"
CURVES = {"mis": ("MIS", "C0", "o"), "ris2": ("RIS 2", "C1", "s"),
          "two_stage": ("two-stage", "C2", "^")}
WAIS = "wais_sim"


def _by_n(doc: Results, technique: str, metric: str) -> dict[float, tuple[float, ...]]:
    """N -> (mean render time, mean error, 95 % interval low, high) of one technique."""
    out: dict[float, tuple[float, ...]] = {}
    for s in doc.summary:
        m = s.metrics[metric]
        if s.technique == technique and s.kind == SPP and m is not None:
            out[s.budget] = (s.time.mean, m.mean, m.ci95[0], m.ci95[1])
    return out


def _line(ax, ns, series, x_of, **style) -> None:
    x = np.array([x_of(n) for n in ns])
    mean = np.array([series[n][1] for n in ns])
    err = np.array([[series[n][1] - series[n][2] for n in ns],
                    [series[n][3] - series[n][1] for n in ns]])
    ax.errorbar(x, mean, yerr=err, capsize=2, ms=5, lw=1, **style)


def write(profile_name: str) -> list[Path]:
    file = paths.RESULTS / "twostage" / f"{FIGURE}{paths.suffix(profile_name)}.json"
    if not file.exists():
        return []
    doc = results.read(file)
    metric = doc.primary_metric
    series = {t: _by_n(doc, t, metric) for t in list(CURVES) + [WAIS]}
    fig, (by_time, by_n) = plt.subplots(1, 2, figsize=(12, 4.6))
    for t, (label, colour, marker) in CURVES.items():
        ns = sorted(series[t])
        _line(by_time, ns, series[t], lambda n, t=t: series[t][n][0], color=colour,
              marker=marker, label=label)
        _line(by_n, ns, series[t], float, color=colour, marker=marker, label=label)
    wais = series[WAIS]
    ns = sorted(n for n in wais if n in series["mis"] and n in series["two_stage"])
    _line(by_time, ns, wais, lambda n: series["mis"][n][0], color="C3", marker="D", ls="none",
          label="simulated WaIS at MIS's time (preprocess not charged)")
    _line(by_time, ns, wais, lambda n: series["two_stage"][n][0], color="C3", marker="D",
          mfc="none", ls="none", label="simulated WaIS at two-stage's time (equal samples)")
    _line(by_time, ns, wais, lambda n: wais[n][0], color="C3", marker="x", ls=":",
          label="simulated WaIS at its own time (1024 splits charged)")
    _line(by_n, ns, wais, float, color="C3", marker="D", mfc="none", label="simulated WaIS")
    threads = doc.provenance.threads_per_job
    by_time.set_xlabel(f"render time (s, {threads} thread{'s' if threads > 1 else ''} per render)")
    by_n.set_xlabel("samples per pixel N")
    for ax in (by_time, by_n):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel(tables.METRIC_NAMES[metric])
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    by_time.set_title("quality against render time")
    by_n.set_title("quality against samples")
    fig.suptitle(f"{doc.experiment} ({doc.profile} profile, {len(doc.seeds)} seeds, "
                 f"{doc.resolution[0]}×{doc.resolution[1]}, 95 % intervals over seeds)")
    fig.tight_layout()
    out = paths.PLOTS / "twostage" / f"{FIGURE}{paths.suffix(profile_name)}.png"
    plots.save(fig, out)
    return [out]
