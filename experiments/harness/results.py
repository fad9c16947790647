"""A results file (results/<paper>/<figure>.json) as typed objects: what the harness writes
and every reader reads, so that no code indexes the file's raw JSON. The fields of each class
are, in order, the keys of its object in the file (configs/schema/results.schema.json
describes them; a test checks every committed file against it). Fields that results made by
older commits lack have defaults; `to_json` leaves an optional field out while it is None."""
from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .config import PaperNumbers
from .fingerprints import Fingerprint
from .records import MatchedBudget, RunRecord, SummaryEntry, to_json


@dataclass(frozen=True)
class ConfigFile:
    file: str  # the experiment config, relative to the repository root
    sha256: str  # of the config as this profile sees it (config.Experiment.profile_sha256)


@dataclass(frozen=True)
class TechniqueEntry:
    label: str
    integrator: dict[str, Any]
    fixed_spp: bool = False  # results older than fixed-spp techniques have none
    samples_at: list[str] | None = None
    set: dict[str, Any] | None = None
    # only when not True: False, a fixed-spp row that matches no time; "baseline", one matched
    # by the baselines alone
    equal_time: bool | str | None = None
    sets_time: bool | None = None  # only when True: its times set equal-time budgets


@dataclass(frozen=True)
class Budgets:
    spp: list[int]
    seconds: list[float]
    matched_spp: list[int] = field(default_factory=list)


@dataclass(frozen=True)
class TableBudgets:
    spp: int
    seconds: float | str | None  # a budget, "matched", or none


@dataclass(frozen=True)
class ReferenceEntry:
    file: str
    sha256: str
    integrator: dict[str, Any]
    spp: int
    noise_rmse: float
    noise_sigma_over_mu: float
    noise_ratio_to_smallest_error: float


@dataclass(frozen=True, kw_only=True)
class Provenance:
    git_commit: str | None
    git_dirty: bool
    engine: str | None = None  # older results: the harness
    started: str
    wall_seconds: float
    cpu_seconds: float | None = None  # older results have none
    machine: dict[str, str | int]
    parallel_jobs: int
    threads_per_job: int
    command: str
    hosts: list[str] | None = None  # the workflow engine's, on a cluster


@dataclass(frozen=True)
class LineFit:
    """`metrics slope`: log error against log spp or log time."""
    intercept: float
    n: int
    r2: float
    slope: float
    slope_stderr: float


@dataclass(frozen=True)
class TechniqueSlopes:
    vs_spp: LineFit
    vs_time: LineFit
    # With slope_time_range "common": the window fitted (None: the techniques shared none, so
    # every run); `windowed` False when the experiment fits every run.
    windowed: bool = False
    time_range: tuple[float, float] | None = None

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {"vs_spp": dataclasses.asdict(self.vs_spp),
                               "vs_time": dataclasses.asdict(self.vs_time)}
        if self.windowed:
            out["time_range"] = list(self.time_range) if self.time_range else None
        return out

    @classmethod
    def from_json(cls, value: dict[str, Any]) -> TechniqueSlopes:
        window = value.get("time_range")
        return cls(LineFit(**value["vs_spp"]), LineFit(**value["vs_time"]),
                   windowed="time_range" in value,
                   time_range=(window[0], window[1]) if window else None)


@dataclass(frozen=True, kw_only=True)
class Results:
    experiment: str  # <paper>/<figure>
    profile: str
    description: str
    config: ConfigFile
    scene: str
    set: dict[str, Any]
    techniques: dict[str, TechniqueEntry]
    baseline: str
    also_baseline: str | None = None
    metrics: list[str]
    relmse_reject: float
    resolution: tuple[int, int]
    seeds: list[int]
    budgets: Budgets
    table: TableBudgets
    matched: list[MatchedBudget] = field(default_factory=list)
    crop: tuple[int, int, int, int] | None  # pixels: x, y, width, height
    reference: ReferenceEntry
    paper: list[PaperNumbers]
    provenance: Provenance
    fingerprints: list[Fingerprint] = field(default_factory=list)
    summary: list[SummaryEntry]
    slopes: dict[str, TechniqueSlopes]
    runs: list[RunRecord]

    @property
    def paper_name(self) -> str:
        return self.experiment.split("/")[0]

    @property
    def primary_metric(self) -> str:
        return self.metrics[0]

    def fixed_spp(self, technique: str) -> bool:
        return self.techniques[technique].fixed_spp

    def to_json(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if f.name == "also_baseline" and value is None:
                continue
            out[f.name] = _plain(value)
        return out

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> Results:
        return cls(
            experiment=doc["experiment"], profile=doc["profile"],
            description=doc["description"], config=ConfigFile(**doc["config"]),
            scene=doc["scene"], set=doc["set"],
            techniques={name: TechniqueEntry(**t) for name, t in doc["techniques"].items()},
            baseline=doc["baseline"], also_baseline=doc.get("also_baseline"),
            metrics=doc["metrics"], relmse_reject=doc["relmse_reject"],
            resolution=(doc["resolution"][0], doc["resolution"][1]), seeds=doc["seeds"],
            budgets=Budgets(**doc["budgets"]), table=TableBudgets(**doc["table"]),
            matched=[MatchedBudget(**m) for m in doc.get("matched", [])],
            crop=(c[0], c[1], c[2], c[3]) if (c := doc["crop"]) else None,
            reference=ReferenceEntry(**doc["reference"]),
            paper=[PaperNumbers(**p) for p in doc["paper"]],
            provenance=Provenance(**doc["provenance"]),
            fingerprints=[Fingerprint.from_json(f) for f in doc.get("fingerprints", [])],
            summary=[SummaryEntry.from_json(s) for s in doc["summary"]],
            slopes={t: TechniqueSlopes.from_json(s) for t, s in doc["slopes"].items()},
            runs=[RunRecord.from_json(r) for r in doc["runs"]])


def _plain(value: Any) -> Any:
    """A field's value as JSON: records through records.to_json (optional fields left out while
    None), tuples as lists."""
    if isinstance(value, TechniqueSlopes):
        return value.to_json()
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {k: _plain(v) for k, v in to_json(value).items()}
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def read(file: Path) -> Results:
    return Results.from_json(json.loads(file.read_text()))
