#!/usr/bin/python3
"""`make stress`: every technique on every stress scene (configs/stress/*.json, scenes built to
break numerics: see configs/stress/generate.py), at the scene's resolution and STRESS_SPP
samples per pixel. Each render must have:

- no non-finite sample (the EXR's renderer.nonFiniteSamples is 0) and no negative pixel;
- a mean that agrees with a long reference of another unbiased technique estimating the same
  quantity, by a block z-test: the image is cut into a 4 × 4 grid of blocks, and for each block
  and channel z = (mean − reference mean) / √(variance of the mean + the reference's), from the
  renders' own variance channels; |z| must stay below the Šidák-corrected two-sided quantile for
  a family level of 0.01 over every z of the run.

The quantity is full light transport (reference: path_mis; for path_mis itself, path_mis with
light sampling only) or direct lighting (reference: direct with MIS; for it, direct with light
sampling only). Techniques that find emitters only by hitting them (path, direct_bsdf) cannot
see point or spot lights: on scenes with those their z-test is not applicable. A technique that
rejects a scene (exit status 2: e.g. two-stage sampling without a lat-long map, PMC-HI with a
point light) is listed as not applicable with the renderer's message.

Writes results/tables/stress.md and stress.json; exits 1 if any render fails a check.
Usage: stress.py [BUILD_DIR] (default build); STRESS_SPP (default 256), STRESS_ONLY (scene
names, comma-separated) from the environment."""
import json
import math
import os
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.stats import norm

from harness import jobs
from harness.exr import read_exr

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build")
RENDERER = BUILD / "bin" / "renderer"
STRESS = ROOT / "configs" / "stress"
TABLE = ROOT / "results" / "tables" / "stress.md"
SPP = int(os.environ.get("STRESS_SPP", "256"))
REFERENCE_FACTOR = 16  # a reference has this many times the samples
FAMILY_LEVEL = 0.01
GRID = 4  # blocks per side

RIS = {"type": "ris", "candidates": 4, "samples": 1}
TECHNIQUES: dict[str, tuple[dict, str]] = {
    "path": ({"type": "path"}, "full"),
    "path_mis": ({"type": "path_mis"}, "full"),
    "path_nee": ({"type": "path_mis", "estimator": {"type": "light"}}, "full"),
    "path_mis_pmc_hi": ({"type": "path_mis", "estimator": {"type": "pmc_hi"}}, "full"),
    "path_mis_ris": ({"type": "path_mis", "estimator": RIS}, "full"),
    "tais": ({"type": "tais"}, "full"),
    "pmc_ip": ({"type": "pmc_ip", "integrator": {"type": "path_mis"}}, "full"),
    "direct_mis": ({"type": "direct"}, "direct"),
    "direct_light": ({"type": "direct", "strategy": "light"}, "direct"),
    "direct_bsdf": ({"type": "direct", "strategy": "bsdf"}, "direct"),
    "direct_ris": ({"type": "direct", "estimator": RIS}, "direct"),
    "direct_pmc_hi": ({"type": "direct", "estimator": {"type": "pmc_hi"}}, "direct"),
    "direct_two_stage": ({"type": "direct", "estimator": {"type": "two_stage", "samples": 4}},
                         "direct"),
    "ris": ({"type": "ris", "mode": "fixed", "candidates": 4, "samples": 2}, "direct"),
    "two_stage": ({"type": "two_stage", "samples": 4}, "direct"),
}
# Per quantity: the reference technique, and the one path_mis or direct_mis itself is held to.
REFERENCES = {"full": ("path_mis", "path_nee"), "direct": ("direct_mis", "direct_light")}
HIT_ONLY = {"path", "direct_bsdf"}  # find emitters only by hitting them
DELTA_LIGHTS = {"point", "spot"}


@dataclass
class Render:
    status: int
    message: str = ""
    seconds: float = 0.0
    non_finite: float = 0.0
    pixels: np.ndarray | None = None  # height × width × 3
    variance: np.ndarray | None = None


@dataclass
class Row:
    scene: str
    technique: str
    result: str = ""
    seconds: float | None = None
    largest_z: float | None = None
    reference: str = ""
    problems: list[str] = field(default_factory=list)


def render(scene: Path, technique: str, spp: int, seed: int, out: Path) -> Render:
    integrator = TECHNIQUES[technique][0]
    proc = jobs.run_process([RENDERER, "render", scene, "--set",
                             f"/integrator={json.dumps(integrator)}", "--spp", spp, "--seed",
                             seed, "--threads", 1, "--no-preview", "--out", out])
    lines = proc.stderr.strip().splitlines()
    if proc.returncode != 0:
        return Render(proc.returncode, lines[-1] if lines else "(no message)")
    spec, data = read_exr(out)
    names = list(spec.channelnames)
    pick = lambda prefix: np.stack([data[..., names.index(prefix + c)] for c in "RGB"], -1)
    return Render(0, seconds=float(spec.getattribute("renderer.renderTime")),
                  non_finite=float(spec.getattribute("renderer.nonFiniteSamples")),
                  pixels=pick(""), variance=pick("variance."))


def block_z(image: Render, reference: Render) -> np.ndarray:
    """z of every block and channel (4 × 4 × 3)."""
    h, w, _ = image.pixels.shape
    rows = np.array_split(np.arange(h), GRID)
    cols = np.array_split(np.arange(w), GRID)
    z = np.zeros((GRID, GRID, 3))
    for i, r in enumerate(rows):
        for j, c in enumerate(cols):
            n = len(r) * len(c)
            block = np.ix_(r, c)
            diff = image.pixels[block].mean((0, 1)) - reference.pixels[block].mean((0, 1))
            var = (image.variance[block].sum((0, 1)) + reference.variance[block].sum((0, 1))) / n**2
            # Without variance (a constant sky, an emitter seen directly) only rounding may
            # differ: float sums of the same values in another order.
            scale = np.maximum(np.abs(image.pixels[block]).mean((0, 1)), 1e-30)
            same = np.abs(diff) <= 1e-5 * scale
            with np.errstate(divide="ignore", invalid="ignore"):
                z[i, j] = np.where(var > 0, diff / np.sqrt(var), np.where(same, 0, np.inf))
    return z


def has_delta_lights(scene: Path) -> bool:
    """Point or spot lights that emit (one of intensity 0 is invisible to every technique)."""
    lights = json.loads(scene.read_text()).get("lights", [])
    return any(light.get("type") in DELTA_LIGHTS and np.any(np.asarray(light["intensity"]) > 0)
               for light in lights)


def reference_for(technique: str) -> str:
    first, second = REFERENCES[TECHNIQUES[technique][1]]
    return second if technique == first else first


def run_scene_renders(scenes: list[Path], scratch: Path) -> dict[tuple[str, str, str], Render]:
    """Every (scene, technique) at SPP, and the references at REFERENCE_FACTOR × SPP."""
    work = [(s, t, "image", SPP, 1) for s in scenes for t in TECHNIQUES]
    work += [(s, r, "reference", SPP * REFERENCE_FACTOR, 1_000_003) for s in scenes
             for pair in REFERENCES.values() for r in pair]
    calls = [lambda s=s, t=t, kind=kind, spp=spp, seed=seed:
             render(s, t, spp, seed, scratch / f"{s.stem}.{t}.{kind}.exr")
             for s, t, kind, spp, seed in work]
    costs = [spp for _, _, _, spp, _ in work]
    results = jobs.run_parallel("stress", calls, costs, jobs.default_jobs())
    return {(s.stem, t, kind): r for (s, t, kind, _, _), r in zip(work, results)}


@dataclass
class Verdicts:
    rows: list[Row]
    threshold: float  # on |z|
    tests: int  # z values compared


def judge(scenes: list[Path], renders: dict[tuple[str, str, str], Render]) -> Verdicts:
    rows, z_values = [], {}
    for scene in scenes:
        delta = has_delta_lights(scene)
        for technique in TECHNIQUES:
            row = Row(scene.stem, technique)
            image = renders[(scene.stem, technique, "image")]
            rows.append(row)
            if image.status == 2:
                row.result = f"n/a: {image.message.removeprefix('error: ')}"
                continue
            if image.status != 0:
                row.problems.append(f"exit status {image.status}: {image.message}")
                continue
            row.seconds = image.seconds
            if image.non_finite > 0:
                row.problems.append(f"{image.non_finite:.0f} non-finite samples")
            if not np.all(np.isfinite(image.pixels)) or np.any(image.pixels < 0):
                row.problems.append("negative or non-finite pixels")
            if technique in HIT_ONLY and delta:
                row.reference = "n/a (point or spot lights)"
                continue
            name = reference_for(technique)
            reference = renders[(scene.stem, name, "reference")]
            if reference.status != 0:
                row.problems.append(f"reference {name} failed: {reference.message}")
                continue
            row.reference = name
            z_values[(scene.stem, technique)] = block_z(image, reference)
    tests = sum(z.size for z in z_values.values())
    threshold = norm.ppf(1 - (1 - (1 - FAMILY_LEVEL) ** (1 / max(tests, 1))) / 2)
    for row in rows:
        z = z_values.get((row.scene, row.technique))
        if z is not None:
            row.largest_z = float(np.max(np.abs(z)))
            if not row.largest_z < threshold:
                row.problems.append(f"|z| {row.largest_z:.2f} ≥ {threshold:.2f}")
        if not row.result:
            row.result = "pass" if not row.problems else "FAIL: " + "; ".join(row.problems)
    return Verdicts(rows, threshold, tests)


def write_table(verdicts: Verdicts, scenes: list[Path]) -> None:
    lines = [
        "# Stress scenes × techniques",
        "",
        f"`make stress` (experiments/stress.py): {len(scenes)} scenes of `configs/stress/`, "
        f"{SPP} spp, references {REFERENCE_FACTOR * SPP} spp, one thread per render. A render "
        f"passes with no non-finite sample, no negative pixel, and every block z (4 × 4 blocks × "
        f"3 channels, {verdicts.tests} in all) below {verdicts.threshold:.2f}, the Šidák-corrected "
        f"quantile for a family level of {FAMILY_LEVEL}. Time is the render loop's.",
        "",
        "| scene | technique | result | time (s) | largest \\|z\\| | reference |",
        "| --- | --- | --- | ---: | ---: | --- |",
    ]
    for r in verdicts.rows:
        seconds = f"{r.seconds:.3f}" if r.seconds is not None else ""
        z = f"{r.largest_z:.2f}" if r.largest_z is not None else ""
        lines.append(f"| {r.scene} | {r.technique} | {r.result} | {seconds} | {z} | "
                     f"{r.reference} |")
    TABLE.write_text("\n".join(lines) + "\n")
    TABLE.with_suffix(".json").write_text(json.dumps(
        {"spp": SPP, "threshold": verdicts.threshold, "tests": verdicts.tests,
         "rows": [r.__dict__ for r in verdicts.rows]}, indent=1) + "\n")


def main() -> int:
    only = [s for s in os.environ.get("STRESS_ONLY", "").split(",") if s]
    scenes = sorted(p for p in STRESS.glob("*.json") if not only or p.stem in only)
    with tempfile.TemporaryDirectory() as scratch:
        renders = run_scene_renders(scenes, Path(scratch))
    verdicts = judge(scenes, renders)
    write_table(verdicts, scenes)
    rows = verdicts.rows
    failed = [r for r in rows if r.result.startswith("FAIL")]
    applicable = sum(1 for r in rows if not r.result.startswith("n/a"))
    print(f"stress: {applicable - len(failed)} of {applicable} renders pass "
          f"({len(rows) - applicable} not applicable); |z| threshold {verdicts.threshold:.2f}; "
          f"{TABLE.relative_to(ROOT)}")
    for r in failed:
        print(f"  {r.scene} / {r.technique}: {r.result}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
