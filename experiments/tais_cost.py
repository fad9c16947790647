#!/usr/bin/python3
"""TAIS's cost per sample against path_mis, per figure, at a profile's sizes (TAIS issue 16,
point 5: the goal is at most ×1.3). Each TAIS figure's map technique (`tais`; fig. 4's default
16² map, `tais_16`) and `path_mis` render at the figure's table spp and the profile's
resolution, one thread per render, two renders at a time (as the experiments run them), over
--seeds seeds; the cost ratio is the mean render-loop time (renderer.renderTime) of TAIS over
path_mis's. Nothing here is a test: run it on a quiet machine.

With --before BIN, an older renderer binary renders the same TAIS jobs, interleaved with the
current ones, so the table shows the ratio before and after a change measured in the same
minutes on the same machine (the scene documents must be ones both binaries read). E.g. the
fused map passes (75d1ec2) against their parent:
    git worktree add /tmp/before 75d1ec2^ && cmake -S /tmp/before -B /tmp/before/build \\
        -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/before/build -j2 --target renderer
    experiments/tais_cost.py --before /tmp/before/build/bin/renderer --before-label 75d1ec2^

The table also gives the ratio measured inside the profile's experiment runs
(results/tais/<figure><suffix>.json, 5 seeds at the table spp), where they exist.
Writes results/tais/cost<suffix>.json and results/tables/tais_cost<suffix>.md."""
import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from harness import config, jobs, paths, provenance, renders  # noqa: E402
from render_stats import read_render  # noqa: E402

FIGURES = ["fig04_map_size", "fig05_time", "fig06_lens", "fig07_scatter_direction",
           "fig08_light_selection", "fig09_bifurcation", "fig10_scatter_distance",
           "fig11_point_on_light", "fig13_error_vs_time"]
BASELINE = "path_mis"
GOAL = 1.3


def tais_technique(figure: str) -> str:
    return "tais_16" if figure == "fig04_map_size" else "tais"


def asset_environment() -> dict[str, str]:
    """The environment with this checkout's asset folders first on RENDERER_ASSETS: a binary
    built from another checkout searches beside that one."""
    ours = [paths.ROOT / "assets", paths.ROOT.parent / "shared" / "assets"]
    given = os.environ.get("RENDERER_ASSETS")
    return {**os.environ,
            "RENDERER_ASSETS": ":".join([*map(str, ours), *([given] if given else [])])}


def render_time(binary: Path, scene_args: list[object], spp: int, seed: int,
                out: Path) -> float:
    """Seconds of one render's render loop, from its EXR."""
    args = [binary, "render", *scene_args, "--seed", seed, "--threads", 1, "--spp", spp,
            "--no-preview", "--out", out]
    proc = subprocess.run([str(a) for a in args], capture_output=True, text=True,
                          env=asset_environment())
    if proc.returncode != 0:
        raise RuntimeError(f"{binary} failed on {out.name}: {proc.stderr.strip()}")
    values, _ = read_render(out)
    return float(values["renderer.renderTime"])


def experiment_ratio(exp: config.Experiment, profile: config.Profile) -> float | None:
    """TAIS over path_mis in mean render time at the table spp, in the experiment's results."""
    results = paths.results_file(exp, profile.name)
    if not results.exists():
        return None
    runs = json.loads(results.read_text())["runs"]

    def mean_time(technique: str) -> float:
        return statistics.fmean(r["time"] for r in runs if r["technique"] == technique
                                and r["kind"] == "spp" and r["budget"] == profile.table_spp)
    return mean_time(tais_technique(exp.figure)) / mean_time(BASELINE)


def measure(profile_name: str, seeds: int, before: Path | None) -> list[dict]:
    """One row per figure: the table spp, size, mean times and ratios."""
    binaries = {"after": paths.renderer_binary(), **({"before": before} if before else {})}
    folder = paths.RENDERS / "tais_cost"
    folder.mkdir(parents=True, exist_ok=True)
    work, costs, keys = [], [], []
    experiments = {f: config.load(paths.CONFIGS / "tais" / f"{f}.json") for f in FIGURES}
    for seed in range(seeds):  # interleaved: every figure and binary once per round
        for figure, exp in experiments.items():
            profile = exp.profiles[profile_name]
            for name in [BASELINE, tais_technique(figure)]:
                technique = exp.techniques[name]
                args = renders.scene_args(exp, profile, technique.integrator,
                                          technique.overrides)
                for label, binary in binaries.items():
                    if name == BASELINE and label == "before":
                        continue  # the change under study is TAIS's; path_mis is the yardstick
                    out = folder / f"{figure}_{name}_{label}_seed{seed}.exr"
                    work.append(lambda b=binary, a=args, s=seed, o=out, n=profile.table_spp:
                                render_time(b, a, n, s, o))
                    costs.append(profile.resolution[0] * profile.resolution[1]
                                 * profile.table_spp)
                    keys.append((figure, name if name == BASELINE else label))
    times = jobs.run_parallel("tais cost", work, costs, 2)
    rows = []
    for figure, exp in experiments.items():
        profile = exp.profiles[profile_name]
        mean = {key: statistics.fmean(t for k, t in zip(keys, times) if k == (figure, key))
                for key in [BASELINE, *binaries]}
        rows.append({"figure": figure, "technique": tais_technique(figure),
                     "spp": profile.table_spp, "resolution": list(profile.resolution),
                     "seconds": mean,
                     "ratio": {label: mean[label] / mean[BASELINE] for label in binaries},
                     "ratio_in_experiment": experiment_ratio(exp, profile)})
    return rows


def table(document: dict) -> str:
    before = document["before"]
    head = ["figure", "TAIS technique", "spp", "size", "path_mis (s)", "TAIS (s)"]
    if before:
        head += [f"TAIS before, {before['label']} (s)", "ratio before"]
    head += ["ratio", "ratio in the experiment runs", f"≤ ×{GOAL}"]
    lines = [f"# TAIS: cost per sample against path_mis ({document['profile']} profile)", "",
             "Generated by `experiments/tais_cost.py`; do not edit. Mean render-loop seconds "
             f"over {document['seeds']} seeds, one thread per render, two renders at a time, at "
             "each figure's table spp; the ratio is TAIS's time over path_mis's. The last "
             "column but one is the same ratio inside the experiment runs (5 seeds). Renderer "
             f"{document['commit'][:10]}" + (f"; before: {before['label']}" if before else "")
             + ".", "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in document["rows"]:
        s = r["seconds"]
        cells = [r["figure"], r["technique"], str(r["spp"]), "×".join(map(str, r["resolution"])),
                 f"{s[BASELINE]:.3g}", f"{s['after']:.3g}"]
        if before:
            cells += [f"{s['before']:.3g}", f"×{r['ratio']['before']:.2f}"]
        in_runs = r["ratio_in_experiment"]
        cells += [f"×{r['ratio']['after']:.2f}", f"×{in_runs:.2f}" if in_runs else "—",
                  "yes" if r["ratio"]["after"] <= GOAL else "no"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--profile", default="full")
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--before", type=Path, help="an older renderer binary")
    parser.add_argument("--before-label", default="before")
    args = parser.parse_args()
    document = {"profile": args.profile, "seeds": args.seeds,
                "commit": provenance.git_commit(),
                "before": ({"binary": str(args.before), "label": args.before_label}
                           if args.before else None),
                "rows": measure(args.profile, args.seeds, args.before)}
    suffix = paths.suffix(args.profile)
    out_json = paths.RESULTS / "tais" / f"cost{suffix}.json"
    out_md = paths.TABLES / f"tais_cost{suffix}.md"
    for out, text in [(out_json, json.dumps(document, indent=1) + "\n"),
                      (out_md, table(document))]:
        scratch = out.with_suffix(out.suffix + ".tmp")
        scratch.write_text(text)
        scratch.replace(out)
        print(f"wrote {paths.relative(out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
