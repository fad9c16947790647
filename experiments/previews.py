#!/usr/bin/python3
"""Small renders of every scene and a labelled contact sheet (`make previews`).

  previews.py [SCENE.json ...] [--size PIXELS] [--spp N]

Renders each scene (default: every configs/scenes/*.json) with its own integrator at a preview
size (the longer side --size pixels, the scene's aspect ratio kept) and --spp samples per
pixel, into results/previews/<scene>.png (the renderer's sRGB preview at exposure 0; the EXR
beside it), then lays them out in results/previews/contact_sheet.png. A scene whose asset is
absent gets a labelled blank tile (unless REQUIRE_ASSETS=1); a scene that fails to load or
render is reported and makes the exit status 1 once the sheet is written."""
import argparse
import math
import re
import subprocess
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))

from harness import paths, renders  # noqa: E402
from harness.errors import HarnessFailure, SceneRejected  # noqa: E402

OUT = paths.RESULTS / "previews"
COLUMNS = 5
TILE_INCHES = 2.0


def natural_key(path: Path) -> list[int | str]:
    """fig4 before fig10."""
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", path.stem)]


def preview_resolution(width: int, height: int, size: int) -> tuple[int, int]:
    scale = size / max(width, height)
    return max(1, round(width * scale)), max(1, round(height * scale))


def render(scene: Path, resolution: tuple[int, int], spp: int) -> Path:
    """Renders the scene; returns the PNG preview's path."""
    exr = OUT / f"{scene.stem}.exr"
    subprocess.run([str(paths.renderer_binary()), "render", str(scene), "--out", str(exr),
                    "--resolution", f"{resolution[0]}x{resolution[1]}", "--spp", str(spp)],
                   check=True, capture_output=True, text=True)
    return exr.with_suffix(".png")


def preview(scene: Path, size: int,
            spp: int) -> tuple[np.ndarray | None, str, str | None]:
    """One scene: (tile image or None, label, failure message or None)."""
    try:
        check = renders.check([scene])
    except SceneRejected as e:
        if e.skippable:
            return None, f"{scene.stem}\n(asset absent)", None
        return None, f"{scene.stem}\n(does not load)", e.message
    except HarnessFailure as e:
        return None, f"{scene.stem}\n(does not load)", str(e)
    resolution = preview_resolution(*check.resolution, size)
    try:
        png = render(scene, resolution, spp)
    except subprocess.CalledProcessError as e:
        message = (e.stderr or "").strip().splitlines()
        return None, f"{scene.stem}\n(render failed)", message[-1] if message else str(e)
    return mpimg.imread(png), f"{scene.stem}\n{check.integrator}", None


def contact_sheet(tiles: list[tuple[np.ndarray | None, str]], spp: int, size: int,
                  out: Path) -> None:
    rows = math.ceil(len(tiles) / COLUMNS)
    fig, axes = plt.subplots(rows, COLUMNS, figsize=(COLUMNS * TILE_INCHES,
                                                     rows * (TILE_INCHES + 0.35)),
                             squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, (image, label) in zip(axes.flat, tiles):
        if image is not None:
            ax.imshow(image, interpolation="nearest")
        ax.set_title(label, fontsize=6.5, pad=3)
    fig.suptitle(f"Scenes in configs/scenes/: previews, longer side {size} px, {spp} spp "
                 f"(make previews)", fontsize=9)
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    fig.savefig(out, dpi=110, facecolor="white")
    plt.close(fig)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scenes", nargs="*", type=Path)
    parser.add_argument("--size", type=int, default=128, help="longer side in pixels")
    parser.add_argument("--spp", type=int, default=256, help="samples per pixel")
    args = parser.parse_args()
    scenes = args.scenes or sorted(paths.SCENES.glob("*.json"), key=natural_key)
    OUT.mkdir(parents=True, exist_ok=True)

    tiles, failures, start = [], [], time.monotonic()
    for i, scene in enumerate(scenes, 1):
        t0 = time.monotonic()
        image, label, failure = preview(scene, args.size, args.spp)
        tiles.append((image, label))
        status = failure or ("skipped: an asset is absent" if image is None else "done")
        print(f"[{i}/{len(scenes)}] {scene.stem}: {status} ({time.monotonic() - t0:.1f} s)",
              flush=True)
        if failure:
            failures.append(scene.stem)
    sheet = OUT / "contact_sheet.png"
    contact_sheet(tiles, args.spp, args.size, sheet)
    print(f"wrote {paths.relative(sheet)} ({len(scenes)} scenes, "
          f"{time.monotonic() - start:.0f} s)")
    if failures:
        print(f"failed: {', '.join(failures)}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
