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
current checkout against the parent of the fused map passes (75d1ec2):
    git worktree add /tmp/before 75d1ec2^ && cmake -S /tmp/before -B /tmp/before/build \\
        -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/before/build -j2 --target renderer
    experiments/tais_cost.py --before /tmp/before/build/bin/renderer --before-label 1819c6a

--before also measures a patched binary: experiments/patches/ holds the patches behind the
committed variant tables, each written with --name and --before-note, e.g. TAIS with no
per-pixel map work at all (the floor any cut of that work can reach):
    git worktree add /tmp/floor HEAD && git -C /tmp/floor apply \
        "$PWD/experiments/patches/tais_no_map_assembly.patch" && cmake ... (as above)
    experiments/tais_cost.py --before /tmp/floor/build/bin/renderer \
        --before-label "no map work" --name tais_cost_floor \
        --before-note "TAIS with the per-pixel map work removed (tais_no_map_assembly.patch)"

The table also gives the ratio measured inside the profile's experiment runs
(results/tais/<figure><suffix>.json, all their seeds at the table spp), where they exist.
Writes results/tables/<name><suffix>.json and .md (name: tais_cost)."""
import argparse
import json
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


def render_time(binary: Path, scene_args: list[object], spp: int, seed: int,
                out: Path) -> float:
    """Seconds of one render's render loop, from its EXR."""
    args = [binary, "render", *scene_args, "--seed", seed, "--threads", 1, "--spp", spp,
            "--no-preview", "--out", out]
    proc = subprocess.run([str(a) for a in args], capture_output=True, text=True,
                          env=paths.asset_environment())
    if proc.returncode != 0:
        raise RuntimeError(f"{binary} failed on {out.name}: {proc.stderr.strip()}")
    values, _ = read_render(out)
    return float(values["renderer.renderTime"])


def experiment_ratio(exp: config.Experiment, profile: config.Profile) -> float | None:
    """TAIS over path_mis in mean render time at the table spp, from the experiment's summary."""
    results = exp.results_file(profile.name)
    if not results.exists():
        return None
    mean_time = {e["technique"]: e["time"]["mean"]
                 for e in json.loads(results.read_text())["summary"]
                 if e["kind"] == "spp" and e["budget"] == profile.table_spp}
    tais, baseline = mean_time.get(tais_technique(exp.figure)), mean_time.get(BASELINE)
    return tais / baseline if tais and baseline else None


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
        head += [f"TAIS at {before['label']} (s)", f"ratio at {before['label']}"]
    head += ["ratio", "ratio in the experiment runs", f"≤ ×{GOAL}"]
    older = (f" The columns at {before['label']} are the TAIS renders of "
             f"{before.get('note') or 'an older binary'}, interleaved with the current ones "
             "and divided by the current binary's path_mis time." if before else "")
    intro = ("Generated by `experiments/tais_cost.py`; do not edit. Mean render-loop seconds "
             f"over {document['seeds']} seeds, one thread per render, two renders at a time, at "
             "each figure's table spp; the ratio is TAIS's time over path_mis's. The last "
             "column but one is the same ratio inside the profile's experiment runs (all their "
             f"seeds). Renderer {document['commit'][:10]}"
             + (" with uncommitted changes" if document.get("git_dirty") else "") + "." + older)
    lines = [f"# TAIS: cost per sample against path_mis ({document['profile']} profile)", "",
             intro, "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
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
    parser.add_argument("--before", type=Path, help="another renderer binary: an older one, or a patched one")
    parser.add_argument("--before-label", default="older",
                        help="the older binary's name in the table, e.g. its commit")
    parser.add_argument("--before-note",
                        help="what the --before binary is, for the table's introduction")
    parser.add_argument("--name", default="tais_cost",
                        help="the tables' file name, without profile suffix and extension")
    args = parser.parse_args()
    document = {"profile": args.profile, "seeds": args.seeds,
                "commit": provenance.git_commit(), "git_dirty": provenance.git_dirty(),
                "before": ({"binary": str(args.before), "label": args.before_label,
                            "note": args.before_note} if args.before else None),
                "rows": measure(args.profile, args.seeds, args.before)}
    suffix = paths.suffix(args.profile)
    out_json = paths.TABLES / f"{args.name}{suffix}.json"  # not results/tais/: not an experiment
    out_md = paths.TABLES / f"{args.name}{suffix}.md"
    provenance.write_json_atomically(out_json, document)
    provenance.write_text_atomically(out_md, table(document))
    for out in (out_json, out_md):
        print(f"wrote {paths.relative(out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
