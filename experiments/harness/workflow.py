"""The units a workflow engine schedules as jobs of their own (experiments/Snakefile): one
render and its measurement, the equal-time budgets matched after the first phase, and the
results document assembled from the records the jobs left beside their renders. They call the
functions the harness's own engine calls (experiment.render_run, matched_budgets,
matched_runs, matched_duplicates, results_document), so both engines write the same numbers.

Files, under results/renders/<profile>/<paper>/<figure>/ as the harness's engine writes them:
  <technique>/<budget>_seed<n>.exr        a render
  <technique>/<budget>_seed<n>.exr.json   its record and what its job cost ("job")
  matched.json                            the matched budgets and the second phase's runs"""
import datetime
import json
import math
import socket
import time
from pathlib import Path
from typing import Any

from . import experiment, paths, provenance, references, render_server
from .config import Experiment, Profile
from .errors import HarnessFailure
from .records import MatchedBudget, Run, RunRecord, to_json


def renders_dir(exp: Experiment, profile: Profile) -> Path:
    return paths.RENDERS / profile.name / exp.id


def record_file(exr: Path) -> Path:
    return exr.with_name(exr.name + ".json")


def matched_file(exp: Experiment, profile: Profile) -> Path:
    return renders_dir(exp, profile) / "matched.json"


def first_phase(exp: Experiment, profile: Profile) -> list[Run]:
    """Every run of the first phase, in the harness's order (experiment.expand)."""
    return experiment.expand(exp, profile)


def second_phase(exp: Experiment, profile: Profile) -> tuple[list[MatchedBudget], list[Run]]:
    """The matched budgets and the second phase's runs, as write_matched left them."""
    document = json.loads(matched_file(exp, profile).read_text())
    return ([MatchedBudget(**m) for m in document["matched"]],
            [Run(**r) for r in document["runs"]])


def _run_named(exp: Experiment, profile: Profile, file_name: str) -> Run:
    """The run whose render is `file_name` (<technique>/<budget>_seed<n>.exr), of either phase:
    looked up rather than parsed, so its budget has the type (int or float) the harness's
    engine gives it, and the records come out equal."""
    runs = first_phase(exp, profile)
    if matched_file(exp, profile).exists():
        runs += second_phase(exp, profile)[1]
    for run in runs:
        if str(run.file_name()) == file_name:
            return run
    raise HarnessFailure(f"{exp.id}: no run of the {profile.name} profile renders {file_name}")


def render_one(exp: Experiment, profile: Profile, file_name: str) -> Path:
    """Renders and measures one run; writes its record beside the render. Returns the record's
    path."""
    run = _run_named(exp, profile, file_name)
    _, reference_file = references.lookup(exp, profile)
    started_at = datetime.datetime.now().astimezone().isoformat(timespec="seconds")
    started = time.monotonic()
    try:
        record = experiment.render_run(exp, profile, run, renders_dir(exp, profile),
                                       reference_file)
    finally:
        render_server.close_all()  # its CPU time counts once it has exited
    job = {"host": socket.gethostname(), "started": started_at,
           "wall_seconds": round(time.monotonic() - started, 3),
           "cpu_seconds": round(experiment.children_cpu_seconds(), 3)}
    out = record_file(renders_dir(exp, profile) / run.file_name())
    provenance.write_json_atomically(out, {"record": to_json(record), "job": job})
    return out


def _read(exp: Experiment, profile: Profile, runs: list[Run]) -> list[dict[str, Any]]:
    documents = []
    for run in runs:
        file = record_file(renders_dir(exp, profile) / run.file_name())
        if not file.exists():
            raise HarnessFailure(f"{exp.id}: {paths.relative(file)} is missing; render it first")
        documents.append(json.loads(file.read_text()))
    return documents


def _records(documents: list[dict[str, Any]]) -> list[RunRecord]:
    return [RunRecord.from_json(d["record"]) for d in documents]


def write_matched(exp: Experiment, profile: Profile) -> Path:
    """From the first phase's records: the matched equal-time budgets and the runs they add."""
    records = _records(_read(exp, profile, first_phase(exp, profile)))
    matched = experiment.matched_budgets(exp, profile, records)
    runs = experiment.matched_runs(exp, profile, matched, records) if matched else []
    out = matched_file(exp, profile)
    provenance.write_json_atomically(out, {"matched": [to_json(m) for m in matched],
                                           "runs": [to_json(r) for r in runs]})
    return out


def assemble(exp: Experiment, profile: Profile) -> Path:
    """The results document from every record, in the order the harness's engine keeps them
    (first phase, second phase, matched duplicates). Its provenance sums the jobs' wall and
    CPU seconds (they may have run on many machines at once): `wall_seconds` is job-slot
    seconds, with parallel_jobs 1."""
    matched, second = second_phase(exp, profile)
    documents = _read(exp, profile, first_phase(exp, profile) + second)
    records = _records(documents)
    records += experiment.matched_duplicates(exp, matched, records)
    entry, reference_file = references.lookup(exp, profile)
    jobs = [d["job"] for d in documents]
    document = experiment.results_document(exp, profile, records, matched, entry, reference_file, {
        "engine": "snakemake",
        "started": min((j["started"] for j in jobs), key=datetime.datetime.fromisoformat),
        "wall_seconds": round(math.fsum(j["wall_seconds"] for j in jobs), 2),
        "cpu_seconds": round(math.fsum(j["cpu_seconds"] for j in jobs), 1),
        "parallel_jobs": 1,
        "hosts": sorted({j["host"] for j in jobs})})
    out = exp.results_file(profile.name)
    provenance.write_json_atomically(out, document.to_json())
    return out


def halves_dir(exp: Experiment, profile: Profile) -> Path:
    """Where the workflow renders an experiment's reference halves: a directory of its own (the
    harness's engine names its by the key, for experiments of one key to share). Shared, a
    half made again for one experiment would make the workflow redo another's renders."""
    return paths.REFERENCE / ".halves" / profile.name / exp.id


def render_reference_half(exp: Experiment, profile: Profile, index: int, threads: int,
                          if_needed: bool = False) -> None:
    """One half of the reference, for reference_merge. With `if_needed`, a half that
    reference_merge will not read (needs_halves) is left as empty files instead: a
    workflow's merge always has both halves as its inputs."""
    scratch = halves_dir(exp, profile)
    if if_needed and not needs_halves(exp, profile):
        scratch.mkdir(parents=True, exist_ok=True)
        for ext in ("exr", "json"):
            (scratch / f"half{index}.{ext}").touch()
        return
    references.render_half(exp, profile, index, scratch, threads)


def needs_halves(exp: Experiment, profile: Profile) -> bool:
    """Whether reference_merge needs the halves rendered: the reference is neither current nor
    a copy of a current one with the same key."""
    if references.status(exp, profile) == "ok":
        return False
    return references.same_key_entry(exp, profile) is None


def reference_merge(exp: Experiment, profile: Profile, stamp: Path) -> str:
    """Makes the reference current: 'current' if it was, 'copied' from another experiment's
    with the same key, or 'merged' from the two halves that render_reference_half left (they
    stay, for the engine to delete). Writes `stamp`, the workflow's mark that the reference
    is current, holding its hash (stamp_is_current)."""
    if references.status(exp, profile) == "ok":
        outcome = "current"
    elif references.copy_same_key(exp, profile):
        outcome = "copied"
    else:
        scratch = halves_dir(exp, profile)
        halves = [{"seed": seed, **json.loads((scratch / f"half{i}.json").read_text()),
                   "resumed": False} for i, seed in enumerate(references.half_seeds())]
        references.merge_halves(exp, profile, scratch, halves,
                                math.fsum(h.get("seconds", 0.0) for h in halves))
        outcome = "merged"
    entry, _ = references.lookup(exp, profile)
    provenance.write_text_atomically(stamp, entry["sha256"] + "\n")
    return outcome


def stamp_is_current(exp: Experiment, profile: Profile, stamp: Path) -> bool:
    """Whether a stamp reference_merge wrote still marks the current reference: the reference
    is current (key and hash, references.status) and is the one the stamp saw, not another
    rendered since with the same key (`make references FORCE=1`), whose renders would differ."""
    if not stamp.exists() or references.status(exp, profile) != "ok":
        return False
    return references.load_manifest()[references.entry_name(exp, profile)]["sha256"] == \
        stamp.read_text().strip()
