"""Command lines for the renderer and the metrics tool, built from an experiment, and their
JSON answers."""
import json
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from . import config, jobs, paths, render_server
from .config import Experiment, Integrator, Profile, Technique
from .errors import HarnessFailure, SceneRejected

# Reference halves use seeds far from the experiments' (0, 1, 2, ...), so a reference is
# independent of every image compared against it.
REFERENCE_SEED_BASE = 1 << 30


@dataclass(frozen=True)
class SceneCheck:
    """`renderer check --json`'s answer for a valid scene document."""
    integrator: str
    resolution: tuple[int, int]
    spp: int
    features: str
    scene_sha256: str  # of the document after overrides: what renders record as sceneSha256
    # of its estimand: the document without the settings that change only how the image is
    # estimated (description, spp, seed, sampler, light selection, roulette, light sampling)
    estimand_sha256: str
    # integrator keys that make a render reproducible where its choices follow what it
    # measures (fingerprints.py); {}: reproducible as configured
    pinned: dict[str, Any]
    transport: str  # the light its image holds: "direct" lighting or "paths"
    time_limit: bool  # whether it can stop at a time limit (else: fixed spp)
    # point and spot lights it can neither sample nor hit (it finds emitters only by hitting
    # them): its image lacks their light
    unreachable_lights: int


@dataclass(frozen=True)
class Comparison:
    """`metrics compare --json`: a render measured against the reference."""
    spp: int  # samples per pixel the render reached (renderer.spp)
    time: float  # seconds of its render loop (renderer.renderTime)
    metrics: dict[str, float | None]  # every metric of config.METRICS; None: not computed


def scene_args(exp: Experiment, profile: Profile, integrator: Integrator,
               overrides: dict[str, Any] | None = None) -> list[object]:
    """`SCENE --set ... --resolution WxH` rendering `integrator` at the profile's size, with the
    experiment's overrides and then `overrides` (a technique's own)."""
    args: list[object] = [exp.scene]
    for pointer, value in [*exp.overrides.items(), *(overrides or {}).items()]:
        args += ["--set", f"{pointer}={json.dumps(value)}"]
    args += ["--set", f"/integrator={json.dumps(integrator, sort_keys=True)}"]
    args += ["--resolution", f"{profile.resolution[0]}x{profile.resolution[1]}"]
    return args


def check(args: Sequence[object]) -> SceneCheck:
    """`renderer check ARGS --json` (ARGS: the scene file, then options). Raises SceneRejected
    for a document the renderer refuses, HarnessFailure when it gives no answer (a bad option,
    a crash)."""
    proc = jobs.run_process([paths.renderer_binary(), "check", *args, "--json"])
    try:
        answer: dict[str, Any] = json.loads(proc.stdout)
    except ValueError:
        raise jobs.failure(proc) from None
    if not answer["valid"]:
        raise SceneRejected(paths.relative(str(args[0])), answer["error"], answer["pointer"],
                            answer["message"])
    width, height = answer["resolution"]
    return SceneCheck(answer["integrator"], (width, height), answer["spp"],
                      answer["features"], answer["sceneSha256"], answer["estimandSha256"],
                      answer["pinned"], answer["transport"], answer["timeLimit"],
                      answer["unreachableLights"])


def check_scene(exp: Experiment, profile: Profile, integrator: Integrator) -> SceneCheck:
    """Checks the scene document a render of `integrator` (a reference's, or one of a figure's
    own) at the profile's size would use. A technique's: check_technique."""
    return check(scene_args(exp, profile, integrator))


def check_technique(exp: Experiment, profile: Profile, technique: Technique,
                    integrator: Integrator | None = None) -> SceneCheck:
    """check_scene for `technique`: its integrator, or a variant of it, with its overrides."""
    return check(scene_args(exp, profile, integrator or technique.integrator,
                            technique.overrides))


def render(exp: Experiment, profile: Profile, integrator: Integrator, out: Path, seed: int,
           spp: int | None = None, seconds: float | None = None, threads: int = 1) -> None:
    """Renders `integrator` (a reference's, or one of a figure's own); a technique's:
    render_technique."""
    _render(scene_args(exp, profile, integrator), out, seed, spp, seconds, threads)


def render_technique(exp: Experiment, profile: Profile, technique: Technique, out: Path,
                     seed: int, spp: int | None = None, seconds: float | None = None,
                     threads: int = 1, integrator: Integrator | None = None) -> None:
    """Renders `technique`: its integrator, or a variant of it, with its overrides."""
    _render(scene_args(exp, profile, integrator or technique.integrator, technique.overrides),
            out, seed, spp, seconds, threads)


def render_at_spp(exp: Experiment, profile: Profile, technique: Technique, out: Path, seed: int,
                  spp: int, threads: int = 1, pinned: dict[str, Any] | None = None) -> None:
    """render_technique at an equal-samples budget of `spp` (Technique.integrator_for: a sweep
    of samples per primary ray renders one pixel sample), with the integrator keys `pinned`."""
    integrator, samples = technique.integrator_for(spp)
    render_technique(exp, profile, technique, out, seed, spp=samples, threads=threads,
                     integrator={**integrator, **(pinned or {})})


def _render(scene: list[object], out: Path, seed: int, spp: int | None, seconds: float | None,
            threads: int) -> None:
    """`renderer render SCENE ...` (on a render server)."""
    args = [*scene, "--seed", seed, "--threads", threads, "--no-preview", "--out", out]
    args += ["--time-limit", seconds] if seconds is not None else ["--spp", spp]
    render_server.render(args)


def compare(image: Path, reference: Path, relmse_reject: float = 0.0) -> Comparison:
    """`metrics compare --json`. relmse_reject: the fraction of pixels with the largest relMSE
    left out of it."""
    answer = json.loads(jobs.run_command([paths.metrics_binary(), "compare", image, reference,
                                          "--json", "--relmse-reject", repr(relmse_reject)]))
    if "time" not in answer or "spp" not in answer:
        raise HarnessFailure(f"{image}: no renderer.renderTime or renderer.spp metadata")
    return Comparison(answer["spp"], answer["time"],
                      {name: answer.get(name) for name in config.METRICS})


def slope(points: list[dict[str, float]], scratch_file: Path) -> dict[str, Any]:
    """`metrics slope --json` over [{"spp", "time", "error"}]: the fit's slope, slope_stderr,
    intercept, r2 and n, vs_spp and vs_time."""
    scratch_file.write_text(json.dumps({"points": points}))
    return json.loads(jobs.run_command([paths.metrics_binary(), "slope", scratch_file, "--json"]))
