"""RIS fig. 1 (Talbot et al. 2005 §3): the density of the resampled Y for p uniform on
[0, π/2] and ĝ(θ) = cos θ + sin⁴(6θ), M = 1, 2, 8 and ∞: histograms of 10⁶ resampled values
against the exact density of resampling,

    p_Y(y) = p(y) · w(y) · E[M / (w(y) + S)],   S = Σ of M − 1 weights w(X), X ~ p, w = ĝ/p,

evaluated by quadrature for M = 2 and by a long-run average over S for M = 8; M = 1 is p and
M = ∞ is ĝ normalised. The samples are drawn here with numpy by the same streaming reservoir
as renderer/techniques/ris/reservoir.h (tests/ris/test_resampling.cpp checks the renderer's own
reservoir against the exact M = 2 density by χ²)."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness import paths, plots  # noqa: E402

HALF_PI = np.pi / 2
P = 1 / HALF_PI
DRAWS = 1_000_000
BINS = 60


def target(theta: np.ndarray) -> np.ndarray:
    return np.cos(theta) + np.sin(6 * theta) ** 4


def resample(m: int, rng: np.random.Generator) -> np.ndarray:
    """DRAWS resampled values from m candidates each, streamed through a weighted reservoir."""
    kept = np.zeros(DRAWS)
    weight_sum = np.zeros(DRAWS)
    for _ in range(m):
        x = rng.uniform(0, HALF_PI, DRAWS)
        w = target(x) / P
        weight_sum += w
        replace = rng.uniform(0, 1, DRAWS) * weight_sum < w
        kept[replace] = x[replace]
    return kept


def exact_density(m: int, y: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """p_Y(y) for m candidates; E[m / (w(y) + S)] by quadrature (m = 2) or over 2·10⁴ draws of S."""
    w_y = target(y)[:, None] / P
    if m == 2:
        x = (np.arange(4096) + 0.5) / 4096 * HALF_PI
        s = (target(x) / P)[None, :]
    else:
        s = (target(rng.uniform(0, HALF_PI, (20_000, m - 1))) / P).sum(axis=1)[None, :]
    return P * w_y[:, 0] * np.mean(m / (w_y + s), axis=1)


def write(profile_name: str) -> list[Path]:
    rng = np.random.default_rng(2005)
    y = np.linspace(0, HALF_PI, 400)
    g_norm = target(y) / (1 + 3 * np.pi / 16)  # ∫ cos θ + sin⁴ 6θ over [0, π/2]
    fig, ax = plt.subplots(figsize=(7, 4.2))
    colours = {1: "tab:blue", 2: "tab:orange", 8: "tab:green"}
    for m, colour in colours.items():
        samples = resample(m, rng)
        ax.hist(samples, bins=BINS, range=(0, HALF_PI), density=True, histtype="step",
                color=colour, alpha=0.55, linewidth=1.2)
        density = np.full_like(y, P) if m == 1 else exact_density(m, y, rng)
        ax.plot(y, density, color=colour, linewidth=1.8, label=f"M = {m}")
    ax.plot(y, g_norm, color="black", linewidth=1.8, linestyle="--", label="M = ∞ (ĝ normalised)")
    ax.set_xlim(0, HALF_PI)
    ax.set_ylim(0, 1.6)
    ax.set_xlabel("θ")
    ax.set_ylabel("density of Y")
    ax.set_title("RIS fig. 1: resampling p = uniform towards ĝ = cos θ + sin⁴ 6θ\n"
                 "lines: exact density; steps: histograms of 10⁶ resampled values")
    ax.legend(loc="upper right")
    out = paths.PLOTS / "ris" / f"fig01_resampling{paths.suffix(profile_name)}.png"
    plots.save(fig, out)
    return [out]
