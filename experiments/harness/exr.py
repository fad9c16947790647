"""Reading the renderer's EXR files (OpenImageIO): one reader for the harness and its tools."""
from pathlib import Path

import numpy as np
import OpenImageIO as oiio


def read_exr(file: Path, channels: int | None = None) -> tuple[oiio.ImageSpec, np.ndarray]:
    """The file's spec (channel names, metadata) and its pixels as float32, height × width ×
    channels; only the first `channels` channels when given."""
    image = oiio.ImageInput.open(str(file))
    if image is None:
        raise FileNotFoundError(f"cannot read {file}: {oiio.geterror()}")
    spec = image.spec()
    count = spec.nchannels if channels is None else channels
    pixels = image.read_image(0, 0, 0, count, "float")
    image.close()
    return spec, np.asarray(pixels).reshape(spec.height, spec.width, count)
