#!/usr/bin/python3
"""Writes the fuzz targets' seed corpus (tests/fuzz/corpus/<target>/): small, valid inputs of
each format, so the fuzzers start from files that reach deep into each reader. Committed with
its output; re-run only to change the seeds. Scene seeds are written by hand (corpus/scene)."""
import struct
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

CORPUS = Path(__file__).resolve().parent / "corpus"

# A tetrahedron around the origin, facing outwards.
VERTICES = [(0.0, 0.6, 0.0), (-0.5, -0.3, 0.4), (0.5, -0.3, 0.4), (0.0, -0.3, -0.5)]
FACES = [(0, 1, 2), (0, 2, 3), (0, 3, 1), (1, 3, 2)]


def ply_ascii() -> bytes:
    head = ["ply", "format ascii 1.0", f"element vertex {len(VERTICES)}", "property float x",
            "property float y", "property float z", f"element face {len(FACES)}",
            "property list uchar int vertex_indices", "end_header"]
    body = [" ".join(map(str, v)) for v in VERTICES] + [f"3 {a} {b} {c}" for a, b, c in FACES]
    return ("\n".join(head + body) + "\n").encode()


def ply_binary_with_normals() -> bytes:
    head = ["ply", "format binary_little_endian 1.0", f"element vertex {len(VERTICES)}",
            "property float x", "property float y", "property float z", "property float nx",
            "property float ny", "property float nz", f"element face {len(FACES)}",
            "property list uchar int vertex_indices", "end_header"]
    data = b""
    for v in VERTICES:
        n = np.asarray(v) / np.linalg.norm(v)
        data += struct.pack("<6f", *v, *n)
    for f in FACES:
        data += struct.pack("<B3i", 3, *f)
    return ("\n".join(head) + "\n").encode() + data


def obj() -> bytes:
    lines = [f"v {x} {y} {z}" for x, y, z in VERTICES] + ["vn 0 1 0"]
    lines += [f"f {a + 1}//1 {b + 1}//1 {c + 1}//1" for a, b, c in FACES]
    return ("\n".join(lines) + "\n").encode()


def obj_quad_negative_indices() -> bytes:
    return b"v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n" \
           b"f -4/-4 -3/-3 -2/-2 -1/-1\n"


def write_image(file: Path, width: int, height: int, channels: int, fmt: str) -> None:
    rng = np.random.default_rng(1)
    pixels = rng.uniform(0.0, 4.0, (height, width, channels)).astype(np.float32)
    pixels[0, 0] = 1e4  # a sun texel
    out = oiio.ImageOutput.create(str(file))
    spec = oiio.ImageSpec(width, height, channels, fmt)
    if channels == 1:
        spec.channelnames = ("Y",)
    if file.suffix == ".exr":
        spec.attribute("compression", "zip")
    out.open(str(file), spec)
    out.write_image(pixels)
    out.close()


def main() -> None:
    for target in ("ply", "obj", "exr", "hdr"):
        (CORPUS / target).mkdir(parents=True, exist_ok=True)
    (CORPUS / "ply" / "tetrahedron_ascii.ply").write_bytes(ply_ascii())
    (CORPUS / "ply" / "tetrahedron_binary_normals.ply").write_bytes(ply_binary_with_normals())
    (CORPUS / "obj" / "tetrahedron.obj").write_bytes(obj())
    (CORPUS / "obj" / "quad_negative_indices.obj").write_bytes(obj_quad_negative_indices())
    write_image(CORPUS / "exr" / "rgb_float_8x4.exr", 8, 4, 3, "float")
    write_image(CORPUS / "exr" / "y_half_8x4.exr", 8, 4, 1, "half")
    write_image(CORPUS / "hdr" / "flat_4x2.hdr", 4, 2, 3, "float")     # too narrow for RLE
    write_image(CORPUS / "hdr" / "rle_16x8.hdr", 16, 8, 3, "float")   # run-length encoded rows


if __name__ == "__main__":
    main()
