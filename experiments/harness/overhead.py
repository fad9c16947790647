"""How much of each experiment's run was spent outside render loops (process start-up, scene
loading and building, writing and measuring images): from its results file, the render loops'
seconds (renderer.renderTime of every render, each counted once) against the job slots' wall
seconds (wall × renders at once)."""
import json
import math

from . import paths


def rows(profile: str) -> list[tuple[str, int, float, float, float]]:
    """(experiment, renders, wall seconds, render-loop seconds, share outside the loops) of
    every results file of the profile."""
    out = []
    for file in sorted(paths.RESULTS.glob("*/*.json")):
        document = json.loads(file.read_text())
        if document.get("profile") != profile or "provenance" not in document:
            continue
        runs = [r for r in document["runs"] if not r.get("duplicate_of")]
        wall = document["provenance"]["wall_seconds"]
        slots = wall * document["provenance"]["parallel_jobs"]
        loops = math.fsum(r["time"] for r in runs)
        out.append((document["experiment"], len(runs), wall, loops,
                    max(0.0, 1 - loops / slots) if slots > 0 else 0.0))
    return out


def report(profile: str) -> str:
    table = rows(profile)
    lines = [f"{'experiment':44s} {'renders':>7s} {'wall s':>8s} {'loops s':>8s} {'outside':>7s}"]
    for name, renders, wall, loops, share in table:
        lines.append(f"{name:44s} {renders:7d} {wall:8.0f} {loops:8.0f} {share:7.0%}")
    if table:  # the share of all, each experiment weighed by its wall time
        wall = math.fsum(t[2] for t in table)
        outside = math.fsum(t[2] * t[4] for t in table) / wall if wall > 0 else 0.0
        lines.append(f"{'all':44s} {sum(t[1] for t in table):7d} {wall:8.0f} "
                     f"{math.fsum(t[3] for t in table):8.0f} {outside:7.0%}")
    return "\n".join(lines)
