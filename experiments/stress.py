#!/usr/bin/python3
"""`make stress`: every technique on every stress scene (configs/stress/*.json, scenes built to
break numerics: see configs/stress/generate.py), at the scene's resolution and STRESS_SPP
samples per pixel. Each render must have:

- no non-finite sample (the EXR's renderer.nonFiniteSamples is 0) and no negative pixel (unless
  the estimator is signed: PMC-IP's unbiased image c + Σ(L − c)/(Nα) has a control variate c and
  can be negative where the radiance is not);
- a mean that agrees with a long reference of another unbiased technique estimating the same
  quantity, by a block test: the image is cut into a 4 × 4 grid of blocks, and for each block
  and channel z = (mean − reference mean) / √(variance of the mean + the reference's), from the
  renders' own variance channels, and p its two-sided normal tail. An adaptive estimator whose
  pixel samples are not independent (PMC-IP: each iteration's mixture follows the pixel's earlier
  samples, and its variance channel is the spread of a few iteration estimates) is rendered with
  SEEDS independent seeds instead, and its t = (mean over seeds − reference) / √(spread over
  seeds / SEEDS + the reference's variance) has SEEDS − 1 degrees of freedom. Every p must stay
  above the Šidák-corrected level for a family level of 0.01 over every test of the run.

A mean test needs the central limit theorem to hold at the budget. An estimator that draws only
light samples for direct lighting cannot find a glossy lobe narrower than what its samples
resolve: with n samples in a block and a lobe of solid angle Ω, about n·Ω·q of them land in it,
q the light-sampling density there, taken as 1/π (a sky sampled by cosine, or a light spanning
π sr). Below 10 expected hits the lobe's contribution is a rare event, the estimate heavy-tailed
(unbiased, but nearly always low), and the test not applicable: such rows are listed with the
expected count. Ω is 2π/(e + 1) for a lobe cos^e about a direction (Phong, Lafortune), and
4 · 2π/(e + 2) for a microfacet lobe cos^e θh (Blinn: e = 1/roughness; Beckmann α: e ≈ 2/α² − 2;
Ashikhmin-Shirley: e + 1 = √((e_u + 1)(e_v + 1))): the reflected lobe spans 4 times the
half-vectors' solid angle.

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
from scipy.stats import t as student_t

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

SEEDS = 16  # independent renders of an adaptive technique (Technique.seeds)
MIN_LOBE_HITS = 10  # expected light samples in the narrowest lobe, per block


@dataclass(frozen=True)
class Technique:
    integrator: dict
    quantity: str  # "full" (light transport) or "direct" (direct lighting)
    light_only: bool = False  # direct lighting from light samples only (no BSDF samples)
    signed: bool = False  # the estimate may be negative where the radiance is not
    adaptive: bool = False  # pixel samples not independent: tested over SEEDS renders


RIS = {"type": "ris", "candidates": 4, "samples": 1}
TECHNIQUES: dict[str, Technique] = {
    "path": Technique({"type": "path"}, "full"),
    "path_mis": Technique({"type": "path_mis"}, "full"),
    "path_nee": Technique({"type": "path_mis", "estimator": {"type": "light"}}, "full",
                          light_only=True),
    "path_mis_pmc_hi": Technique({"type": "path_mis", "estimator": {"type": "pmc_hi"}}, "full"),
    "path_mis_ris": Technique({"type": "path_mis", "estimator": RIS}, "full", light_only=True),
    "tais": Technique({"type": "tais"}, "full"),
    "pmc_ip": Technique({"type": "pmc_ip", "integrator": {"type": "path_mis"}}, "full",
                        signed=True, adaptive=True),
    "direct_mis": Technique({"type": "direct"}, "direct"),
    "direct_light": Technique({"type": "direct", "strategy": "light"}, "direct",
                              light_only=True),
    "direct_bsdf": Technique({"type": "direct", "strategy": "bsdf"}, "direct"),
    "direct_ris": Technique({"type": "direct", "estimator": RIS}, "direct", light_only=True),
    "direct_pmc_hi": Technique({"type": "direct", "estimator": {"type": "pmc_hi"}}, "direct"),
    "direct_two_stage": Technique(
        {"type": "direct", "estimator": {"type": "two_stage", "samples": 4}}, "direct"),
    "ris": Technique({"type": "ris", "mode": "fixed", "candidates": 4, "samples": 2}, "direct",
                     light_only=True),
    "two_stage": Technique({"type": "two_stage", "samples": 4}, "direct"),
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

    def rgb(self) -> np.ndarray:
        """The pixels of a render that succeeded."""
        if self.pixels is None:
            raise ValueError(f"a render that failed (status {self.status}) has no pixels")
        return self.pixels

    def variance_of_mean(self) -> np.ndarray:
        """The variance channels of a render that succeeded."""
        if self.variance is None:
            raise ValueError(f"a render that failed (status {self.status}) has no variance")
        return self.variance


@dataclass
class Row:
    scene: str
    technique: str
    result: str = ""
    seconds: float | None = None
    largest_z: float | None = None
    reference: str = ""
    statistic: str = ""  # "z", or "t (16 seeds)" for an adaptive technique
    problems: list[str] = field(default_factory=list)


def render(scene: Path, technique: str, spp: int, seed: int, out: Path) -> Render:
    integrator = TECHNIQUES[technique].integrator
    proc = jobs.run_process([RENDERER, "render", scene, "--set",
                             f"/integrator={json.dumps(integrator)}", "--spp", spp, "--seed",
                             seed, "--threads", 1, "--no-preview", "--out", out])
    lines = proc.stderr.strip().splitlines()
    if proc.returncode != 0:
        return Render(proc.returncode, lines[-1] if lines else "(no message)")
    spec, data = read_exr(out)
    names = list(spec.channelnames)
    pick = lambda prefix: np.stack([data[..., names.index(prefix + c)] for c in "RGB"],
                                   -1).astype(np.float64)
    return Render(0, seconds=float(spec.getattribute("renderer.renderTime")),
                  non_finite=float(spec.getattribute("renderer.nonFiniteSamples")),
                  pixels=pick(""), variance=pick("variance."))


def blocks(shape: tuple[int, ...]) -> list[tuple]:
    """The GRID × GRID blocks of an image of `shape`, as index tuples."""
    rows = np.array_split(np.arange(shape[0]), GRID)
    cols = np.array_split(np.arange(shape[1]), GRID)
    return [np.ix_(r, c) for r in rows for c in cols]


def block_means(image: np.ndarray) -> np.ndarray:
    return np.array([image[b].mean((0, 1)) for b in blocks(image.shape)])


def block_variances(variance: np.ndarray) -> np.ndarray:
    """Variance of each block's mean, from the pixels' variances of their means."""
    return np.array([variance[b].sum((0, 1)) / variance[b][..., 0].size**2
                     for b in blocks(variance.shape)])


@dataclass
class BlockTest:
    statistic: np.ndarray  # z or t, per block and channel
    p: np.ndarray  # two-sided tail probabilities
    kind: str  # "z" or "t (16 seeds)"


def block_test(images: list[Render], reference: Render) -> BlockTest:
    """The test of each block's mean against the reference's: z from one render's variance
    channels, or t over several independent renders."""
    ref_mean = block_means(reference.rgb())
    ref_var = block_variances(reference.variance_of_mean())
    means = np.array([block_means(r.rgb()) for r in images])
    if len(images) == 1:
        var = block_variances(images[0].variance_of_mean()) + ref_var
        diff, dof = means[0] - ref_mean, None
    else:
        dof = len(images) - 1
        diff, var = means.mean(0) - ref_mean, means.var(0, ddof=1) / len(images) + ref_var
    # Where the values are (nearly) constant (a constant sky, an emitter seen directly) only
    # rounding may differ: float sums of the same values in another order. Counted as
    # agreement whatever the variance, which a few ulps across seeds would make tiny.
    same = np.abs(diff) <= 1e-5 * np.maximum(np.abs(means).mean(0), 1e-30)
    with np.errstate(divide="ignore", invalid="ignore"):
        stat = np.where(same, 0, np.where(var > 0, diff / np.sqrt(var), np.inf))
    tail = norm.sf(np.abs(stat)) if dof is None else student_t.sf(np.abs(stat), dof)
    return BlockTest(stat, 2 * tail, "z" if dof is None else f"t ({len(images)} seeds)")


def lobe_exponent(material: dict) -> float | None:
    """The exponent e of a material's narrowest glossy lobe, as a microfacet cos^e θh (None:
    no glossy lobe); lobes about a direction are converted to the same solid angle."""
    kind = material.get("type")
    about_direction = lambda e: 4 * (e + 1) - 2  # 2π/(e + 1) = 4 · 2π/(e' + 2)
    def number(key: str, default: float | None = None) -> float | None:
        value = material.get(key, default)  # a texture is not judged: None
        return float(value) if isinstance(value, (int, float)) else None
    if kind == "phong":
        e = number("exponent", 32)
        return None if e is None else about_direction(e)
    if kind == "lafortune":  # a preset's lobes are broad (skin)
        lobes = [l["exponent"] for l in material.get("lobes", [])
                 if isinstance(l.get("exponent"), (int, float))]
        return about_direction(max(lobes)) if lobes else None
    if kind == "blinn":
        r = number("roughness", 0.1)
        return None if r is None else 1 / r
    if kind == "cook_torrance":
        a = number("roughness", 0.2)
        return None if a is None else 2 / a**2 - 2
    if kind == "ashikhmin_shirley":
        if "exponent_u" in material:
            eu, ev = number("exponent_u"), number("exponent_v")
        else:
            ru, rv = number("roughness_u"), number("roughness_v")
            eu, ev = (1 / ru, 1 / rv) if ru and rv else (None, None)
        return None if eu is None or ev is None else math.sqrt((eu + 1) * (ev + 1)) - 1
    return None


def narrowest_lobe(scene: Path) -> float | None:
    """The solid angle of the narrowest glossy lobe of any material in the scene."""
    exponents = []
    def visit(node) -> None:
        if isinstance(node, dict):
            if isinstance(node.get("type"), str) and (e := lobe_exponent(node)) is not None:
                exponents.append(e)
            for value in node.values():
                visit(value)
        elif isinstance(node, list):
            for value in node:
                visit(value)
    document = json.loads(scene.read_text())
    visit(document.get("materials", {}))
    visit(document.get("shapes", []))
    return 4 * 2 * math.pi / (max(exponents) + 2) if exponents else None


def expected_lobe_hits(scene: Path, render: Render) -> float | None:
    """Light samples per block expected in the scene's narrowest lobe (None: no glossy lobe)."""
    omega = narrowest_lobe(scene)
    if omega is None:
        return None
    h, w, _ = render.rgb().shape
    return SPP * h * w / GRID**2 * omega / math.pi


def has_delta_lights(scene: Path) -> bool:
    """Point or spot lights that emit (one of intensity 0 is invisible to every technique)."""
    lights = json.loads(scene.read_text()).get("lights", [])
    return any(light.get("type") in DELTA_LIGHTS and np.any(np.asarray(light["intensity"]) > 0)
               for light in lights)


def reference_for(technique: str) -> str:
    first, second = REFERENCES[TECHNIQUES[technique].quantity]
    return second if technique == first else first


def run_scene_renders(scenes: list[Path], scratch: Path) -> dict[tuple[str, str, str], Render]:
    """Every (scene, technique) at SPP (kind "image<seed>", seeds 1, or 1 to SEEDS for an
    adaptive technique), and the references at REFERENCE_FACTOR × SPP."""
    work = [(s, t, f"image{seed}", SPP, seed) for s in scenes for t in TECHNIQUES
            for seed in range(1, (SEEDS if TECHNIQUES[t].adaptive else 1) + 1)]
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
    level: float  # every p must be above it
    z_threshold: float  # the same level as a |z|
    t_threshold: float  # and as a |t| over SEEDS seeds
    tests: int  # block means compared


def judge(scenes: list[Path], renders: dict[tuple[str, str, str], Render]) -> Verdicts:
    rows, tests = [], {}
    for scene in scenes:
        delta = has_delta_lights(scene)
        for name, technique in TECHNIQUES.items():
            row = Row(scene.stem, name)
            rows.append(row)
            images = [renders[(scene.stem, name, f"image{seed}")]
                      for seed in range(1, (SEEDS if technique.adaptive else 1) + 1)]
            if images[0].status == 2:
                row.result = f"n/a: {images[0].message.removeprefix('error: ')}"
                continue
            if failed := [i for i in images if i.status != 0]:
                row.problems.append(f"exit status {failed[0].status}: {failed[0].message}")
                continue
            row.seconds = float(np.mean([i.seconds for i in images]))
            if (non_finite := sum(i.non_finite for i in images)) > 0:
                row.problems.append(f"{non_finite:.0f} non-finite samples")
            if not all(np.all(np.isfinite(i.rgb())) for i in images):
                row.problems.append("non-finite pixels")
            if not technique.signed and any(np.any(i.rgb() < 0) for i in images):
                row.problems.append("negative pixels")
            if name in HIT_ONLY and delta:
                row.reference = "n/a (point or spot lights)"
                continue
            hits = expected_lobe_hits(scene, images[0]) if technique.light_only else None
            if hits is not None and hits < MIN_LOBE_HITS:
                row.reference = (f"n/a: heavy-tailed (≈{hits:.2g} light samples per block in "
                                 f"the narrowest lobe, {MIN_LOBE_HITS} needed)")
                continue
            reference_name = reference_for(name)
            reference = renders[(scene.stem, reference_name, "reference")]
            if reference.status != 0:
                row.problems.append(f"reference {reference_name} failed: {reference.message}")
                continue
            row.reference = reference_name
            tests[(scene.stem, name)] = block_test(images, reference)
    count = sum(t.p.size for t in tests.values())
    level = 1 - (1 - FAMILY_LEVEL) ** (1 / max(count, 1))  # Šidák
    for row in rows:
        test = tests.get((row.scene, row.technique))
        if test is not None:
            row.largest_z = float(np.max(np.abs(test.statistic)))
            row.statistic = test.kind
            if not np.min(test.p) > level:
                row.problems.append(f"|{test.kind[0]}| {row.largest_z:.2f}: p {np.min(test.p):.1e} "
                                    f"≤ {level:.1e}")
        if not row.result:
            untested = row.largest_z is None
            row.result = ("FAIL: " + "; ".join(row.problems) if row.problems
                          else "pass, no mean test" if untested else "pass")
    return Verdicts(rows, level, float(norm.isf(level / 2)),
                    float(student_t.isf(level / 2, SEEDS - 1)), count)


def write_table(verdicts: Verdicts, scenes: list[Path]) -> None:
    lines = [
        "# Stress scenes × techniques",
        "",
        f"`make stress` (experiments/stress.py): {len(scenes)} scenes of `configs/stress/`, "
        f"{SPP} spp, references {REFERENCE_FACTOR * SPP} spp, one thread per render. A render "
        f"passes with no non-finite sample, no negative pixel (PMC-IP's signed image excepted), "
        f"and every block test (4 × 4 blocks × 3 channels, {verdicts.tests} in all) with p above "
        f"{verdicts.level:.1e}, the Šidák-corrected level for a family level of {FAMILY_LEVEL} "
        f"(|z| below {verdicts.z_threshold:.2f}); PMC-IP, adaptive, by t over {SEEDS} seeds "
        f"(|t| below {verdicts.t_threshold:.2f} with {SEEDS - 1} degrees of freedom). "
        f"Light-sample-only estimators are not mean-tested where the narrowest glossy lobe "
        f"expects fewer than {MIN_LOBE_HITS} of their samples per block (the method is in "
        f"experiments/stress.py); those rows, and hit-only techniques under point lights, pass "
        f"with no mean test. Time is the render loop's (the mean over seeds).",
        "",
        "| scene | technique | result | time (s) | largest \\|z\\| or \\|t\\| | reference |",
        "| --- | --- | --- | ---: | ---: | --- |",
    ]
    for r in verdicts.rows:
        seconds = f"{r.seconds:.3f}" if r.seconds is not None else ""
        z = f"{r.largest_z:.2f}" if r.largest_z is not None else ""
        if r.statistic.startswith("t"):
            z += " (t)"
        lines.append(f"| {r.scene} | {r.technique} | {r.result} | {seconds} | {z} | "
                     f"{r.reference} |")
    TABLE.write_text("\n".join(lines) + "\n")
    TABLE.with_suffix(".json").write_text(json.dumps(
        {"spp": SPP, "level": verdicts.level, "z_threshold": verdicts.z_threshold,
         "tests": verdicts.tests, "rows": [r.__dict__ for r in verdicts.rows]}, indent=1) + "\n")


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
    untested = sum(1 for r in rows if r.result == "pass, no mean test")
    print(f"stress: {applicable - len(failed)} of {applicable} renders pass, {untested} of them "
          f"without a mean test ({len(rows) - applicable} not applicable); |z| threshold "
          f"{verdicts.z_threshold:.2f}; {TABLE.relative_to(ROOT)}")
    for r in failed:
        print(f"  {r.scene} / {r.technique}: {r.result}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
