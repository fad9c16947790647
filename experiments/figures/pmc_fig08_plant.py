"""PMC fig. 8: soft shadows and glossy surfaces on the plant (configs/experiments/pmc/
tab2_plant.json, its techniques at equal draws, at its profile's resolution). Top: PMC-HI, MIS
and the reference; bottom: the soft shadows beside the pot, zoomed (PMC-HI left, MIS right, as
the paper). Images are seed 0's; each zoom's title gives its RMSE against the reference's, the
mean over the profile's seeds."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness import paths, plots, references, renders  # noqa: E402

from .images import crop, figure_run, rgb, shown  # noqa: E402

CONFIG = paths.CONFIGS / "pmc" / "tab2_plant.json"
# The shadows of the pot and the leaves on the table, as fractions: x, y, width, height.
CROP = (0.48, 0.60, 0.36, 0.36)
TECHNIQUES = [("pmc_hi_27", "PMC-HI"), ("mis_27", "MIS")]


def write(profile_name: str) -> list[Path]:
    run = figure_run(CONFIG, profile_name, "pmc", "fig08")
    renders.check_technique(run.exp, run.profile, run.exp.techniques["mis_27"])
    images: dict[str, np.ndarray] = {}
    zooms: dict[str, list[np.ndarray]] = {}
    for name, _ in TECHNIQUES:
        zooms[name] = []
        for seed in range(run.profile.seeds):
            exr = run.folder / f"{name}_seed{seed}.exr"
            renders.render_technique(run.exp, run.profile, run.exp.techniques[name], exr,
                                     seed=seed, spp=run.profile.spp[0], threads=2)
            pixels = rgb(exr)
            images.setdefault(name, pixels)
            zooms[name].append(crop(pixels, CROP))
    reference_file = references.current_file(run.exp, run.profile)
    full_reference = rgb(reference_file) if reference_file else None
    reference = crop(full_reference, CROP) if full_reference is not None else None
    scale = float(np.percentile(images["mis_27"], 99))

    fig, axes = plt.subplots(2, 3, figsize=(13, 6.4),
                             gridspec_kw={"height_ratios": [1.0, 1.1]})
    for ax, (name, label) in zip(axes[0], TECHNIQUES):
        ax.imshow(shown(images[name], scale))
        ax.set_title(f"{label}, 27 draws per pixel", fontsize=10)
    for ax, (name, label) in zip(axes[1], TECHNIQUES):
        title = f"{label}, zoomed"
        if reference is not None:
            assert zooms[name][0].shape == reference.shape
            rmse = [np.sqrt(np.mean((z - reference) ** 2)) for z in zooms[name]]
            title += f": RMSE {np.mean(rmse):.4f}\n(mean of {len(rmse)} seeds)"
        ax.imshow(shown(zooms[name][0], scale), interpolation="nearest")
        ax.set_title(title, fontsize=10)
    if full_reference is not None and reference is not None:
        axes[0, 2].imshow(shown(full_reference, scale))
        axes[0, 2].set_title("reference", fontsize=10)
        axes[1, 2].imshow(shown(reference, scale), interpolation="nearest")
        axes[1, 2].set_title("reference, zoomed", fontsize=10)
    else:
        axes[0, 2].axis("off")
        axes[1, 2].axis("off")
    for ax in axes.ravel():
        ax.set_xticks([])
        ax.set_yticks([])
    out = paths.PLOTS / "pmc" / f"fig08_plant{run.suffix}.png"
    plots.save(fig, out)
    return [out]
