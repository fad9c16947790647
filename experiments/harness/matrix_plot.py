"""The cross-paper matrix's heat map (results/plots/matrix/heatmap.png): one panel per light
transport, scenes down, techniques across, each cell coloured by log₂ of its gain at equal
time (matrix_tables.Cell) and labelled with the gain and its 95 % interval (†: its renders
took another time than the default's); refused cells hatched, cells of the other transport
left out."""
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import colors  # noqa: E402

from . import paths  # noqa: E402
from .matrix_configs import DEFAULT, PAPER  # noqa: E402
from .matrix_tables import TRANSPORTS, Row, columns, groups  # noqa: E402
from .plots import save  # noqa: E402

LIMIT = 4.0  # log₂ gain at which the colour saturates (×16)
NORM = colors.Normalize(-LIMIT, LIMIT)
CMAP = plt.get_cmap("RdBu")


def cell_colour(gain: float) -> tuple[str, bool]:
    """A gain's colour (hex) on the heat map's scale, and whether text on it should be white."""
    value = max(-LIMIT, min(LIMIT, math.log2(gain)))
    return colors.to_hex(CMAP(NORM(value))), abs(value) > 0.6 * LIMIT


def heatmap(all_rows: list[Row], out: Path) -> None:
    panels = list(groups(all_rows))
    heights = [len(group) + 2 for _, group in panels]
    width = max(len(columns(group)) for _, group in panels)
    fig, axes = plt.subplots(len(panels), 1, figsize=(2.0 + 1.25 * width, 0.42 * sum(heights)),
                             gridspec_kw={"height_ratios": heights}, squeeze=False)
    for ax, (transport, group) in zip(axes[:, 0], panels):
        names = columns(group)
        for y, r in enumerate(group):
            for x, name in enumerate(names):
                c = r.cells.get(name)
                if c is None:
                    continue
                if c.refusal is not None:
                    ax.add_patch(plt.Rectangle((x - .5, y - .5), 1, 1, facecolor="0.85",
                                               hatch="//", edgecolor="0.6", linewidth=0))
                    ax.text(x, y, "refused", ha="center", va="center", fontsize=6, color="0.3")
                    continue
                if name == DEFAULT:
                    gain, label = 1.0, f"1\n{r.budget:.3g} s"
                elif c.gain is None:
                    continue
                else:
                    lo, hi = c.gain.ci95
                    gain, label = c.gain.value, f"×{c.gain.value:.2g}\n[{lo:.2g}, {hi:.2g}]"
                    if c.unequal_time:
                        label += f"\n† ×{c.time_ratio:.2g} time"
                colour, dark = cell_colour(gain)
                ax.add_patch(plt.Rectangle((x - .5, y - .5), 1, 1, facecolor=colour))
                ax.text(x, y, label, ha="center", va="center", fontsize=6,
                        color="white" if dark else "black")
        ax.set_xlim(-.5, len(names) - .5)
        ax.set_ylim(len(group) - .5, -.5)
        ax.set_xticks(range(len(names)), names, rotation=30, ha="right", fontsize=7)
        ax.set_yticks(range(len(group)), [r.scene.removesuffix(".json") for r in group],
                      fontsize=7)
        ax.set_title(f"{TRANSPORTS[transport]}: relMSE gain over the scene's default at equal "
                     "time (> 1: better; 95 % interval over seeds; † not at equal time)", fontsize=8)
        ax.tick_params(length=0)
    bar = fig.colorbar(plt.cm.ScalarMappable(norm=NORM, cmap=CMAP), ax=axes[:, 0],
                       fraction=0.02, pad=0.01)
    bar.set_label("log₂ gain", fontsize=7)
    save(fig, out)


def write_all(all_rows: list[Row], profile_name: str) -> list[Path]:
    if not all_rows:
        return []
    out = paths.PLOTS / PAPER / f"heatmap{paths.suffix(profile_name)}.png"
    heatmap(all_rows, out)
    return [out]
