#!/usr/bin/python3
"""How close the bench dragon can come to raw Embree's throughput (issue 19): Embree alone on
the very rays a render traces. Nothing here is a test: run it on a quiet machine.

The goal is the render loop at ≥ 75 % of raw Embree: the guide's figures for this machine kind
(render_stats.GUIDE_RAW_EMBREE) would trace the render's ray mix in some time T, and the loop
must take at most T / 0.75. This script measures
 - the render loop of the current renderer (dragon_bench.json, 2 threads, median of 5);
 - Embree alone on the rays that render traced, per thread and in the order traced, with
   nothing else running: a binary built with experiments/patches/embree_replay.patch records
   every ray (RECORD_RAYS=1) and replays them after the render (median of 3 replays). The
   same binary replays them under other Embree accelerations (RTC_CONFIG; each records its
   own render's rays) and regrouped by path depth, as a wavefront renderer would order them
   without its sorting or packets (REPLAY_BATCH: all rays of one depth of a batch of
   consecutive paths together);
 - on one thread, the loop split in three: Embree alone on its rays (the replay); everything
   but Embree alone: the same binary (PLAYBACK_HITS=1, which also fixes the pass sizes)
   records Embree's answers and renders the same samples again taking them from the record,
   so shading, sampling and the film run without Embree's traversal evicting their data (the
   played-back image must equal the rendered one bit for bit); and what the loop takes beyond
   the two, their interference. That remainder also holds the patched binary's own costs
   (reading the record), so it is as uncertain as the loop's run-to-run spread.

    git worktree add /tmp/replay HEAD && git -C /tmp/replay apply \\
        "$PWD/experiments/patches/embree_replay.patch" && cmake -S /tmp/replay \\
        -B /tmp/replay/build -DCMAKE_BUILD_TYPE=Release && \\
        cmake --build /tmp/replay/build -j2 --target renderer
    experiments/embree_floor.py --patched /tmp/replay/build/bin/renderer

Writes results/tables/embree_floor.md and .json."""
import argparse
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from harness import paths, provenance  # noqa: E402
from render_stats import GUIDE_RAW_EMBREE, guide_seconds, read_render  # noqa: E402

SCENE = paths.SCENES / "dragon_bench.json"
THREADS = 2
GOAL = 0.75
# (label, environment of the patched binary)
REPLAYS: list[tuple[str, dict[str, str]]] = [
    ("the renderer's Embree set-up (bvh8.triangle4, high quality)", {}),
    ("bvh8.triangle4i", {"RTC_CONFIG": "tri_accel=bvh8.triangle4i"}),
    ("bvh8.triangle4v", {"RTC_CONFIG": "tri_accel=bvh8.triangle4v"}),
    ("bvh4.triangle4", {"RTC_CONFIG": "tri_accel=bvh4.triangle4"}),
    ("binned SAH, no spatial splits", {"RTC_CONFIG": "tri_builder=sah"}),
    ("regrouped: batches of 8 paths", {"REPLAY_BATCH": "8"}),
    ("regrouped: batches of 64 paths", {"REPLAY_BATCH": "64"}),
    ("regrouped: batches of 512 paths", {"REPLAY_BATCH": "512"}),
]
REPLAY_LINE = re.compile(r"^replay: (\d+) rays on (\d+) threads, batch \S+: ([0-9.]+) s$", re.M)
PLAYBACK_LINE = re.compile(r"^playback: the render without Embree: ([0-9.]+) s, image (\w+)$",
                           re.M)


def render(binary: Path, out: Path, env: dict[str, str],
           threads: int = THREADS) -> tuple[dict[str, float], str]:
    proc = subprocess.run([str(binary), "render", str(SCENE), "--threads", str(threads),
                           "--no-preview", "--out", str(out)],
                          capture_output=True, text=True, env={**paths.asset_environment(), **env})
    if proc.returncode != 0:
        raise SystemExit(f"{binary} failed: {proc.stderr.strip()}")
    return read_render(out)[0], proc.stderr


def replay_seconds(binary: Path, stderr: str, threads: int) -> tuple[int, float]:
    """The replayed ray count and the median of the three replays' seconds."""
    found = REPLAY_LINE.findall(stderr)
    if len(found) != 3:
        raise SystemExit(f"{binary} printed no replay (built without the patch?)")
    if any(int(t) != threads for _, t, _ in found):
        raise SystemExit(f"{binary} recorded rays on other than the render's {threads} threads")
    return int(found[0][0]), statistics.median(float(s) for _, _, s in found)


def playback_seconds(binary: Path, stderr: str) -> float:
    found = PLAYBACK_LINE.findall(stderr)
    if len(found) != 1:
        raise SystemExit(f"{binary} printed no playback (built without the patch?)")
    seconds, image = found[0]
    if image != "identical":
        raise SystemExit(f"{binary}: the played-back image differs from the rendered one")
    return float(seconds)


def loop_seconds(scratch: Path, threads: int, runs: int) -> tuple[float, dict[str, float]]:
    metas = [render(paths.renderer_binary(), scratch / "loop.exr", {}, threads)[0]
             for _ in range(runs)]
    return statistics.median(m["renderer.renderTime"] for m in metas), metas[0]


def one_thread(patched: Path, scratch: Path) -> dict[str, float]:
    """The one-thread loop, Embree alone and everything but Embree alone (medians of 3)."""
    loop, _ = loop_seconds(scratch, 1, 3)
    embree, rest = [], []
    for _ in range(3):
        _, stderr = render(patched, scratch / "playback.exr",
                           {"RECORD_RAYS": "1", "PLAYBACK_HITS": "1"}, threads=1)
        embree.append(replay_seconds(patched, stderr, 1)[1])
        rest.append(playback_seconds(patched, stderr))
    return {"loop": loop, "embree_alone": statistics.median(embree),
            "rest_alone": statistics.median(rest)}


def measure(patched: Path, scratch: Path) -> dict:
    loop, meta = loop_seconds(scratch, THREADS, 5)
    rays = {kind: meta[f"renderer.rays.{kind}"] for kind in GUIDE_RAW_EMBREE}
    replays = []
    for label, env in REPLAYS:
        _, stderr = render(patched, scratch / "replay.exr", {"RECORD_RAYS": "1", **env})
        count, seconds = replay_seconds(patched, stderr, THREADS)
        replays.append({"replay": label, "rays": count, "seconds": seconds})
    if replays[0]["rays"] != sum(rays.values()):  # the same set-up traces the same rays
        raise SystemExit(f"{patched} traced {replays[0]['rays']} rays, the renderer "
                         f"{sum(rays.values()):.0f}: not the same render")
    return {"commit": provenance.git_commit(), "git_dirty": provenance.git_dirty(),
            "machine": provenance.machine(), "threads": THREADS, "rays": rays,
            "loop_seconds": loop, "guide_seconds": guide_seconds(meta),
            "replays": replays, "one_thread": one_thread(patched, scratch)}


def table(d: dict) -> str:
    guide, loop = d["guide_seconds"], d["loop_seconds"]
    floor = d["replays"][0]["seconds"]
    budget = guide / GOAL
    rays = d["rays"]
    figures = " / ".join(f"{rate:g}" for rate in GUIDE_RAW_EMBREE.values())
    lines = [
        f"# Embree alone on the bench dragon's own rays ({d['commit'] or '?'}"
        f"{', dirty' if d['git_dirty'] else ''})",
        "",
        f"dragon_bench.json, {d['threads']} threads: {rays['camera'] / 1e6:.2f} M camera, "
        f"{rays['extension'] / 1e6:.2f} M bounce and {rays['shadow'] / 1e6:.2f} M shadow rays "
        f"per frame. The guide's raw Embree figures ({figures} Mrays/s) would trace them in "
        f"{guide:.3f} s; the goal (≥ {GOAL * 100:.0f} % of raw Embree) needs a loop of at most "
        f"{budget:.3f} s. Written by experiments/embree_floor.py.",
        "",
        "| what | seconds per frame | guide's raw time ÷ this |",
        "| --- | ---: | ---: |",
        f"| render loop, current renderer (median of 5) | {loop:.3f} | {guide / loop:.0%} |",
    ]
    for r in d["replays"]:
        lines.append(f"| Embree alone on the render's rays: {r['replay']} (median of 3) | "
                     f"{r['seconds']:.3f} | {guide / r['seconds']:.0%} |")
    one = d["one_thread"]
    interference = one["loop"] - one["embree_alone"] - one["rest_alone"]
    budget1 = budget * one["loop"] / loop  # the goal's loop on one thread
    lines += [
        "",
        "One thread, the loop split in three (medians of 3):",
        "",
        "| part | seconds per frame | share of the loop |",
        "| --- | ---: | ---: |",
        f"| render loop | {one['loop']:.3f} | 100% |",
        f"| Embree alone on its rays, path order | {one['embree_alone']:.3f} | "
        f"{one['embree_alone'] / one['loop']:.0%} |",
        f"| everything but Embree alone (Embree's answers played back) | "
        f"{one['rest_alone']:.3f} | {one['rest_alone'] / one['loop']:.0%} |",
        f"| interference and the patch's own costs (the loop less the two) | {interference:.3f} | "
        f"{interference / one['loop']:.0%} |",
    ]
    lines += [
        "",
        f"- Outside Embree the loop spends at least {loop - floor:.3f} s "
        f"({(loop - floor) / loop:.0%} of it): shading, sampling, the film, and Embree's own "
        f"slow-down beside them. The goal leaves {budget - floor:.3f} s for all of that, "
        f"{1 - (budget - floor) / (loop - floor):.0%} less.",
        f"- On one thread the goal's loop is {budget1:.3f} s (scaled by the loop's two-thread "
        f"speed-up, {one['loop'] / loop:.2f}x). With Embree as fast as alone and no "
        f"interference at all, everything but Embree would have to take "
        f"{1 - (budget1 - one['embree_alone']) / one['rest_alone']:.0%} less time than it takes "
        f"alone; with today's interference, "
        f"{1 - (budget1 - one['embree_alone'] - interference) / one['rest_alone']:.0%} less.",
        "- Ray counts of the replays differ by a few rays between accelerations: rays that "
        "graze an edge or a coincident surface find another hit, and the recorded paths follow.",
    ]
    return "\n".join(lines) + "\n"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--patched", type=Path, required=True,
                        help="a renderer built with experiments/patches/embree_replay.patch")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        document = measure(args.patched, Path(scratch))
    out = paths.TABLES / "embree_floor"
    provenance.write_json_atomically(out.with_suffix(".json"), document)
    provenance.write_text_atomically(out.with_suffix(".md"), table(document))
    print(table(document), end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
