#!/usr/bin/python3
"""Writes configs/scenes/textures/twostage_fig11_roughness.exr, the roughness map of the
stand-in for two-stage fig. 11 ('a scene in which the specular roughness parameter is
controlled by a texture map'). Our own procedural data: wavy stripes whose Blinn roughness
runs log-uniformly from 0.004 (exponent 250, near-mirror) to 0.3 (exponent 3.3, broad), so
neighbouring points have very different BRDF shapes. 128 × 64, grey RGB (a float parameter
reads the luminance), half floats, ZIP. Deterministic.
Run: /usr/bin/python3 configs/scenes/generators/twostage_fig11_roughness.py"""
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

WIDTH, HEIGHT = 128, 64
ROUGHNESS = (0.004, 0.3)
STRIPES = 5  # across u
WAVES = 2    # of the stripes' wobble along v
OUT = Path(__file__).resolve().parents[1] / "textures" / "twostage_fig11_roughness.exr"


def roughness():
    u = (np.arange(WIDTH) + 0.5) / WIDTH
    v = 1 - (np.arange(HEIGHT) + 0.5) / HEIGHT  # row 0 is the top, where v = 1
    uu, vv = np.meshgrid(u, v)
    phase = STRIPES * uu + 0.3 * np.sin(2 * np.pi * WAVES * vv)
    t = 0.5 + 0.5 * np.sin(2 * np.pi * phase)  # in [0, 1]
    lo, hi = np.log(ROUGHNESS)
    return np.exp(lo + t * (hi - lo))


def write(values):
    OUT.parent.mkdir(parents=True, exist_ok=True)
    spec = oiio.ImageSpec(WIDTH, HEIGHT, 3, "half")
    spec.attribute("compression", "zip")
    spec.attribute("ImageDescription", "Blinn roughness for configs/scenes/"
                   "twostage_fig11_varying_roughness.json; written by " + Path(__file__).name)
    out = oiio.ImageOutput.create(str(OUT))
    if out is None or not out.open(str(OUT), spec):
        raise SystemExit(f"cannot write {OUT}: {oiio.geterror()}")
    out.write_image(np.repeat(values[:, :, None], 3, axis=2).astype(np.float32))
    out.close()


if __name__ == "__main__":
    write(roughness())
    print(f"wrote {OUT}")
