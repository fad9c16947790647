"""PMC fig. 5: the Cornell box's caustic (configs/experiments/pmc/tab1_box.json, at its
profile's resolution, seed 0), cropped. Row 1: uniform path tracing at 16, 32, 64 and 128 spp;
row 2: PMC-IP in the figure's schedule (iterations of 4 spp after a 4-spp initial image; "64
iterations, each averaging 4 spp") after 4, 8, 16 and 32 iterations, the same sample counts;
row 3: uniform at 256 spp against PMC-IP after 16 iterations (64 spp), and the reference. Each
crop's RMSE against the reference's crop is in its title. PMC-IP's estimates at iteration k do
not depend on how many follow, so each is a render stopped there."""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from harness import paths, plots, renders  # noqa: E402

from .images import crop, figure_run, rgb, shown  # noqa: E402

CONFIG = paths.CONFIGS / "pmc" / "tab1_box.json"
# The caustic under the glass sphere, as fractions of the image: x, y, width, height.
CROP = (0.40, 0.70, 0.45, 0.30)
UNIFORM_SPP = [16, 32, 64, 128, 256]
ITERATIONS = [4, 8, 16, 32]


def write(profile_name: str) -> list[Path]:
    run = figure_run(CONFIG, profile_name, "pmc", "fig05")
    uniform = run.exp.techniques["uniform"].integrator
    adaptive = dict(run.exp.techniques["pmc_ip"].integrator, initial_spp=4, iteration_spp=4)
    renders.check_scene(run.exp, run.profile, adaptive)
    files: dict[str, Path] = {}
    for spp in UNIFORM_SPP:
        files[f"uniform {spp}"] = run.folder / f"uniform_{spp}spp.exr"
        renders.render(run.exp, run.profile, uniform, files[f"uniform {spp}"], seed=0, spp=spp,
                       threads=2)
    for k in ITERATIONS:
        files[f"pmc {k}"] = run.folder / f"pmc_ip_{k}_iterations.exr"
        renders.render(run.exp, run.profile, adaptive, files[f"pmc {k}"], seed=0,
                       spp=4 + 4 * (k - 1), threads=2)
    reference_file = paths.REFERENCE / "pmc" / f"tab1_box.{profile_name}.exr"
    reference = crop(rgb(reference_file), CROP) if reference_file.exists() else None
    scale = float(np.percentile(reference if reference is not None
                                else crop(rgb(files["uniform 256"]), CROP), 99))

    def panel(ax, pixels: np.ndarray, title: str) -> None:
        if reference is not None and pixels is not reference:
            title += f"\nRMSE {np.sqrt(np.mean((pixels - reference) ** 2)):.3f}"
        ax.imshow(shown(pixels, scale), interpolation="nearest")
        ax.set_title(title, fontsize=9)

    fig, axes = plt.subplots(3, 4, figsize=(12, 8.2))
    for ax, spp in zip(axes[0], UNIFORM_SPP):
        panel(ax, crop(rgb(files[f"uniform {spp}"]), CROP), f"path tracing, {spp} spp")
    for ax, k in zip(axes[1], ITERATIONS):
        panel(ax, crop(rgb(files[f"pmc {k}"]), CROP), f"PMC-IP, {k} iterations ({4 * k} spp)")
    panel(axes[2, 0], crop(rgb(files["uniform 256"]), CROP), "path tracing, 256 spp")
    panel(axes[2, 1], crop(rgb(files["pmc 16"]), CROP), "PMC-IP, 16 iterations (64 spp)")
    if reference is not None:
        panel(axes[2, 2], reference, "reference")
    for ax in axes.ravel():
        ax.set_xticks([])
        ax.set_yticks([])
    axes[2, 3].axis("off")
    if reference is None:
        axes[2, 2].axis("off")
    out = paths.PLOTS / "pmc" / f"fig05_caustic{run.suffix}.png"
    plots.save(fig, out)
    return [out]
