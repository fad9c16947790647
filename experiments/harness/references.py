"""Long reference renders and their manifest (reference/manifest.json).

A reference is the average of two independent half-references; half their RMS difference
estimates the reference's own noise (Var((A+B)/2) = Var(A-B)/4). A comparison is refused
when that noise is not below a fifth of the smallest error measured against the reference."""
import contextlib
import datetime
import fcntl
import hashlib
import json
import shutil
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from . import jobs, paths, provenance, render_server, renders
from .config import Experiment, Profile
from .errors import HarnessFailure

MAX_NOISE_RATIO = 0.2
# reference/manifest.json: "<paper>/<figure>/<profile>" -> its reference's entry.
Manifest = dict[str, dict[str, Any]]


def file_name(exp: Experiment, profile: Profile) -> Path:
    return Path(exp.paper_name) / f"{exp.figure}.{profile.name}.exr"


def key(exp: Experiment, profile: Profile) -> str:
    """What determines the reference image: the estimand of the scene document it renders
    (after overrides, with the reference integrator and the profile's resolution; without the
    settings that change only how the image is estimated, such as Russian roulette or light
    selection, and without the file's whitespace and comments) and its spp. A change makes the
    reference stale. Code changes do not: after fixing an integrator, re-render with
    `make references FORCE=1`. Kept per process while the config and scene files are
    unchanged: `renderer check` takes about 0.2 s, and status, copies and merges each ask."""
    cached = (exp.file, exp.profile_sha256[profile.name], exp.scene.stat().st_mtime_ns)
    if cached not in _keys:
        spec = {
            "scene_estimand_sha256": renders.check_scene(
                exp, profile, exp.reference_integrator).estimand_sha256,
            "spp": profile.reference_spp,
        }
        _keys[cached] = hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()
    return _keys[cached]


_keys: dict[tuple[Path, str, int], str] = {}


def load_manifest() -> Manifest:
    if not paths.MANIFEST.exists():
        return {}
    return json.loads(paths.MANIFEST.read_text())


@contextlib.contextmanager
def _manifest_lock() -> Iterator[None]:
    """Holds an exclusive lock on the manifest's lock file: processes that write entries of
    different experiments at once (a workflow engine's parallel jobs) each read the others'
    entries before writing theirs. Released when the file closes."""
    lock = paths.MANIFEST.with_name(".manifest.lock")
    lock.parent.mkdir(parents=True, exist_ok=True)
    with open(lock, "a") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        yield


def update_manifest_entry(name: str,
                          update: Callable[[dict[str, Any] | None], dict[str, Any]]) -> None:
    """Replaces one entry by update(the entry or None), reading, changing and writing the
    manifest under its lock."""
    with _manifest_lock():
        manifest = load_manifest()
        manifest[name] = update(manifest.get(name))
        provenance.write_json_atomically(paths.MANIFEST, manifest)


def entry_name(exp: Experiment, profile: Profile) -> str:
    return f"{exp.id}/{profile.name}"


def status(exp: Experiment, profile: Profile, manifest: Manifest | None = None) -> str:
    """'ok', 'missing' or 'stale'."""
    entry = (manifest if manifest is not None else load_manifest()).get(entry_name(exp, profile))
    file = paths.REFERENCE / file_name(exp, profile)
    if entry is None or not file.exists():
        return "missing"
    if entry["key"] != key(exp, profile) or entry["sha256"] != provenance.sha256_file(file):
        return "stale"
    return "ok"


def current_file(exp: Experiment, profile: Profile) -> Path | None:
    """The current reference's file; None when it is missing or stale (figures that show it
    leave it out then)."""
    return paths.REFERENCE / file_name(exp, profile) if status(exp, profile) == "ok" else None


def lookup(exp: Experiment, profile: Profile) -> tuple[dict[str, Any], Path]:
    """The manifest entry of a current reference; refuses a missing or stale one."""
    manifest = load_manifest()
    state = status(exp, profile, manifest)
    if state != "ok":
        raise HarnessFailure(f"{exp.id}: the {profile.name} reference is {state}; run "
                             f"`make references PROFILE={profile.name}`")
    entry = manifest[entry_name(exp, profile)]
    return entry, paths.REFERENCE / entry["file"]


def _same_key_entry(manifest: Manifest, wanted: str) -> tuple[str, dict[str, Any]] | None:
    """A current reference of another experiment with the same key: the same scene document,
    integrator, resolution and spp, rendered with the same fixed seeds, so the same image."""
    for name, entry in manifest.items():
        file = paths.REFERENCE / entry["file"]
        if (entry["key"] == wanted and file.exists()
                and entry["sha256"] == provenance.sha256_file(file)):
            return name, entry
    return None


def _copy_reference(exp: Experiment, profile: Profile, source: str,
                    entry: dict[str, Any]) -> None:
    out = paths.REFERENCE / file_name(exp, profile)
    out.parent.mkdir(parents=True, exist_ok=True)
    scratch = out.with_name(f".{out.name}.copying")
    shutil.copyfile(paths.REFERENCE / entry["file"], scratch)
    scratch.replace(out)
    copied = {**entry, "file": str(file_name(exp, profile)), "copied_from": source}
    update_manifest_entry(entry_name(exp, profile), lambda _: copied)
    print(f"[references] {entry_name(exp, profile)}: the same image as {source}, copied",
          flush=True)


def halves_dir(exp: Experiment, profile: Profile) -> Path:
    """Where the two halves of a reference are rendered: named by its key, so a run killed
    after its first half resumes there, and experiments of one key share them."""
    return paths.REFERENCE / f".halves-{key(exp, profile)[:16]}"


def half_seeds() -> list[int]:
    return [renders.REFERENCE_SEED_BASE, renders.REFERENCE_SEED_BASE + 1]


def render_half(exp: Experiment, profile: Profile, index: int, scratch: Path,
                threads: int) -> dict[str, Any]:
    """Renders half `index` (0 or 1) of the reference into `scratch` unless it is complete
    there; returns its provenance. A half is complete once its stamp (commit, seconds, CPUs) is
    beside it: the stamp is written after the render succeeded, while a render that Ctrl-C
    stopped leaves a valid EXR of fewer samples and no stamp. (An empty EXR is a workflow's
    placeholder for a half it did not need: workflow.render_reference_half.)"""
    seed = half_seeds()[index]
    half = scratch / f"half{index}.exr"
    stamp = half.with_suffix(".json")
    if half.exists() and half.stat().st_size > 0 and stamp.exists():
        print(f"[references] {paths.relative(half)}: rendered before, reused", flush=True)
        return {"seed": seed, **json.loads(stamp.read_text()), "resumed": True}
    scratch.mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    renders.render(exp, profile, exp.reference_integrator, half, seed,
                   spp=profile.reference_spp // 2, threads=threads)
    # The CPUs it could run on: a cluster job's allocation, which should hold its threads.
    origin = {"git_commit": provenance.git_commit(), "git_dirty": provenance.git_dirty(),
              "seconds": round(time.monotonic() - started, 2), "threads": threads,
              "cpus": jobs.default_jobs()}
    provenance.write_json_atomically(stamp, origin)
    return {"seed": seed, **origin, "resumed": False}


def merge_halves(exp: Experiment, profile: Profile, scratch: Path,
                 halves: list[dict[str, Any]], wall_seconds: float) -> None:
    """Merges the two halves in `scratch` into the reference and records its manifest entry
    (the halves' provenance, and `wall_seconds` spent on them and the merge)."""
    out = paths.REFERENCE / file_name(exp, profile)
    out.parent.mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    merged = json.loads(jobs.run_command(
        [paths.metrics_binary(), "merge", *(scratch / f"half{i}.exr" for i in range(2)),
         "--out", out, "--json"]))
    rendered = {
        "file": str(file_name(exp, profile)),
        "key": key(exp, profile),
        "scene": paths.relative(exp.scene),
        "set": exp.overrides,
        "integrator": exp.reference_integrator,
        "resolution": list(profile.resolution),
        "spp": profile.reference_spp,
        "seeds": half_seeds(),
        "wall_seconds": round(wall_seconds + time.monotonic() - started, 2),
        "halves": halves,
        "sha256": provenance.sha256_file(out),
        "noise_rmse": merged["noise_rmse"],
        "noise_sigma_over_mu": merged["noise_sigma_over_mu"],
        "created": datetime.date.today().isoformat(),
        "git_commit": provenance.git_commit(),
        "git_dirty": provenance.git_dirty(),
    }
    update_manifest_entry(entry_name(exp, profile), lambda _: rendered)
    print(f"[references] {paths.relative(out)}: noise σ/µ {merged['noise_sigma_over_mu']:.3g}",
          flush=True)


def same_key_entry(exp: Experiment, profile: Profile) -> tuple[str, dict[str, Any]] | None:
    """A current reference of another experiment with this one's key (its name and entry)."""
    return _same_key_entry(load_manifest(), key(exp, profile))


def copy_same_key(exp: Experiment, profile: Profile) -> bool:
    """Copies a current reference of another experiment with the same key, if there is one."""
    same = same_key_entry(exp, profile)
    if same is not None:
        _copy_reference(exp, profile, *same)
    return same is not None


def render_reference(exp: Experiment, profile: Profile, reuse: bool = True) -> None:
    """Renders the two halves with all cores, merges them, records the manifest entry; or, with
    `reuse`, copies a current reference with the same key, and resumes from a half that a
    killed run finished. Without `reuse` (forced, e.g. after fixing an integrator) every half is
    rendered again."""
    if reuse and copy_same_key(exp, profile):
        return
    print(f"[references] {entry_name(exp, profile)}: 2 x {profile.reference_spp // 2} spp of "
          f"{exp.reference_integrator['type']} at {profile.resolution[0]}x{profile.resolution[1]}",
          flush=True)
    started = time.monotonic()
    scratch = halves_dir(exp, profile)
    if not reuse:
        shutil.rmtree(scratch, ignore_errors=True)
    halves = [render_half(exp, profile, i, scratch, jobs.default_jobs()) for i in range(2)]
    merge_halves(exp, profile, scratch, halves, time.monotonic() - started)
    shutil.rmtree(scratch)


def ensure(experiments: list[Experiment], profile_name: str, force: bool = False) -> None:
    """Renders every reference that is missing or stale (or all of them with force)."""
    try:
        for exp in experiments:
            profile = exp.profiles[profile_name]
            if force or status(exp, profile) != "ok":
                # Forced (after a code change), a reference is rendered afresh, not copied.
                render_reference(exp, profile, reuse=not force)
    finally:
        # Reaped now, the servers' CPU time is not charged to the experiment run next.
        render_server.close_all()


def check_noise(exp: Experiment, profile: Profile, entry: dict[str, Any],
                smallest_rmse: float) -> float:
    """Refuses a too-noisy reference; returns the ratio of its noise to the smallest error (the
    results file records it: the manifest does not, since equal-time errors move run to run
    and a run must not rewrite a tracked file for that)."""
    if smallest_rmse <= 0:
        raise HarnessFailure(f"{exp.id}: a render matches the reference exactly (RMSE 0), so "
                             "the reference's noise cannot be judged against it")
    ratio = entry["noise_rmse"] / smallest_rmse
    if ratio >= MAX_NOISE_RATIO:
        raise HarnessFailure(
            f"{exp.id}: the {profile.name} reference's noise (RMSE {entry['noise_rmse']:.3g}) is "
            f"{ratio:.2f} of the smallest error compared against it ({smallest_rmse:.3g}); it "
            f"must be below {MAX_NOISE_RATIO}. Raise reference_spp.")
    return ratio
