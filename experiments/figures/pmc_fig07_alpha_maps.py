"""PMC fig. 7: how PMC-HI's mixture weights vary over the checker floor
(configs/experiments/pmc/tab2_checks.json, at its profile's resolution, seed 0). One estimate
per pixel, as the paper's: two iterations of N = 2m = 8 (m = 4: the BSDF, two lights, the
cone), 16 samples, and the weights α^(2) the estimate would use next, from the estimator's
`alpha_maps` channels. From left to right, as the paper: the left (large) light's weight, the
right (small) light's, the BSDF's and the cone's; bright is high weight. The rendered image
is beside them. Also writes the share of floor pixels where each component has the largest
weight (fig07_alpha_maps*.json), which the analysis cites."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness import paths, plots, provenance, renders  # noqa: E402

from .images import channels, figure_run, rgb, shown  # noqa: E402

CONFIG = paths.CONFIGS / "pmc" / "tab2_checks.json"
# The scene's lights in order: light 0 is the large quad on the left, light 1 the small one.
COMPONENTS = [("pmc_hi.alpha.light0", "α_L1, left (large) light"),
              ("pmc_hi.alpha.light1", "α_L2, right (small) light"),
              ("pmc_hi.alpha.bsdf", "α_BRDF"), ("pmc_hi.alpha.cone", "α_cone")]


def write(profile_name: str) -> list[Path]:
    run = figure_run(CONFIG, profile_name, "pmc", "fig07")
    integrator = {"type": "direct",
                  "estimator": {"type": "pmc_hi", "samples": 8, "iterations": 2,
                                "alpha_maps": True}}
    renders.check_scene(run.exp, run.profile, integrator)
    exr = run.folder / "pmc_hi_16.exr"
    renders.render(run.exp, run.profile, integrator, exr, seed=0, spp=1, threads=2)

    alphas = channels(exr, [name for name, _ in COMPONENTS])
    floor = np.sum(alphas, axis=0) > 0  # pixels whose first hit made an estimate
    winner = np.argmax(np.stack(alphas), axis=0)
    shares = {name: float(np.mean(winner[floor] == k)) for k, (name, _) in enumerate(COMPONENTS)}
    means = {name: float(np.mean(a[floor])) for (name, _), a in zip(COMPONENTS, alphas)}

    fig, axes = plt.subplots(1, 5, figsize=(17, 3.9))
    axes[0].imshow(shown(rgb(exr)))
    axes[0].set_title("PMC-HI, 2 × 8 samples")
    for ax, (name, title), alpha in zip(axes[1:], COMPONENTS, alphas):
        im = ax.imshow(alpha, cmap="gray", vmin=0, vmax=1)
        ax.set_title(f"{title}\nlargest at {100 * shares[name]:.0f} % of the floor")
    fig.colorbar(im, ax=list(axes[1:]), fraction=0.015, label="α after two iterations")
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    out = paths.PLOTS / "pmc" / f"fig07_alpha_maps{run.suffix}.png"
    plots.save(fig, out)
    summary = paths.PLOTS / "pmc" / f"fig07_alpha_maps{run.suffix}.json"
    provenance.write_json_atomically(summary, {"pixels_with_an_estimate": int(floor.sum()),
                                               "largest_share": shares, "mean_alpha": means})
    return [out, summary]
