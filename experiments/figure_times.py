#!/usr/bin/python3
"""Render time of each figure's technique, this build against another renderer binary (issue 40's
before/after table in the README's Performance section). Each row renders one technique of an
experiment config at the quick profile's resolution and the spp given, one thread, and the two
binaries take turns (--runs times each); the table gives the median render-loop seconds
(renderer.renderTime) of each and their ratio. Nothing here is a test: run it on a quiet machine.

    git worktree add /tmp/before <commit> && cmake -S /tmp/before -B /tmp/before/build \\
        -DCMAKE_BUILD_TYPE=Release && cmake --build /tmp/before/build -j2 --target renderer
    experiments/figure_times.py --before /tmp/before/build/bin/renderer --before-label <commit>
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from harness import paths  # noqa: E402
from render_stats import read_render  # noqa: E402

# (row, experiment config, technique, spp)
FIGURES = [
    ("RIS fig. 3", "ris/fig03_dragon_one_ray", "ris_robust", 1),
    ("RIS fig. 4, light sampling (N = 20)", "ris/fig04_dragon_env", "light", 20),
    ("RIS fig. 4, robust RIS", "ris/fig04_dragon_env", "ris_robust", 20),
    ("RIS fig. 4, the paper's M and N", "ris/fig04_dragon_env", "ris_paper_mn", 20),
    ("two-stage fig. 8 (Blinn)", "twostage/fig08_blinn", "two_stage", 16),
    ("two-stage fig. 10", "twostage/fig10_variable_samples", "variable", 16),
    ("two-stage fig. 11", "twostage/fig11_varying_roughness", "two_stage", 4),
    ("two-stage fig. 12", "twostage/fig12_time", "two_stage", 16),
    ("TAIS fig. 6", "tais/fig06_lens", "tais", 32),
    ("TAIS fig. 11", "tais/fig11_point_on_light", "tais", 32),
    ("TAIS fig. 13", "tais/fig13_error_vs_time", "tais", 128),
]


def render_seconds(binary, config, technique, spp, scratch):
    experiment = json.loads((paths.ROOT / "configs" / "experiments" / f"{config}.json").read_text())
    width, height = experiment["profiles"]["quick"]["resolution"]
    integrator = experiment["techniques"][technique]["integrator"]
    out = Path(scratch) / "render.exr"
    subprocess.run([binary, "render", str(paths.ROOT / experiment["scene"]), "--set",
                    "/integrator=" + json.dumps(integrator), "--resolution", f"{width}x{height}",
                    "--spp", str(spp), "--seed", "1", "--threads", "1", "--no-preview", "--out",
                    str(out)], check=True, capture_output=True)
    return read_render(out)[0]["renderer.renderTime"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--before", required=True, help="the other renderer binary")
    parser.add_argument("--before-label", default="before")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    current = str(paths.renderer_binary())
    print(f"| figure (technique, spp) | {args.before_label} (s) | now (s) | now / "
          f"{args.before_label} |")
    print("|---|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as scratch:
        for row, config, technique, spp in FIGURES:
            times: dict[str, list[float]] = {args.before: [], current: []}
            for _ in range(args.runs):
                for binary in times:
                    times[binary].append(render_seconds(binary, config, technique, spp, scratch))
            before, now = (statistics.median(times[b]) for b in (args.before, current))
            print(f"| {row} ({technique}, {spp} spp) | {before:.3g} | {now:.3g} | "
                  f"×{now / before:.2f} |", flush=True)


if __name__ == "__main__":
    main()
