"""The records of an experiment's results (results/<paper>/<figure>.json): a run (one render
and its measurements), the summary of a technique at a budget over the seeds, and the
equal-time budgets matched to fixed-spp techniques. The fields of each record are, in order,
the keys of its object in the results files, so that `to_json` writes the files' format."""
from __future__ import annotations

import dataclasses
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from .stats import EfficiencyEstimate, Estimate, Gain, MetricSummary

SPP = "spp"  # equal samples: the budget is samples per pixel
TIME = "time"  # equal time: the budget is seconds


@dataclass(frozen=True)
class TechniqueBudget:
    """A technique at one budget: what runs are grouped by and summaries are looked up by."""
    technique: str
    kind: str  # SPP or TIME
    budget: float  # samples per pixel or seconds

    @property
    def key(self) -> TechniqueBudget:
        """The technique and budget alone: a record that extends them never equals them."""
        return TechniqueBudget(self.technique, self.kind, self.budget)


@dataclass(frozen=True)
class Run(TechniqueBudget):
    """One render to make."""
    seed: int

    def file_name(self) -> Path:
        budget = f"{self.budget:.12g}{'spp' if self.kind == SPP else 's'}"
        return Path(self.technique) / f"{budget}_seed{self.seed}.exr"


@dataclass(frozen=True)
class OriginalBudget:
    """The equal-sample budget whose records a fixed-spp technique's equal-time records
    copy (see experiment.matched_duplicates)."""
    kind: str
    budget: float


@dataclass(frozen=True)
class RunRecord(Run):
    """A run rendered and measured against the reference: an entry of the results' "runs"."""
    spp: int  # samples per pixel reached
    time: float  # seconds of the render loop (renderer.renderTime)
    file: str  # the render, relative to the repository root
    metrics: dict[str, float | None]  # every metric of config.METRICS; None: undefined
    duplicate_of: OriginalBudget | None = None

    @classmethod
    def from_json(cls, value: dict[str, Any]) -> RunRecord:
        return cls(value["technique"], value["kind"], value["budget"], value["seed"],
                   spp=value["spp"], time=value["time"], file=value["file"],
                   metrics=value["metrics"],
                   duplicate_of=_original_budget(value.get("duplicate_of")))


@dataclass(frozen=True)
class SummaryEntry(TechniqueBudget):
    """A technique at a budget over every seed: an entry of the results' "summary"."""
    spp: Estimate
    time: Estimate
    metrics: dict[str, MetricSummary | None]  # the experiment's metrics; None: undefined
    gain: dict[str, Gain | None]  # over the baseline at the same budget; {} for the baseline
    duplicate_of: OriginalBudget | None = None
    # over the experiment's also_baseline; None without one, {} for it
    also_gain: dict[str, Gain | None] | None = None

    @classmethod
    def from_json(cls, value: dict[str, Any]) -> SummaryEntry:
        return cls(
            value["technique"], value["kind"], value["budget"],
            spp=_with_interval(Estimate, value["spp"]),
            time=_with_interval(Estimate, value["time"]),
            metrics={name: _metric_summary(m) for name, m in value["metrics"].items()},
            gain=_gains(value["gain"]) or {},
            duplicate_of=_original_budget(value.get("duplicate_of")),
            also_gain=_gains(value.get("also_gain")))


@dataclass(frozen=True)
class MatchedBudget:
    """An equal-time budget matched to a fixed-spp technique's mean render time at one of
    its spp budgets: an entry of the results' "matched"."""
    technique: str
    spp: int
    seconds: float


def to_json(record: Any) -> dict[str, Any]:
    """A record as the object the results files hold. An optional field (one that defaults to
    None) is left out while it is None: only copies carry "duplicate_of"."""
    optional = {f.name for f in dataclasses.fields(record) if f.default is None}
    return {name: value for name, value in dataclasses.asdict(record).items()
            if not (name in optional and value is None)}


def _with_interval(cls: type, value: dict[str, Any]) -> Any:
    return cls(**{**value, "ci95": tuple(value["ci95"])})


def _metric_summary(value: dict[str, Any] | None) -> MetricSummary | None:
    if value is None:
        return None
    return _with_interval(EfficiencyEstimate if "estimator" in value else Estimate, value)


def _gains(value: dict[str, Any] | None) -> dict[str, Gain | None] | None:
    if value is None:
        return None
    return {name: None if g is None else _with_interval(Gain, g) for name, g in value.items()}


def _original_budget(value: dict[str, Any] | None) -> OriginalBudget | None:
    return None if value is None else OriginalBudget(**value)


R = TypeVar("R", bound=TechniqueBudget)


def group_by_key(records: Iterable[R]) -> dict[TechniqueBudget, list[R]]:
    """(technique, kind, budget) -> its records, in the order first seen."""
    groups: dict[TechniqueBudget, list[R]] = {}
    for r in records:
        groups.setdefault(r.key, []).append(r)
    return groups


def index_by_key(entries: Iterable[SummaryEntry]) -> dict[TechniqueBudget, SummaryEntry]:
    """(technique, kind, budget) -> its summary entry (there is one per key)."""
    return {e.key: e for e in entries}
