"""RIS fig. 4 with the map: the most resampling could gain on our scene, from the results of
configs/experiments/ris/fig04_m_sweep.json (light sampling at N = 5 and 20, RIS at fixed M = 2
… 64 with N = 20, equal primary rays).

The model is the paper's eq. (2), summed over the image: N light samples of M candidates at each
of `spp` primary rays give an image MSE of

    MSE · spp = C + (A/M + B)/N,

with A = Σ(e3 − e2), B = Σ(e2 − e1) over pixels and C the variance of the primary rays
themselves (the pixel's area, what N does not average). The renders' times give the costs:

    render time = S + spp · pixels · (T_0 + N (M T_X + T_Y)).

At a fixed number of primary rays (the paper's setting, and robust RIS's), RIS may spend on each
the time of 20 light samples, 20 (T_X + T_Y): N(M) = 20 (T_X + T_Y)/(M T_X + T_Y). The largest
equal-time gain over light sampling that any M could reach is then

    max over M ≥ 1 of (C + (A + B)/20) / (C + (A/M + B)/N(M)),

a function of r = T_Y/T_X alone; r → ∞ (free candidates) gives its ceiling, the gain at equal
samples and M → ∞. Fitted by weighted least squares (each mean weighted by its standard error
over seeds), with 95 % intervals from resampling the seeds. Writes the plot and
results/tables/ris_variance_model<suffix>.md; nothing when the experiment has not been run."""
import json
from dataclasses import dataclass
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness import paths, plots, provenance, records  # noqa: E402

EXPERIMENT = "fig04_m_sweep"
BASE_N = 20  # the paper's light samples per primary ray
PAPER_GAIN = 3.33  # fig. 4: variance −70 %
TARGET_GAIN = 1.3  # issue 40's done criterion
BOOTSTRAP = 2000


@dataclass(frozen=True)
class Fit:
    a: float  # Σ (e3 − e2): what more candidates remove
    b: float  # Σ (e2 − e1): what they cannot (ĝ is not f: visibility)
    c: float  # the primary rays' own variance
    t0: float  # seconds per primary ray besides its light samples
    tx: float  # seconds per candidate
    ty: float  # seconds per finished sample (its shadow ray)

    def gain(self, m: np.ndarray, r: float) -> np.ndarray:
        """Equal-time gain of M candidates over light sampling at the same primary rays, for
        T_Y/T_X = r (N from the time of BASE_N light samples, at least 1)."""
        n = np.maximum(1.0, BASE_N * (1 + r) / (m + r))
        return (self.c + (self.a + self.b) / BASE_N) / (self.c + (self.a / m + self.b) / n)

    def best_gain(self, r: float) -> tuple[float, float]:
        """The largest gain over M (and the M that reaches it)."""
        m = np.geomspace(1, 1e5, 4001)
        g = self.gain(m, r)
        return float(g.max()), float(m[g.argmax()])

    def robust_gain(self, r: float) -> float:
        """The gain of robust RIS (eq. 4: M = T_Y/T_X, at least 1)."""
        return float(self.gain(np.array([max(1.0, r)]), r)[0])

    def robust_ratio_for(self, gain: float) -> float:
        """The smallest T_Y/T_X at which robust RIS reaches `gain` (inf: never)."""
        return self._smallest_ratio(self.robust_gain, gain)

    def ceiling(self) -> float:
        """Free candidates: equal samples, M → ∞."""
        return (self.c + (self.a + self.b) / BASE_N) / (self.c + self.b / BASE_N)

    def ratio_for(self, gain: float) -> float:
        """The smallest T_Y/T_X at which the best M reaches `gain` (inf: never)."""
        return self._smallest_ratio(lambda r: self.best_gain(r)[0], gain)

    def _smallest_ratio(self, gain_at, gain: float) -> float:
        """Bisection in log r; both gains grow with r towards the ceiling."""
        if self.ceiling() <= gain:
            return float("inf")
        lo, hi = 1e-3, 1e6
        for _ in range(100):
            mid = np.sqrt(lo * hi)
            lo, hi = (mid, hi) if gain_at(mid) < gain else (lo, mid)
        return float(hi)


def _counts(integrator: dict) -> tuple[float, float]:
    """M and N of a technique of the sweep."""
    if integrator["type"] == "direct":
        return 1.0, float(integrator["light_samples"])
    return float(integrator["candidates"]), float(integrator["samples"])


def _fit(runs: list[records.RunRecord], counts: dict[str, tuple[float, float]],
         pixels: int) -> Fit:
    groups = records.group_by_key(runs)
    rows, mse, weight = [], [], []
    for key, group in groups.items():
        m, n = counts[key.technique]
        values = np.array([r.metrics["mse"] * r.spp for r in group])
        err = values.std(ddof=1) / np.sqrt(len(values)) if len(values) > 1 else values.mean()
        rows.append([1.0, 1 / (m * n), 1 / n])
        mse.append(values.mean())
        weight.append(1 / max(err, 1e-30))
    x, y, w = np.array(rows), np.array(mse), np.array(weight)
    c, a, b = np.linalg.lstsq(x * w[:, None], y * w, rcond=None)[0]
    # Times: S + spp·pixels·(T_0 + N M T_X + N T_Y), over every run.
    design = np.array([[1.0, r.spp * pixels, r.spp * pixels * counts[r.technique][0]
                        * counts[r.technique][1], r.spp * pixels * counts[r.technique][1]]
                       for r in runs])
    times = np.array([r.time for r in runs])
    _, t0, tx, ty = np.linalg.lstsq(design, times, rcond=None)[0]
    return Fit(float(a), float(b), float(c), float(t0), float(tx), float(ty))


def _resampled(runs: list[records.RunRecord], counts, pixels: int, rng) -> Fit:
    """The fit on the seeds drawn with replacement (every run of a drawn seed)."""
    seeds = sorted({r.seed for r in runs})
    drawn = rng.choice(seeds, size=len(seeds), replace=True)
    chosen = [r for s in drawn for r in runs if r.seed == s]  # a seed drawn twice counts twice
    return _fit(chosen, counts, pixels)


def _interval(values: list[float]) -> tuple[float, float]:
    v = np.array(values)
    v = v[np.isfinite(v)] if np.isfinite(v).any() else v
    return float(np.percentile(v, 2.5)), float(np.percentile(v, 97.5))


def _quantities(fit: Fit) -> dict[str, float]:
    r = fit.ty / fit.tx
    return {
        "A/B": fit.a / fit.b,
        "ceiling": fit.ceiling(),
        "T_X (ns)": fit.tx * 1e9,
        "T_Y (ns)": fit.ty * 1e9,
        "T_0 (ns)": fit.t0 * 1e9,
        "T_Y/T_X": r,
        "best gain at T_Y/T_X": fit.best_gain(r)[0],
        "best M at T_Y/T_X": fit.best_gain(r)[1],
        "robust gain at T_Y/T_X": fit.robust_gain(r),
        "robust gain at T_Y/T_X = 2": fit.robust_gain(2.0),
        f"T_Y/T_X for robust x{TARGET_GAIN}": fit.robust_ratio_for(TARGET_GAIN),
        "best gain at T_Y/T_X = 2": fit.best_gain(2.0)[0],
        "best gain at T_Y/T_X = 4": fit.best_gain(4.0)[0],
        f"T_Y/T_X for x{TARGET_GAIN}": fit.ratio_for(TARGET_GAIN),
        f"T_X (ns) for x{TARGET_GAIN}": fit.ty / fit.ratio_for(TARGET_GAIN) * 1e9,
        f"T_Y/T_X for x{PAPER_GAIN / 1.25:.2f}": fit.ratio_for(PAPER_GAIN / 1.25),
    }


def _table(doc: records.Results, fit: Fit, intervals: dict[str, tuple[float, float]]) -> str:
    lines = [f"# RIS fig. 4 with the map: the most resampling could gain ({doc['profile']} "
             f"profile)", "",
             f"From `{doc['config']['file']}` ({len(doc['seeds'])} seeds, "
             f"{doc['resolution'][0]} × {doc['resolution'][1]}, "
             f"{doc['provenance']['parallel_jobs']} renders at once, "
             f"{doc['provenance']['threads_per_job']} thread each), written by "
             "`experiments/figures/ris_fig04_variance_model.py` (the model is in its docstring). "
             "Gains are equal-time MSE ratios over light sampling (M = 1, N = 20) at the same "
             "primary rays, for the best M; intervals: 95 %, seeds resampled.", "",
             "| quantity | value | 95 % interval |", "|---|---|---|"]
    for name, value in _quantities(fit).items():
        lo, hi = intervals[name]
        lines.append(f"| {name} | {value:.3g} | [{lo:.3g}, {hi:.3g}] |")
    return "\n".join(lines) + "\n"


def write(profile_name: str) -> list[Path]:
    suffix = paths.suffix(profile_name)
    file = paths.RESULTS / "ris" / f"{EXPERIMENT}{suffix}.json"
    if not file.exists():
        return []
    doc = json.loads(file.read_text())
    runs = [r for r in records.read_runs(doc) if r.kind == records.SPP]
    counts = {name: _counts(t["integrator"]) for name, t in doc["techniques"].items()}
    pixels = doc["resolution"][0] * doc["resolution"][1]
    fit = _fit(runs, counts, pixels)
    rng = np.random.default_rng(0)
    resampled = [_resampled(runs, counts, pixels, rng) for _ in range(BOOTSTRAP)]
    names = list(_quantities(fit))
    samples = [_quantities(f) for f in resampled]
    intervals = {n: _interval([s[n] for s in samples]) for n in names}

    fig, (by_m, by_cost) = plt.subplots(1, 2, figsize=(12, 4.6))
    for key, group in sorted(records.group_by_key(runs).items(),
                             key=lambda kv: counts[kv[0].technique]):
        m, n = counts[key.technique]
        if n != BASE_N:
            continue
        values = np.array([r.metrics["mse"] * r.spp for r in group])
        by_m.errorbar(m, values.mean(), yerr=1.96 * values.std(ddof=1) / np.sqrt(len(values)),
                      color="C0" if key.budget == max(doc["budgets"]["spp"]) else "C1",
                      marker="o", capsize=2, ls="none")
    ms = np.geomspace(1, 128, 200)
    by_m.plot(ms, fit.c + (fit.a / ms + fit.b) / BASE_N, "k-", lw=1,
              label=f"C + (A/M + B)/N, A/B = {fit.a / fit.b:.2f}")
    by_m.axhline(fit.c + fit.b / BASE_N, color="k", ls=":", lw=1, label="M → ∞")
    by_m.set_xscale("log", base=2)
    by_m.set_xlabel(f"candidates per sample M (N = {BASE_N})")
    by_m.set_ylabel("MSE × spp")
    by_m.set_title("equal samples: eq. (2) fitted (blue: 20 spp, orange: 4 spp)")
    rs = np.geomspace(0.1, 100, 120)
    by_cost.plot(rs, [fit.best_gain(r)[0] for r in rs], "C0-", label="best M, equal time")
    lo = [np.percentile([f.best_gain(r)[0] for f in resampled[:200]], 2.5) for r in rs[::6]]
    hi = [np.percentile([f.best_gain(r)[0] for f in resampled[:200]], 97.5) for r in rs[::6]]
    by_cost.fill_between(rs[::6], lo, hi, color="C0", alpha=0.2, label="95 % (seeds resampled)")
    by_cost.plot(rs, [fit.robust_gain(r) for r in rs], "C1-", label="robust M = T_Y/T_X (eq. 4)")
    by_cost.axhline(fit.ceiling(), color="k", ls=":", lw=1, label="ceiling: free candidates")
    by_cost.axhline(TARGET_GAIN, color="C3", ls="--", lw=1, label=f"x{TARGET_GAIN}")
    by_cost.axvline(fit.ty / fit.tx, color="C2", lw=1,
                    label=f"measured here: T_Y/T_X = {fit.ty / fit.tx:.2f}")
    by_cost.set_xscale("log")
    by_cost.set_xlabel("T_Y / T_X")
    by_cost.set_ylabel("MSE gain over light sampling")
    by_cost.set_title("the equal-time gain: the best M, and robust RIS's")
    for ax in (by_m, by_cost):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"{doc['experiment']} ({doc['profile']} profile, {len(doc['seeds'])} seeds)")
    fig.tight_layout()
    out = paths.PLOTS / "ris" / f"{EXPERIMENT}_variance_model{suffix}.png"
    plots.save(fig, out)
    table = paths.TABLES / f"ris_variance_model{suffix}.md"
    provenance.write_text_atomically(table, _table(doc, fit, intervals))
    return [out, table]
