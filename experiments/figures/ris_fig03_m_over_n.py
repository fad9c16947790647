"""RIS fig. 3's lower image: the optimal M/N per pixel (eq. 3, within the time of 20 light
samples) on the dragon, from the `ris` integrator's optimal mode (its channel ris.mOverN),
beside the image it renders, at the resolution of the profile of
configs/experiments/ris/fig03_dragon_one_ray.json. Green: larger M (resampling pays), red:
larger N (visibility dominates), on a log scale."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

from harness import paths, plots, renders  # noqa: E402

from .images import channels, figure_run, rgb, shown  # noqa: E402

CONFIG = paths.CONFIGS / "ris" / "fig03_dragon_one_ray.json"


def write(profile_name: str) -> list[Path]:
    run = figure_run(CONFIG, profile_name, "ris", "fig03_m_over_n")
    exr = run.folder / "ris_optimal.exr"
    technique = run.exp.techniques["ris_optimal"]
    # SceneRejected when an asset is absent
    renders.check_technique(run.exp, run.profile, technique)
    renders.render_technique(run.exp, run.profile, technique, exr, seed=0, spp=1, threads=2)
    (ratio,) = channels(exr, ["ris.mOverN"])

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    left.imshow(shown(rgb(exr)))
    left.set_title("optimal RIS, 1 primary ray per pixel")
    masked = np.ma.masked_less_equal(ratio, 0)
    lo, hi = max(float(masked.min()), 1e-3), max(float(masked.max()), 1e-2)
    im = right.imshow(masked, cmap="RdYlGn", norm=LogNorm(vmin=lo, vmax=max(hi, lo * 10)))
    right.set_title("optimal M/N per pixel (eq. 3)")
    right.set_facecolor("0.6")
    fig.colorbar(im, ax=right, label="M / N (green: more candidates, red: more samples; grey: no hit)")
    for ax in (left, right):
        ax.set_xticks([])
        ax.set_yticks([])
    out = paths.PLOTS / "ris" / f"fig03_m_over_n{run.suffix}.png"
    plots.save(fig, out)
    return [out]
