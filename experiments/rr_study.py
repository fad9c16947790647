#!/usr/bin/python3
"""Russian roulette rules chosen by measured efficiency (`make rr-study`).

Every scene in configs/scenes that a path tracer renders (the default scene, the bench dragon,
the TAIS scenes and PMC's caustic box) is rendered by path_mis under each rule at its own
resolution and path length, 16 spp, one thread per render and two renders at once, with SEEDS
seeds. A rule is the depth from which roulette is played (`rr_depth`; "scene" is the depth the
scene set before the default became "from vertex 1, below 0.25") and the survival probability
below which it is played (`rr_threshold`; the survival probability is min(1, max throughput ·
η²) throughout). Every rule is unbiased, so the error of a render is its variance: efficiency =
1 / (mean over pixels and channels of the variance of the pixel mean, from the EXR's own
channels × render-loop seconds).

Renders of one seed share their random numbers, so each rule is compared with the former
default (the scene's depth, always) paired by seed: the table gives the geometric mean over
seeds of efficiency(rule) / efficiency(former default) with a 95 % t-interval, per scene and
as the geometric mean over scenes.
Writes results/tables/rr_efficiency.{md,json}. Not a test: it times renders, on a quiet machine.
Usage: rr_study.py [BUILD_DIR] (default build)."""
import concurrent.futures
import json
import math
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from render_stats import read_render

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build")
RENDERER = BUILD / "bin" / "renderer"
TABLES = ROOT / "results" / "tables"
SCENES = ["cornell_spheres", "dragon_bench", "tais_fig4_bunny_box", "tais_fig5_motion_spheres",
          "tais_fig6_colour_wheel", "tais_fig7_glass_caustic", "tais_fig8_spot_lights",
          "tais_fig9_glass_reflections", "tais_fig10_fog_spots", "tais_fig11_env_glossy_plane",
          "tais_fig13_many_lights", "pmc_tab1_cornell_caustic"]
# The depths the scenes set until the default became rule "from vertex 1, below 0.25" (the
# colour wheel set none: the former default, 4).
FORMER_DEPTH = {"cornell_spheres": 4, "dragon_bench": 3, "tais_fig4_bunny_box": 3,
                "tais_fig5_motion_spheres": 3, "tais_fig6_colour_wheel": 4,
                "tais_fig7_glass_caustic": 5, "tais_fig8_spot_lights": 3,
                "tais_fig9_glass_reflections": 5, "tais_fig10_fog_spots": 3,
                "tais_fig11_env_glossy_plane": 3, "tais_fig13_many_lights": 3,
                "pmc_tab1_cornell_caustic": 5}
# name → (rr_depth, or None for the scene's former depth; rr_threshold). The first, the former
# default, is what the others are compared with.
RULES = {
    "scene depth, always": (None, 1.0),
    "scene depth, below 0.5": (None, 0.5),
    "scene depth, below 0.25": (None, 0.25),
    "scene depth, below 0.1": (None, 0.1),
    "from vertex 1, below 0.25": (1, 0.25),
    "from vertex 1, below 0.1": (1, 0.1),
    "from vertex 2, always": (2, 1.0),
}
FORMER_RULE = next(iter(RULES))
SEEDS = 6
SPP = 16
T95 = {5: 2.571, 6: 2.447, 7: 2.365, 9: 2.262}  # two-sided 95 % t quantiles by degrees of freedom


def render(scene: str, rule: str, seed: int, scratch: Path) -> tuple[float, float]:
    """(mean variance of the pixel mean, render-loop seconds) of one render."""
    depth, threshold = RULES[rule]
    out = scratch / f"{scene}.{list(RULES).index(rule)}.{seed}.exr"
    args = [RENDERER, "render", ROOT / "configs" / "scenes" / f"{scene}.json", "--spp", SPP,
            "--seed", seed, "--threads", 1, "--no-preview", "--out", out,
            "--set", f"/render/rr_threshold={threshold}",
            "--set", f"/render/rr_depth={FORMER_DEPTH[scene] if depth is None else depth}"]
    subprocess.run([str(a) for a in args], check=True, capture_output=True)
    values, variance = read_render(out)
    out.unlink()
    return variance, values["renderer.renderTime"]


def interval(log_ratios: list[float]) -> tuple[float, float, float]:
    """Geometric mean and 95 % t-interval of ratios given by their logarithms."""
    mean = statistics.fmean(log_ratios)
    half = T95[len(log_ratios) - 1] * statistics.stdev(log_ratios) / math.sqrt(len(log_ratios))
    return math.exp(mean), math.exp(mean - half), math.exp(mean + half)


def measure() -> dict[str, dict[str, list[tuple[float, float]]]]:
    jobs = [(scene, rule, seed) for scene in SCENES for seed in range(SEEDS) for rule in RULES]
    results: dict[str, dict[str, list[tuple[float, float]]]] = {
        scene: {rule: [(math.nan, math.nan)] * SEEDS for rule in RULES} for scene in SCENES}
    with tempfile.TemporaryDirectory() as scratch, \
            concurrent.futures.ThreadPoolExecutor(2) as pool:
        futures = {pool.submit(render, *job, Path(scratch)): job for job in jobs}
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            scene, rule, seed = futures[future]
            results[scene][rule][seed] = future.result()
            print(f"\r{done}/{len(jobs)} renders", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    return results


def table(results) -> tuple[str, dict]:
    log_gain: dict[str, dict[str, list[float]]] = {rule: {} for rule in RULES}
    for scene in SCENES:
        base = results[scene][FORMER_RULE]
        for rule in RULES:
            log_gain[rule][scene] = [math.log((vb * tb) / (v * t))
                                     for (v, t), (vb, tb) in zip(results[scene][rule], base)]
    rules = list(RULES)[1:]
    lines = ["| scene | " + " | ".join(rules) + " |", "| --- |" + " ---: |" * len(rules)]
    summary = {}
    for scene in SCENES:
        cells = ["{:.2f} [{:.2f}, {:.2f}]".format(*interval(log_gain[r][scene])) for r in rules]
        lines.append(f"| {scene} | " + " | ".join(cells) + " |")
    overall = []
    for rule in rules:  # the geometric mean over scenes, each scene's mean log gain once
        per_scene = [statistics.fmean(log_gain[rule][s]) for s in SCENES]
        summary[rule] = {"geometric_mean_gain": math.exp(statistics.fmean(per_scene)),
                         "worst_scene_gain": math.exp(min(per_scene)),
                         "best_scene_gain": math.exp(max(per_scene))}
        overall.append("{:.3f} (worst {:.2f})".format(summary[rule]["geometric_mean_gain"],
                                                      summary[rule]["worst_scene_gain"]))
    lines.append("| geometric mean over scenes | " + " | ".join(overall) + " |")
    return "\n".join(lines), summary


def main() -> None:
    results = measure()
    text, summary = table(results)
    TABLES.mkdir(parents=True, exist_ok=True)
    header = (f"# Russian roulette rules: efficiency relative to `{FORMER_RULE}`\n\n"
              f"path_mis, each scene's resolution and path length, {SPP} spp, one thread per "
              f"render, {SEEDS} seeds; efficiency = 1 / (mean variance of the pixel mean × "
              "render-loop seconds), geometric mean over seeds of the ratio to the former default "
              "rule paired by seed, with its 95 % interval. Made by experiments/rr_study.py.\n\n")
    (TABLES / "rr_efficiency.md").write_text(header + text + "\n")
    raw = {scene: {rule: [{"variance": v, "seconds": t} for v, t in runs]
                   for rule, runs in rules.items()} for scene, rules in results.items()}
    (TABLES / "rr_efficiency.json").write_text(json.dumps(
        {"rules": {k: {"rr_depth": d, "rr_threshold": t} for k, (d, t) in RULES.items()},
         "spp": SPP, "seeds": SEEDS, "summary": summary, "renders": raw}, indent=1) + "\n")
    print(header + text)


if __name__ == "__main__":
    main()
