#!/usr/bin/python3
"""`make bench`: where users wait, measured. Nothing here is a test (tests never time).

- start-up: `renderer --help`, and a whole `renderer render` of the default scene at 8×8 and
  1 spp (loading, building, writing included), medians of 11 runs;
- the default scene (cornell_spheres) at 512², 64 spp, 2 threads: peak memory (RSS), the time
  to write its EXR (radiance, variance, sample count) and PNG preview, the process's time
  outside the render loop, Msamples/s and efficiency 1/(variance × time);
- the bench dragon (202,520 triangles, path_mis, 512×384, 24 spp), 1 and 2 threads, medians of
  3 runs: Mrays/s, Msamples/s, efficiency, and the renderer's ray throughput against raw
  Embree's on the same rays (raw_embree_bench): the time raw Embree would take for the
  render's mix of camera, bounce and shadow rays, over the render loop's time.

Efficiency is 1/(mean pixel variance of the mean × render-loop seconds), from the EXR's own
variance channels: higher is better, comparable between versions of one scene and integrator.
Usage: bench.py [BUILD_DIR] (default build)."""
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from render_stats import GUIDE_RAW_EMBREE, guide_seconds, read_render

ROOT = Path(__file__).resolve().parent.parent
BUILD = Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build")
RENDERER = BUILD / "bin" / "renderer"
RAW_EMBREE = BUILD / "bin" / "raw_embree_bench"
DEFAULT_SCENE = ROOT / "configs" / "scenes" / "cornell_spheres.json"
DRAGON = ROOT / "configs" / "scenes" / "dragon_bench.json"


def timed(args: list[object]) -> tuple[float, float, str]:
    """Wall seconds, peak RSS in MiB and stderr of one process. GNU time forks a small process
    for the program: the peak a child reports to its Python parent through wait4 would include
    the Python process it was forked from (the kernel keeps the high-water mark across exec)."""
    start = time.perf_counter()
    proc = subprocess.run(["/usr/bin/time", "-f", "peak-rss-kib %M"] + [str(a) for a in args],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - start
    errors, _, peak = proc.stderr.rstrip().rpartition("\n")
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(map(str, args[:3]))} ... failed: {errors.strip()}")
    return wall, int(peak.split()[-1]) / 1024, errors


def written_ms(summary: str) -> float:
    return float(summary.rsplit("(written in ", 1)[1].split(" ms", 1)[0])


def start_up(scratch: Path) -> None:
    helps = [timed([RENDERER, "--help"]) for _ in range(11)]
    renders = [timed([RENDERER, "render", DEFAULT_SCENE, "--resolution", "8x8", "--spp", "1",
                      "--threads", "1", "--out", scratch / "tiny.exr"]) for _ in range(11)]
    print("start-up (median of 11):")
    print(f"  renderer --help: {statistics.median(w for w, _, _ in helps) * 1e3:.1f} ms, "
          f"peak RSS {statistics.median(m for _, m, _ in helps):.1f} MiB")
    print(f"  whole render, default scene at 8x8, 1 spp: "
          f"{statistics.median(w for w, _, _ in renders) * 1e3:.1f} ms")


def default_scene(scratch: Path) -> None:
    out = scratch / "default.exr"
    wall, rss, errors = timed([RENDERER, "render", DEFAULT_SCENE, "--resolution", "512x512",
                               "--spp", "64", "--threads", "2", "--out", out])
    meta, variance = read_render(out)
    seconds = meta["renderer.renderTime"]
    outside = wall - seconds
    print("default scene (cornell_spheres), path_mis, 512x512, 64 spp, 2 threads:")
    print(f"  peak RSS {rss:.1f} MiB; EXR + PNG written in {written_ms(errors):.0f} ms; "
          f"outside the render loop {outside:.2f} s of {wall:.2f} s")
    print(f"  {meta['samples'] / seconds * 1e-6:.3f} Msamples/s; efficiency "
          f"1/(variance x time) = {1 / (variance * seconds):.4g}")


def raw_embree() -> dict[str, float]:
    proc = subprocess.run([str(RAW_EMBREE)], capture_output=True, text=True, check=True)
    return json.loads(proc.stdout)


def dragon(scratch: Path) -> None:
    out = scratch / "dragon.exr"
    print("bench dragon (dragon_vrip_res2, 202,520 triangles), path_mis, 512x384, 24 spp, "
          "median of 3 runs:")
    results = {}
    for threads in (1, 2):
        runs = []
        for _ in range(3):
            timed([RENDERER, "render", DRAGON, "--threads", threads, "--no-preview",
                   "--out", out])
            runs.append(read_render(out))
        seconds = statistics.median(m["renderer.renderTime"] for m, _ in runs)
        meta, variance = runs[0]
        rays = {k: meta[f"renderer.rays.{k}"] for k in ("camera", "extension", "shadow")}
        samples = meta["samples"]
        results[threads] = (seconds, rays, meta)
        print(f"  {threads} thread(s): {sum(rays.values()) / seconds * 1e-6:.2f} Mrays/s, "
              f"{samples / seconds * 1e-6:.2f} Msamples/s, efficiency "
              f"{1 / (variance * seconds):.4g}")
    print(f"  2-thread speed-up: {results[1][0] / results[2][0]:.2f}x")
    raw = raw_embree()
    seconds, rays, meta = results[2]
    raw_seconds = (rays["camera"] / raw["camera"] + rays["extension"] / raw["bounce"]
                   + rays["shadow"] / raw["shadow"]) * 1e-6
    print(f"  raw Embree, 2 threads: camera {raw['camera']:.1f}, bounce {raw['bounce']:.1f}, "
          f"shadow {raw['shadow']:.1f} Mrays/s; the render's {sum(rays.values()) * 1e-6:.2f} M "
          f"rays would take it {raw_seconds:.2f} s against the render loop's {seconds:.2f} s: "
          f"{raw_seconds / seconds:.0%} of raw Embree's throughput")
    guide = guide_seconds(meta)
    figures = ", ".join(f"{kind} {rate:g}" for kind, rate in GUIDE_RAW_EMBREE.items())
    print(f"  the guide's raw Embree figures ({figures} Mrays/s) would take {guide:.2f} s: "
          f"{guide / seconds:.0%} of raw Embree's throughput (issue 19's goal: 75 %; "
          f"make embree-floor splits the loop)")


def main() -> None:
    with tempfile.TemporaryDirectory() as scratch:
        start_up(Path(scratch))
        default_scene(Path(scratch))
        dragon(Path(scratch))


if __name__ == "__main__":
    main()
