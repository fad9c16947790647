"""CI thresholds: re-run the equal-sample budgets an experiment's thresholds name, and fail
when a technique's error rises above its stored maximum or its gain over the baseline falls
below its stored floor. `calibrate` proposes thresholds from a results file."""
import json
import math
import tempfile
from pathlib import Path

from . import experiment, references
from .errors import HarnessFailure

SIGMAS = 4  # thresholds sit this many standard deviations (or errors) from the measurement
MIN_MARGIN = 0.02


def evaluate(exp, summary):
    """One verdict per stored limit, against a summary (see experiment.summarise)."""
    metric = exp.primary_metric
    by_budget = {(s["technique"], s["budget"]): s for s in summary if s["kind"] == "spp"}
    verdicts = []
    for c in exp.thresholds.checks:
        s = by_budget[(c.technique, c.spp)]
        if c.max_error is not None:
            measured = (s["metrics"].get(metric) or {}).get("mean")
            verdicts.append({"technique": c.technique, "spp": c.spp, "limit": "max_error",
                             "threshold": c.max_error, "measured": measured,
                             "passed": measured is not None and measured <= c.max_error})
        if c.min_gain is not None:
            # No gain (a zero error) fails too: the check cannot vouch for it.
            measured = (s["gain"].get(metric) or {}).get("value")
            verdicts.append({"technique": c.technique, "spp": c.spp, "limit": "min_gain",
                             "threshold": c.min_gain, "measured": measured,
                             "passed": measured is not None and measured >= c.min_gain})
    return verdicts


def run_check(exp, workers):
    """Renders what the thresholds need (their techniques and the baseline at their spp,
    every seed) into a scratch directory; returns the verdicts. Writes nothing else."""
    profile = exp.profiles[exp.thresholds.profile]
    needed = set()
    for c in exp.thresholds.checks:
        needed.add((c.technique, "spp", c.spp))
        if c.min_gain is not None:
            needed.add((exp.baseline, "spp", c.spp))
    entry, reference_file = references.lookup(exp, profile)
    with tempfile.TemporaryDirectory() as scratch:
        runs = experiment.expand(exp, profile, only=needed)
        records = experiment.execute(exp, profile, runs, Path(scratch), reference_file, workers)
    references.check_noise(exp, profile, entry, experiment.smallest_rmse(records), record=False)
    return evaluate(exp, experiment.summarise(exp, records))


def format_verdicts(exp, verdicts):
    lines = []
    for v in verdicts:
        relation = "<=" if v["limit"] == "max_error" else ">="
        what = exp.primary_metric if v["limit"] == "max_error" else f"gain in {exp.primary_metric}"
        measured = "undefined" if v["measured"] is None else f"{v['measured']:.4g}"
        lines.append(f"  {'PASS' if v['passed'] else 'FAIL'} {v['technique']} at {v['spp']} spp: "
                     f"{what} {measured} (must be {relation} {v['threshold']:.4g})")
    return "\n".join(lines)


def _round(x, direction, digits=3):
    """x to `digits` significant digits, rounded with `direction` (math.ceil or math.floor)."""
    scale = 10 ** (digits - 1 - math.floor(math.log10(x)))
    return direction(x * scale) / scale


def calibrate(exp, results, spps):
    """A thresholds block from measured results: max_error = mean + 4 sd over seeds (rounded
    up), min_gain = gain · exp(-4 s.e. of log gain) (paired; rounded down). Either sits at
    least MIN_MARGIN from the measurement: CI machines may pick other Embree kernels, which
    perturb renders slightly, and two near-identical techniques on shared seeds have a paired
    gain with a standard error of 1e-6, which no such perturbation should trip."""
    if results["config"]["sha256"] != exp.config_sha256:
        raise HarnessFailure(f"{exp.id}: the results were made with another version of the "
                             "config; run the experiment again first")
    metric = exp.primary_metric
    checks = []
    for s in results["summary"]:
        e = s["metrics"][metric]
        if s["kind"] != "spp" or s["budget"] not in spps or not e or e["mean"] <= 0:
            continue
        check = {"technique": s["technique"], "spp": int(s["budget"]),
                 "max_error": _round(max(e["mean"] + SIGMAS * e["sd"],
                                       e["mean"] * (1 + MIN_MARGIN)), math.ceil)}
        g = s["gain"].get(metric)
        if g:
            log_se = g["stderr"] / g["value"]
            floor = min(g["value"] * math.exp(-SIGMAS * log_se), g["value"] / (1 + MIN_MARGIN))
            check["min_gain"] = _round(floor, math.floor)
        checks.append(check)
    order = list(exp.techniques)
    checks.sort(key=lambda c: (order.index(c["technique"]), c["spp"]))
    method = (f"max_error = mean + {SIGMAS} sd of {metric} over the {len(results['seeds'])} "
              f"seeds; min_gain = gain x exp(-{SIGMAS} s.e. of the paired log gain); each at "
              f"least {MIN_MARGIN:.0%} from the measurement; set by `experiments/run.py "
              f"calibrate` from the {results['profile']} profile at commit "
              f"{(results['provenance']['git_commit'] or 'unknown')[:10]}, "
              f"{results['provenance']['started'][:10]}")
    return {"profile": results["profile"], "method": method, "checks": checks}


def format_block(block):
    return json.dumps({"thresholds": block}, indent=2, ensure_ascii=False)
