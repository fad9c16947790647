"""What the figure scripts that render share: the experiment and profile a figure renders at,
with a folder for its renders, and the channels of the EXRs they read back."""
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

from harness import config, paths
from harness.config import Experiment, Profile


@dataclass(frozen=True)
class FigureRun:
    exp: Experiment
    profile: Profile
    suffix: str  # of the outputs' names (paths.suffix)
    folder: Path  # results/renders/<paper>/<figure><suffix>, created


def figure_run(config_file: Path, profile_name: str, paper: str, figure: str) -> FigureRun:
    exp = config.load(config_file)
    suffix = paths.suffix(profile_name)
    folder = paths.RENDERS / paper / f"{figure}{suffix}"
    folder.mkdir(parents=True, exist_ok=True)
    return FigureRun(exp, exp.profiles[profile_name], suffix, folder)


def channels(exr: Path, names: list[str]) -> list[np.ndarray]:
    image = oiio.ImageBuf(str(exr))
    pixels = image.get_pixels(oiio.FLOAT)
    return [pixels[:, :, image.spec().channelindex(n)] for n in names]


def rgb(exr: Path) -> np.ndarray:
    return np.stack(channels(exr, ["R", "G", "B"]), axis=-1)


def shown(pixels: np.ndarray, scale: float | None = None) -> np.ndarray:
    """For display: divided by `scale` (default the 99th percentile), negatives black, gamma
    2.2, clipped."""
    if scale is None:
        scale = float(np.percentile(pixels, 99))
    return np.clip(np.clip(pixels / max(scale, 1e-6), 0, None) ** (1 / 2.2), 0, 1)


def crop(pixels: np.ndarray, window: tuple[float, float, float, float]) -> np.ndarray:
    """The window (x, y, width, height, as fractions of the image) of an image."""
    h, w = pixels.shape[:2]
    x0, y0 = int(window[0] * w), int(window[1] * h)
    return pixels[y0:y0 + max(1, int(window[3] * h)), x0:x0 + max(1, int(window[2] * w))]
