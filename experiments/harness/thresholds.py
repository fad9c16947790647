"""CI thresholds: re-run the equal-sample budgets an experiment's thresholds name, and fail
when a technique's error rises above its stored maximum or its gain over the baseline falls
below its stored floor. `calibrate` proposes thresholds from a results file."""
import json
import math
import tempfile
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from . import experiment, records, references
from .config import Experiment, ThresholdCheck, Thresholds
from .errors import HarnessFailure
from .records import SPP, SummaryEntry, TechniqueBudget
from .results import Results
from .stats import Estimate, Gain

SIGMAS = 4  # thresholds sit this many standard deviations (or errors) from the measurement
MIN_MARGIN = 0.02
MAX_ERROR, MIN_GAIN = "max_error", "min_gain"


@dataclass(frozen=True)
class Verdict:
    """One stored limit against its measurement."""
    technique: str
    spp: int
    limit: str  # MAX_ERROR or MIN_GAIN
    threshold: float
    measured: float | None  # None: undefined (a missing metric, a zero error)
    passed: bool


def _thresholds(exp: Experiment) -> Thresholds:
    if exp.thresholds is None:
        raise HarnessFailure(f"{exp.id}: the config has no thresholds")
    return exp.thresholds


def evaluate(exp: Experiment, summary: list[SummaryEntry]) -> list[Verdict]:
    """One verdict per stored limit, against a summary (see experiment.summarise)."""
    metric = exp.primary_metric
    by_key = records.index_by_key(summary)
    verdicts = []
    for c in _thresholds(exp).checks:
        s = by_key[TechniqueBudget(c.technique, SPP, c.spp)]
        if c.max_error is not None:
            error = s.metrics.get(metric)
            measured = None if error is None else error.mean
            verdicts.append(Verdict(c.technique, c.spp, MAX_ERROR, c.max_error, measured,
                                    measured is not None and measured <= c.max_error))
        if c.min_gain is not None:
            # No gain (a zero error) fails too: the check cannot vouch for it.
            gain = s.gain.get(metric)
            measured = None if gain is None else gain.value
            verdicts.append(Verdict(c.technique, c.spp, MIN_GAIN, c.min_gain, measured,
                                    measured is not None and measured >= c.min_gain))
    return verdicts


def run_check(exp: Experiment, workers: int) -> list[Verdict]:
    """Renders what the thresholds need (their techniques and the baseline at their spp,
    every seed) into a scratch directory; returns the verdicts. Writes nothing else."""
    profile = exp.profiles[_thresholds(exp).profile]
    needed = set()
    for c in _thresholds(exp).checks:
        needed.add(TechniqueBudget(c.technique, SPP, c.spp))
        if c.min_gain is not None:
            needed.add(TechniqueBudget(exp.baseline, SPP, c.spp))
    entry, reference_file = references.lookup(exp, profile)
    with tempfile.TemporaryDirectory() as scratch:
        runs = experiment.expand(exp, profile, only=needed)
        rendered = experiment.execute(exp, profile, runs, Path(scratch), reference_file, workers)
    references.check_noise(exp, profile, entry, experiment.smallest_rmse(rendered))
    return evaluate(exp, experiment.summarise(exp, rendered))


def format_verdicts(exp: Experiment, verdicts: list[Verdict]) -> str:
    lines = []
    for v in verdicts:
        relation = "<=" if v.limit == MAX_ERROR else ">="
        what = exp.primary_metric if v.limit == MAX_ERROR else f"gain in {exp.primary_metric}"
        measured = "undefined" if v.measured is None else f"{v.measured:.4g}"
        lines.append(f"  {'PASS' if v.passed else 'FAIL'} {v.technique} at {v.spp} spp: "
                     f"{what} {measured} (must be {relation} {v.threshold:.4g})")
    return "\n".join(lines)


def _round(x: float, direction: Callable[[float], int], digits: int = 3) -> float:
    """x to `digits` significant digits, rounded with `direction` (math.ceil or math.floor)."""
    scale = 10 ** (digits - 1 - math.floor(math.log10(x)))
    return direction(x * scale) / scale


def _max_error(e: Estimate) -> float:
    return _round(max(e.mean + SIGMAS * e.sd, e.mean * (1 + MIN_MARGIN)), math.ceil)


def _min_gain(g: Gain) -> float:
    log_se = g.stderr / g.value
    return _round(min(g.value * math.exp(-SIGMAS * log_se), g.value / (1 + MIN_MARGIN)),
                  math.floor)


def calibrate(exp: Experiment, results: Results, spps: list[int]) -> Thresholds:
    """A thresholds block from measured results: max_error = mean + 4 sd over seeds (rounded
    up), min_gain = gain · exp(-4 s.e. of log gain) (paired; rounded down). Either sits at
    least MIN_MARGIN from the measurement: CI machines may pick other Embree kernels, which
    perturb renders slightly, and two near-identical techniques on shared seeds have a paired
    gain with a standard error of 1e-6, which no such perturbation should trip."""
    if results.config.sha256 != exp.profile_sha256[results.profile]:
        raise HarnessFailure(f"{exp.id}: the results were made with another version of the "
                             "config; run the experiment again first")
    metric = exp.primary_metric
    checks = []
    for s in results.summary:
        e, g = s.metrics[metric], s.gain.get(metric)
        if s.kind != SPP or s.budget not in spps or not e or e.mean <= 0:
            continue
        checks.append(ThresholdCheck(s.technique, int(s.budget),
                                     _max_error(e) if isinstance(e, Estimate) else None,
                                     None if g is None else _min_gain(g)))
    order = list(exp.techniques)
    checks.sort(key=lambda c: (order.index(c.technique), c.spp))
    method = (f"max_error = mean + {SIGMAS} sd of {metric} over the {len(results.seeds)} "
              f"seeds; min_gain = gain x exp(-{SIGMAS} s.e. of the paired log gain); each at "
              f"least {MIN_MARGIN:.0%} from the measurement; set by `experiments/run.py "
              f"calibrate` from the {results.profile} profile at commit "
              f"{(results.provenance.git_commit or 'unknown')[:10]}, "
              f"{results.provenance.started[:10]}")
    return Thresholds(results.profile, method, checks)


def format_block(block: Thresholds) -> str:
    """The block as the config's "thresholds" key, without the limits a check lacks."""
    value = {**records.to_json(block), "checks": [records.to_json(c) for c in block.checks]}
    return json.dumps({"thresholds": value}, indent=2, ensure_ascii=False)
