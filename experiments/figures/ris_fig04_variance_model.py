"""RIS fig. 4 with the map: the most resampling could gain on our scene, from the results of
configs/experiments/ris/fig04_m_sweep.json (light sampling at N = 5 and 20, RIS at M = 4 with
N = 5 and at M = 2 … 64 with N = 20, equal primary rays).

The model is the paper's eq. (2), summed over the image: N light samples of M candidates at each
of `spp` primary rays give an image MSE of

    MSE · spp = C + (A/M + B)/N,

with A = Σ(e3 − e2), B = Σ(e2 − e1) over pixels and C the variance of the primary rays
themselves (the pixel's area, what N does not average). The renders' times give the costs:

    render time = S + spp · pixels · (T_0 + N (M T_X + T_Y))   (RIS)
                = S + spp · pixels · (T_0 + N t_L)             (light sampling),

where t_L = T_X + T_L: light sampling draws the same light samples, but traces no shadow ray
for a sample below the horizon, which RIS with M ≥ 2 almost never keeps (T_L < T_Y).

At a fixed number of primary rays (the paper's setting, and robust RIS's), RIS may spend on each
the time of 20 light samples: N(M) = 20 (T_X + T_L)/(M T_X + T_Y), at least 1 (T_L in place of
T_Y at M = 1, which is light sampling itself, and in between for a fractional M < 2). The equal-time
gain over light sampling at M candidates is

    (C + (A + B)/20) / (C + (A/M + B)/N(M)),

robust RIS's at M = T_Y/T_X (eq. 4), the best at the best M. Both are given at the measured
costs and as functions of T_X (T_Y and T_L held: a cheaper candidate makes light sampling's
draws cheaper too); T_X → 0 (free candidates) gives the ceiling, the gain at equal samples and
M → ∞. Fitted by weighted least squares (each mean weighted by its standard error over seeds),
with 95 % intervals from resampling the seeds. Writes the plot and
results/tables/ris_variance_model<suffix>.md; nothing when the experiment has not been run."""
from dataclasses import dataclass
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness import paths, plots, provenance, records, results  # noqa: E402
from harness.results import Results  # noqa: E402

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
    tx: float  # T_X: seconds per candidate
    ty: float  # T_Y: seconds per RIS sample besides its candidates (its shadow ray)
    tl: float  # T_L: seconds per light-sampling sample besides its draw

    def gain(self, m: np.ndarray, tx: float) -> np.ndarray:
        """Equal-time gain of M candidates over light sampling at the same primary rays, for
        candidates of cost `tx`."""
        # M = 1 is light sampling itself (the same draws and rays); a fractional M between 1
        # and 2 is rounded randomly per point, so its shadow rays interpolate.
        finish = self.tl + (self.ty - self.tl) * np.clip(m - 1, 0, 1)
        n = np.maximum(1.0, BASE_N * (tx + self.tl) / (m * tx + finish))
        return (self.c + (self.a + self.b) / BASE_N) / (self.c + (self.a / m + self.b) / n)

    def best_gain(self, tx: float) -> tuple[float, float]:
        """The largest gain over M (and the M that reaches it)."""
        m = np.geomspace(1, 1e5, 4001)
        g = self.gain(m, tx)
        return float(g.max()), float(m[g.argmax()])

    def robust_gain(self, tx: float) -> float:
        """The gain of robust RIS (eq. 4: M = T_Y/T_X, at least 1)."""
        return float(self.gain(np.array([max(1.0, self.ty / tx)]), tx)[0])

    def ceiling(self) -> float:
        """Free candidates: equal samples, M → ∞."""
        return (self.c + (self.a + self.b) / BASE_N) / (self.c + self.b / BASE_N)

    def cost_for(self, gain_at, gain: float) -> float:
        """The largest T_X at which gain_at(T_X) reaches `gain` (0: never); both gains fall as
        T_X grows. Bisection in log T_X."""
        if self.ceiling() <= gain:
            return 0.0
        lo, hi = 1e-13, 1e-5
        for _ in range(100):
            mid = np.sqrt(lo * hi)
            lo, hi = (mid, hi) if gain_at(mid) >= gain else (lo, mid)
        return float(lo)


LIGHT = ("light", "light_n5")  # the light-sampling techniques of the sweep


def _counts(integrator: dict) -> tuple[float, float]:
    """M and N of a technique of the sweep."""
    if integrator["type"] == "direct":
        return 1.0, float(integrator["light_samples"])
    return float(integrator["candidates"]), float(integrator["samples"])


def _mse_times_spp(group: list[records.RunRecord]) -> np.ndarray:
    """MSE · spp of each run (the model's left side); every run of the sweep has an MSE."""
    return np.array([(r.metrics["mse"] or np.nan) * r.spp for r in group])


def _fit(runs: list[records.RunRecord], counts: dict[str, tuple[float, float]],
         pixels: int) -> Fit:
    groups = records.group_by_key(runs)
    rows, mse, weight = [], [], []
    for key, group in groups.items():
        m, n = counts[key.technique]
        values = _mse_times_spp(group)
        err = values.std(ddof=1) / np.sqrt(len(values)) if len(values) > 1 else values.mean()
        rows.append([1.0, 1 / (m * n), 1 / n])
        mse.append(values.mean())
        weight.append(1 / max(err, 1e-30))
    x, y, w = np.array(rows), np.array(mse), np.array(weight)
    c, a, b = np.linalg.lstsq(x * w[:, None], y * w, rcond=None)[0]
    # Times: S + spp·pixels·(T_0 + N (M T_X + T_Y)), or (T_0 + N t_L) for light sampling.
    design, times = [], []
    for r in runs:
        m, n = counts[r.technique]
        rays = r.spp * pixels
        light = r.technique in LIGHT
        design.append([1.0, rays, 0 if light else rays * n * m, 0 if light else rays * n,
                       rays * n if light else 0])
        times.append(r.time)
    _, t0, tx, ty, tl = np.linalg.lstsq(np.array(design), np.array(times), rcond=None)[0]
    return Fit(float(a), float(b), float(c), float(t0), float(tx), float(ty), float(tl - tx))


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
    half = fit.ty / 2  # T_Y/T_X = 2: issue 40's first criterion
    robust_tx = fit.cost_for(fit.robust_gain, TARGET_GAIN)
    return {
        "A/B": fit.a / fit.b,
        "ceiling (free candidates)": fit.ceiling(),
        "T_X (ns)": fit.tx * 1e9,
        "T_Y (ns)": fit.ty * 1e9,
        "T_L (ns)": fit.tl * 1e9,
        "T_0 (ns)": fit.t0 * 1e9,
        "T_Y/T_X": fit.ty / fit.tx,
        "robust RIS: gain": fit.robust_gain(fit.tx),
        "best M: gain": fit.best_gain(fit.tx)[0],
        "best M": fit.best_gain(fit.tx)[1],
        "robust RIS: gain at T_Y/T_X = 2": fit.robust_gain(half),
        "best M: gain at T_Y/T_X = 2": fit.best_gain(half)[0],
        f"robust RIS: T_X (ns) for x{TARGET_GAIN}": robust_tx * 1e9,
        f"robust RIS: T_Y/T_X for x{TARGET_GAIN}": fit.ty / robust_tx if robust_tx else np.inf,
        f"best M: T_X (ns) for x{TARGET_GAIN}":
            fit.cost_for(lambda tx: fit.best_gain(tx)[0], TARGET_GAIN) * 1e9,
        f"best M: T_X (ns) for x{PAPER_GAIN / 1.25:.2f}":
            fit.cost_for(lambda tx: fit.best_gain(tx)[0], PAPER_GAIN / 1.25) * 1e9,
    }


def _table(doc: Results, fit: Fit, intervals: dict[str, tuple[float, float]]) -> str:
    lines = [f"# RIS fig. 4 with the map: the most resampling could gain ({doc.profile} "
             f"profile)", "",
             f"From `{doc.config.file}` ({len(doc.seeds)} seeds, "
             f"{doc.resolution[0]} × {doc.resolution[1]}, "
             f"{doc.provenance.parallel_jobs} renders at once, "
             f"{doc.provenance.threads_per_job} thread each), written by "
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
    doc = results.read(file)
    runs = [r for r in doc.runs if r.kind == records.SPP]
    counts = {name: _counts(t.integrator) for name, t in doc.techniques.items()}
    pixels = doc.resolution[0] * doc.resolution[1]
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
        values = _mse_times_spp(group)
        by_m.errorbar(m, values.mean(), yerr=1.96 * values.std(ddof=1) / np.sqrt(len(values)),
                      color="C0" if key.budget == max(doc.budgets.spp) else "C1",
                      marker="o", capsize=2, ls="none")
    ms = np.geomspace(1, 128, 200)
    by_m.plot(ms, fit.c + (fit.a / ms + fit.b) / BASE_N, "k-", lw=1,
              label=f"C + (A/M + B)/N, A/B = {fit.a / fit.b:.2f}")
    by_m.axhline(fit.c + fit.b / BASE_N, color="k", ls=":", lw=1, label="M → ∞")
    by_m.set_xscale("log", base=2)
    by_m.set_xlabel(f"candidates per sample M (N = {BASE_N})")
    by_m.set_ylabel("MSE × spp")
    by_m.set_title("equal samples: eq. (2) fitted (blue: 20 spp, orange: 4 spp)")
    txs = np.geomspace(1e-9, 400e-9, 120)
    ns = txs * 1e9
    by_cost.plot(ns, [fit.best_gain(tx)[0] for tx in txs], "C0-", label="best M")
    few = resampled[:200]
    by_cost.fill_between(ns[::6], *[[np.percentile([f.best_gain(tx)[0] for f in few], q)
                                     for tx in txs[::6]] for q in (2.5, 97.5)],
                         color="C0", alpha=0.2, label="95 % (seeds resampled)")
    by_cost.plot(ns, [fit.robust_gain(tx) for tx in txs], "C1-",
                 label="robust RIS, M = T_Y/T_X (eq. 4)")
    by_cost.axhline(fit.ceiling(), color="k", ls=":", lw=1, label="ceiling: free candidates")
    by_cost.axhline(TARGET_GAIN, color="C3", ls="--", lw=1, label=f"x{TARGET_GAIN}")
    by_cost.axvline(fit.tx * 1e9, color="C2", lw=1,
                    label=f"measured: T_X = {fit.tx * 1e9:.0f} ns, T_Y = {fit.ty * 1e9:.0f} ns")
    by_cost.axvline(fit.ty / 2 * 1e9, color="C2", ls="--", lw=1, label="T_Y/T_X = 2")
    by_cost.set_xscale("log")
    by_cost.set_xlabel("T_X, ns per candidate (T_Y and T_L as measured)")
    by_cost.set_ylabel("MSE gain over light sampling")
    by_cost.set_title("the equal-time gain: the best M, and robust RIS's")
    for ax in (by_m, by_cost):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"{doc.experiment} ({doc.profile} profile, {len(doc.seeds)} seeds)")
    fig.tight_layout()
    out = paths.PLOTS / "ris" / f"{EXPERIMENT}_variance_model{suffix}.png"
    plots.save(fig, out)
    table = paths.TABLES / f"ris_variance_model{suffix}.md"
    provenance.write_text_atomically(table, _table(doc, fit, intervals))
    return [out, table]
