"""Fingerprints of the renderer that made a results file: pixel hashes of a few of the
experiment's own renders, so that a renderer change that alters its images is found
(`make check-results`) even when its config did not change.

Per technique, one render: seed 0 at its smallest equal-samples budget. A render whose choices
follow what it measured (RIS's robust M and N from timed costs) is not reproducible, so the
fingerprint renders it once more with the values the renderer pins for it (`renderer check
--json`, "pinned"). A hash covers the pixels of every channel (radiance, variance, counts,
auxiliary channels), not the metadata (times, dates)."""
import functools
import hashlib
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from . import exr, jobs, paths, renders
from .config import Experiment, Profile, Technique
from .records import SPP, RunRecord

SEED = 0


@dataclass(frozen=True)
class Fingerprint:
    """One render of a technique and the hash of its pixels."""
    technique: str
    spp: int  # the equal-samples budget (its pixel samples: Technique.integrator_for)
    seed: int
    pinned: dict[str, Any]  # integrator keys set to make the render reproducible; {}: none
    pixels_sha256: str

    @classmethod
    def from_json(cls, value: dict[str, Any]) -> "Fingerprint":
        return cls(**value)


def pixels_sha256(file: Path) -> str:
    """SHA-256 of the image's pixels, every channel as little-endian float32."""
    _, pixels = exr.read_exr(file)
    return hashlib.sha256(np.ascontiguousarray(pixels, dtype="<f4").tobytes()).hexdigest()


def smallest_budget(profile: Profile) -> int | None:
    return int(min(profile.spp)) if profile.spp else None


def _pinned(exp: Experiment, profile: Profile, technique: Technique, spp: int) -> dict[str, Any]:
    integrator, _ = technique.integrator_for(spp)
    return renders.check_technique(exp, profile, technique, integrator).pinned


def render_hash(exp: Experiment, profile: Profile, technique: Technique, spp: int,
                pinned: dict[str, Any], scratch: Path) -> str:
    """Renders the technique at `spp` (seed SEED, one thread) with `pinned` set; its hash."""
    out = scratch / f"{technique.name}_{spp}spp_seed{SEED}.exr"
    renders.render_at_spp(exp, profile, technique, out, SEED, spp, pinned=pinned)
    return pixels_sha256(out)


def record(exp: Experiment, profile: Profile, runs: list[RunRecord],
           workers: int) -> list[Fingerprint]:
    """The fingerprints of a finished profile: each technique's run of seed SEED at the
    smallest spp budget hashed as it is, or rendered again pinned where it measured."""
    spp = smallest_budget(profile)
    if spp is None:
        return []
    by_technique = {r.technique: r for r in runs
                    if r.kind == SPP and r.budget == spp and r.seed == SEED
                    and r.duplicate_of is None}
    pinned = {name: _pinned(exp, profile, exp.techniques[name], spp) for name in by_technique}
    with tempfile.TemporaryDirectory() as scratch:
        again = [name for name in by_technique if pinned[name]]
        work = [functools.partial(render_hash, exp, profile, exp.techniques[name], spp,
                                  pinned[name], Path(scratch)) for name in again]
        rendered = dict(zip(again, jobs.run_parallel(f"{exp.id} fingerprints", work,
                                                     [1.0] * len(work), workers)))
    return [Fingerprint(name, spp, SEED, pinned[name],
                        rendered[name] if pinned[name] else pixels_sha256(paths.output(run.file)))
            for name, run in by_technique.items()]


def stale(exp: Experiment, profile: Profile, fingerprints: list[Fingerprint],
          workers: int) -> list[str]:
    """Re-renders each fingerprint with the current renderer: what differs, one line each."""
    if not fingerprints:
        return ["the results have no fingerprint"]
    with tempfile.TemporaryDirectory() as scratch:
        work = []
        for f in fingerprints:
            if f.technique not in exp.techniques:
                return [f"technique {f.technique} is no longer in the config"]
            pinned = _pinned(exp, profile, exp.techniques[f.technique], f.spp)
            work.append(functools.partial(render_hash, exp, profile, exp.techniques[f.technique],
                                          f.spp, pinned, Path(scratch)))
        hashes = jobs.run_parallel(f"{exp.id} fingerprints", work, [1.0] * len(work), workers)
    return [f"{f.technique} at {f.spp} spp, seed {f.seed}: pixels differ"
            for f, h in zip(fingerprints, hashes) if h != f.pixels_sha256]
