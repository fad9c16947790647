"""Statistics over seeds: means with Student-t 95 % intervals, gains over a baseline with
delta-method intervals, and the verdict against a paper's reported gain."""
import math
from dataclasses import dataclass

from scipy import stats as scipy_stats

CONFIDENCE = 0.95
# A gain within this factor of the paper's counts as reproduced: our scenes are recreations
# from the papers' descriptions, so only the size of the effect can be compared.
REPRODUCED_FACTOR = 1.25


def t_quantile(n):
    """Two-sided 95 % Student-t quantile for n samples (n - 1 degrees of freedom)."""
    return float(scipy_stats.t.ppf(0.5 + CONFIDENCE / 2, n - 1))


@dataclass
class Estimate:
    mean: float
    sd: float  # sample standard deviation across seeds
    n: int

    @property
    def stderr(self):
        return self.sd / math.sqrt(self.n)

    @property
    def half_width(self):
        return t_quantile(self.n) * self.stderr

    def interval(self):
        return (self.mean - self.half_width, self.mean + self.half_width)

    def to_json(self):
        lo, hi = self.interval()
        return {"mean": self.mean, "sd": self.sd, "n": self.n, "stderr": self.stderr,
                "ci95": [lo, hi]}


def estimate(values):
    values = [float(v) for v in values]
    n = len(values)
    if n < 2:
        raise ValueError("an interval needs at least two seeds")
    mean = math.fsum(values) / n
    sd = math.sqrt(math.fsum((v - mean) ** 2 for v in values) / (n - 1))
    return Estimate(mean, sd, n)


@dataclass
class Gain:
    """How many times better a technique is than the baseline (> 1: better)."""
    value: float
    stderr: float
    ci95: tuple

    def to_json(self):
        return {"value": self.value, "stderr": self.stderr, "ci95": list(self.ci95)}


def gain(baseline, technique, higher_is_better):
    """Ratio of means, oriented so that > 1 means the technique is better. The interval is
    the delta method on log(ratio): var = (sd_b/mean_b)^2/n_b + (sd_t/mean_t)^2/n_t, with the
    t quantile of the smaller sample (conservative). Seeds are shared between techniques
    (common random numbers), so positively correlated errors make this wider, not narrower,
    than a paired interval."""
    num, den = (technique, baseline) if higher_is_better else (baseline, technique)
    value = num.mean / den.mean
    log_var = (num.sd / num.mean) ** 2 / num.n + (den.sd / den.mean) ** 2 / den.n
    log_se = math.sqrt(log_var)
    t = t_quantile(min(num.n, den.n))
    return Gain(value, value * log_se, (value * math.exp(-t * log_se), value * math.exp(t * log_se)))


def paper_gain(values, baseline, technique, higher_is_better):
    if baseline not in values or technique not in values:
        return None
    b, t = values[baseline], values[technique]
    return t / b if higher_is_better else b / t


def verdict(ours, paper):
    """'reproduced' when our gain is within REPRODUCED_FACTOR of the paper's or the paper's
    gain lies inside our 95 % interval; otherwise 'weaker' or 'stronger'."""
    if paper is None or ours is None:
        return "—"
    lo, hi = ours.ci95
    if paper / REPRODUCED_FACTOR <= ours.value <= paper * REPRODUCED_FACTOR or lo <= paper <= hi:
        return "reproduced"
    return "weaker" if ours.value < paper else "stronger"
