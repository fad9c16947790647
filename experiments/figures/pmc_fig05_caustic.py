"""PMC fig. 5: the Cornell box's caustic (configs/experiments/pmc/tab1_box.json, at its profile's
resolution, through its pbrt-v1 film and sampling), cropped. Row 1: uniform path tracing at 16,
32, 64 and 128 spp; row 2: PMC-IP in the figure's schedule (iterations of 4 spp after a 4-spp
initial image; "64 iterations, each averaging 4 spp") after 4, 8, 16 and 32 iterations, the same
sample counts, our unbiased image (the iterations' estimates averaged); row 3: the same renders'
pooled image (all samples averaged: biased, the other reading of the paper's intermediate
results); row 4: uniform at 256 spp against PMC-IP after 16 iterations (64 spp), and the
reference. Images are seed 0's; each title gives the crop's RMSE against the reference's crop,
the mean over the profile's seeds (at most SEEDS). Each panel is a render of its own sample
count: under `pbrt_v1` sampling a pixel's stratified set spans the render's samples, so the
first k iterations of a longer render would be a different (less stratified) image."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness import paths, plots, references, renders  # noqa: E402

from .images import crop, figure_run, rgb, shown  # noqa: E402

CONFIG = paths.CONFIGS / "pmc" / "tab1_box.json"
# The caustic under the glass sphere, as fractions of the image: x, y, width, height.
CROP = (0.40, 0.70, 0.45, 0.30)
# Each seed renders 13 panels of up to 256 spp, so the figure takes fewer seeds than the
# table's 40 (quick); its RMSE titles illustrate, the table's intervals are the experiment's.
SEEDS = 10
ROWS = [
    [("uniform", 16), ("uniform", 32), ("uniform", 64), ("uniform", 128)],
    [("iterations", 4), ("iterations", 8), ("iterations", 16), ("iterations", 32)],
    [("pooled", 4), ("pooled", 8), ("pooled", 16), ("pooled", 32)],
    [("uniform", 256), ("iterations", 16), ("pooled", 16), ("reference", 0)],
]
TITLES = {"uniform": "path tracing, {} spp", "iterations": "PMC-IP, {} iterations",
          "pooled": "PMC-IP pooled (biased), {} it."}


def write(profile_name: str) -> list[Path]:
    run = figure_run(CONFIG, profile_name, "pmc", "fig05")
    uniform, pmc_ip = run.exp.techniques["uniform"], run.exp.techniques["pmc_ip"]
    adaptive = dict(pmc_ip.integrator, initial_spp=4, iteration_spp=4)
    # Each panel: the technique it renders, with that integrator (a variant of its own).
    panels_of = {"uniform": (uniform, uniform.integrator),
                 "iterations": (pmc_ip, dict(adaptive, image="iterations")),
                 "pooled": (pmc_ip, dict(adaptive, image="pooled"))}
    renders.check_technique(run.exp, run.profile, pmc_ip, adaptive)
    panels = sorted({p for row in ROWS for p in row if p[0] != "reference"})
    seeds = range(min(run.profile.seeds, SEEDS))
    crops: dict[tuple[str, int], list[np.ndarray]] = {p: [] for p in panels}
    for seed in seeds:
        for kind, n in panels:
            exr = run.folder / f"{kind}_{n}_seed{seed}.exr"
            spp = n if kind == "uniform" else 4 * n  # PMC-IP: 4 + 4 (n − 1)
            technique, integrator = panels_of[kind]
            renders.render_technique(run.exp, run.profile, technique, exr, seed=seed, spp=spp,
                                     threads=2, integrator=integrator)
            crops[(kind, n)].append(crop(rgb(exr), CROP))
    reference_file = references.current_file(run.exp, run.profile)
    reference = crop(rgb(reference_file), CROP) if reference_file else None
    scale = float(np.percentile(reference if reference is not None
                                else crops[("uniform", 256)][0], 99))

    fig, axes = plt.subplots(4, 4, figsize=(12, 10.6))
    for row_axes, row in zip(axes, ROWS):
        for ax, (kind, n) in zip(row_axes, row):
            ax.set_xticks([])
            ax.set_yticks([])
            if kind == "reference":
                if reference is None:
                    ax.axis("off")
                    continue
                ax.imshow(shown(reference, scale), interpolation="nearest")
                ax.set_title("reference", fontsize=9)
                continue
            title = TITLES[kind].format(n)
            if reference is not None:
                assert crops[(kind, n)][0].shape == reference.shape
                rmse = [np.sqrt(np.mean((c - reference) ** 2)) for c in crops[(kind, n)]]
                title += f"\nRMSE {np.mean(rmse):.3f} (mean of {len(rmse)} seeds)"
            ax.imshow(shown(crops[(kind, n)][0], scale), interpolation="nearest")
            ax.set_title(title, fontsize=9)
    out = paths.PLOTS / "pmc" / f"fig05_caustic{run.suffix}.png"
    plots.save(fig, out)
    return [out]
