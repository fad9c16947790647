"""Statistics over seeds: means with Student-t 95 % intervals; products of powers of means
(gains over a baseline, efficiencies 1/(T·Err)) with paired delta-method intervals; the
verdict against a paper's reported gain."""
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import stats as scipy_stats

CONFIDENCE = 0.95
# A gain within this factor of the paper's counts as reproduced: our scenes are recreations
# from the papers' descriptions, so only the size of the effect can be compared.
REPRODUCED_FACTOR = 1.25


def t_quantile(n: int) -> float:
    """Two-sided 95 % Student-t quantile for n samples (n - 1 degrees of freedom)."""
    return float(scipy_stats.t.ppf(0.5 + CONFIDENCE / 2, n - 1))


@dataclass(frozen=True)
class Estimate:
    """A mean over seeds with its Student-t 95 % interval. The fields, in order, are the keys
    of its object in the results files."""
    mean: float
    sd: float  # sample standard deviation across seeds
    n: int
    stderr: float
    ci95: tuple[float, float]


def estimate(values: Sequence[float]) -> Estimate:
    values = [float(v) for v in values]
    n = len(values)
    if n < 2:
        raise ValueError("an interval needs at least two seeds")
    mean = math.fsum(values) / n
    sd = math.sqrt(math.fsum((v - mean) ** 2 for v in values) / (n - 1))
    stderr = sd / math.sqrt(n)
    half_width = t_quantile(n) * stderr
    return Estimate(mean, sd, n, stderr, (mean - half_width, mean + half_width))


@dataclass(frozen=True)
class Gain:
    """A product of powers of means, e.g. how many times better a technique is than the
    baseline (> 1: better). stderr and ci95 are on the value's scale."""
    value: float
    stderr: float
    ci95: tuple[float, float]


EFFICIENCY_ESTIMATOR = "1/(mean time x mean error)"


@dataclass(frozen=True)
class EfficiencyEstimate:
    """An efficiency over seeds, 1/(mean time · mean error): a ratio of means with a paired
    delta-method interval, so it has no per-seed values and no sd. The fields, in order, are
    the keys of its object in the results files."""
    mean: float
    stderr: float
    ci95: tuple[float, float]
    n: int
    estimator: str = EFFICIENCY_ESTIMATOR


# What the results hold for a metric over seeds: an error's mean, or an efficiency.
MetricSummary = Estimate | EfficiencyEstimate


def mean_power_product(columns: Sequence[Sequence[float]], powers: Sequence[int]) -> Gain:
    """Π mean(column_i)^power_i over paired samples (row k of every column comes from the
    same seed), with a delta-method interval on the log scale:
    var(log value) = Σ_ij p_i p_j cov(c_i, c_j) / (n · mean_i · mean_j),
    using the sample covariance, so correlation between the columns (shared seeds, or the
    time and error of one render) is accounted for. A ratio of means rather than a mean of
    per-seed ratios, which Jensen's inequality would bias upwards."""
    x = np.array(columns, dtype=float)
    n = x.shape[1]
    if n < 2:
        raise ValueError("an interval needs at least two seeds")
    means = x.mean(axis=1)
    if np.any(means <= 0):
        raise ValueError("a product of powers of means needs positive means")
    p = np.array(powers, dtype=float)
    scaled = p / means
    log_var = float(scaled @ np.cov(x, ddof=1).reshape(len(p), len(p)) @ scaled) / n
    log_se = math.sqrt(max(log_var, 0.0))
    value = float(np.prod(means ** p))
    t = t_quantile(n)
    return Gain(value, value * log_se, (value * math.exp(-t * log_se), value * math.exp(t * log_se)))


def efficiency(times: Sequence[float], errors: Sequence[float]) -> EfficiencyEstimate:
    """1/(mean time · mean error), not a mean of per-seed efficiencies (which Jensen's
    inequality biases upwards); time and error of one render are paired."""
    e = mean_power_product([times, errors], (-1, -1))
    return EfficiencyEstimate(e.value, e.stderr, e.ci95, len(times))


def gain(baseline: Sequence[float], technique: Sequence[float], higher_is_better: bool) -> Gain:
    """Ratio of the mean metric of the baseline and of the technique over the same seeds,
    oriented so that > 1 means the technique is better."""
    if len(baseline) != len(technique):
        raise ValueError("a paired gain needs the same seeds for both techniques")
    powers = (-1, 1) if higher_is_better else (1, -1)
    return mean_power_product([baseline, technique], powers)


def paper_gain(values: dict[str, float], baseline: str, technique: str,
               higher_is_better: bool) -> float | None:
    if baseline not in values or technique not in values:
        return None
    b, t = values[baseline], values[technique]
    return t / b if higher_is_better else b / t


def verdict(ours: Gain | None, paper: float | None) -> str:
    """'reproduced' when our gain is within REPRODUCED_FACTOR of the paper's; 'weaker' or
    'stronger' when our whole 95 % interval lies below or above that band; 'inconclusive'
    when the point is outside the band but the interval reaches into it."""
    if paper is None or ours is None:
        return "—"
    band = (paper / REPRODUCED_FACTOR, paper * REPRODUCED_FACTOR)
    lo, hi = ours.ci95
    if band[0] <= ours.value <= band[1]:
        return "reproduced"
    if hi < band[0]:
        return "weaker"
    if lo > band[1]:
        return "stronger"
    return "inconclusive"
