"""PMC fig. 4: PMC-IP on the Buddha (configs/experiments/pmc/tab1_buddha.json, at its profile's
resolution, through its pbrt-v1 film and sampling, seed 0). Top: the uniform 2-spp initial
image, the α image PMC-IP computes from it (|P|·α: 1 is a uniform share, log scale; from the
variance image over each pixel's filter support), PMC-IP after two iterations (2 + 4 + 4, its
samples pooled through the film: the experiment's `pmc_ip`) and uniform 10 spp. Bottom: the
variance of each final image's pixels (both from their samples through the film's variance
estimator), on one log scale."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

from harness import paths, plots, renders  # noqa: E402

from .images import channels, figure_run, rgb, shown  # noqa: E402

CONFIG = paths.CONFIGS / "pmc" / "tab1_buddha.json"


def luminance_variance(exr: Path) -> np.ndarray:
    r, g, b = channels(exr, ["variance.R", "variance.G", "variance.B"])
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def write(profile_name: str) -> list[Path]:
    run = figure_run(CONFIG, profile_name, "pmc", "fig04")
    exp, profile, suffix, folder = run.exp, run.profile, run.suffix, run.folder
    runs = {"initial": ("uniform", 2), "alpha": ("pmc_ip", 6), "pmc_ip": ("pmc_ip", 10),
            "uniform": ("uniform", 10)}
    files = {}
    renders.check_technique(exp, profile, exp.techniques["pmc_ip"])  # assets present?
    for name, (technique, spp) in runs.items():
        files[name] = folder / f"{name}.exr"
        renders.render_technique(exp, profile, exp.techniques[technique], files[name], seed=0,
                                 spp=spp, threads=2)
    scale = float(np.percentile(rgb(files["uniform"]), 99))

    def display(exr: Path) -> np.ndarray:
        # Mitchell's negative lobes can leave a pixel slightly negative: black here.
        return shown(rgb(exr), scale)

    fig, axes = plt.subplots(2, 4, figsize=(12, 9.5))
    axes[0, 0].imshow(display(files["initial"]))
    axes[0, 0].set_title("initial image, 2 spp")
    (alpha,) = channels(files["alpha"], ["pmc.alpha"])
    im = axes[0, 1].imshow(alpha, cmap="magma", norm=LogNorm(vmin=max(alpha.min(), 1e-3),
                                                              vmax=max(alpha.max(), 1e-2)))
    axes[0, 1].set_title("α from it (|P|·α)")
    fig.colorbar(im, ax=axes[0, 1], fraction=0.046)
    axes[0, 2].imshow(display(files["pmc_ip"]))
    axes[0, 2].set_title("PMC-IP, 2 + 4 + 4")
    axes[0, 3].imshow(display(files["uniform"]))
    axes[0, 3].set_title("uniform, 10 spp")
    variances = [luminance_variance(files[n]) for n in ("pmc_ip", "uniform")]
    positive = np.concatenate([v[v > 0] for v in variances])
    norm = LogNorm(vmin=float(np.percentile(positive, 1)), vmax=float(positive.max()))
    for ax, variance, title in zip(axes[1, 2:], variances, ("PMC-IP", "uniform")):
        im = ax.imshow(np.maximum(variance, norm.vmin), cmap="viridis", norm=norm)
        ax.set_title(f"{title}: pixel variance")
    fig.colorbar(im, ax=list(axes[1, 2:]), fraction=0.046, label="luminance variance")
    for ax in axes.ravel():
        ax.set_xticks([])
        ax.set_yticks([])
    for ax in axes[1, :2]:
        ax.axis("off")
    out = paths.PLOTS / "pmc" / f"fig04_buddha{suffix}.png"
    plots.save(fig, out)
    return [out]
