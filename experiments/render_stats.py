"""What `make bench` and `make rr-study` read from a render's EXR: its numeric metadata and
the mean variance of its pixel means (from the renderer's own variance channels), the error
of an unbiased render and the denominator of efficiency 1/(variance × time)."""
from pathlib import Path

import numpy as np

from harness.exr import read_exr


# The developers' guide's raw Embree figures for this machine kind (rtcIntersect1, 2 threads,
# the 202k-triangle dragon), in Mrays/s per kind of ray: issue 19's yardstick (goal ≥ 75 %).
GUIDE_RAW_EMBREE = {"camera": 35.0, "extension": 16.0, "shadow": 18.0}


def guide_seconds(values: dict[str, float]) -> float:
    """The seconds raw Embree at the guide's figures would take for a render's rays."""
    return sum(values[f"renderer.rays.{kind}"] / rate
               for kind, rate in GUIDE_RAW_EMBREE.items()) * 1e-6


def read_render(exr: Path) -> tuple[dict[str, float], float]:
    """The render's numeric renderer.* metadata plus "samples" (spp × pixels), and the mean over
    pixels and channels of the variance of the pixel mean."""
    spec, pixels = read_exr(exr)
    names = list(spec.channelnames)
    variance = np.mean([pixels[..., names.index(f"variance.{c}")] for c in "RGB"])
    values = {a.name: a.value for a in spec.extra_attribs
              if a.name.startswith("renderer.") and isinstance(a.value, (int, float))}
    values["samples"] = values["renderer.spp"] * spec.width * spec.height
    return values, float(variance)
