"""CI thresholds: re-run the equal-sample budgets an experiment's thresholds name, and fail
when a technique's error rises above its stored maximum or its gain over the baseline falls
below its stored floor. `calibrate` proposes thresholds from a results file."""
import json
import math
import tempfile
from pathlib import Path

from . import experiment, references

SIGMAS = 4  # thresholds sit this many standard deviations (or errors) from the measurement


def evaluate(exp, summary):
    """One verdict per stored limit, against a summary (see experiment.summarise)."""
    metric = exp.primary_metric
    by_budget = {(s["technique"], s["budget"]): s for s in summary if s["kind"] == "spp"}
    verdicts = []
    for c in exp.thresholds.checks:
        s = by_budget[(c.technique, c.spp)]
        if c.max_error is not None:
            measured = s["metrics"][metric]["mean"]
            verdicts.append({"technique": c.technique, "spp": c.spp, "limit": "max_error",
                             "threshold": c.max_error, "measured": measured,
                             "passed": measured <= c.max_error})
        if c.min_gain is not None:
            measured = s["gain"][metric]["value"]
            verdicts.append({"technique": c.technique, "spp": c.spp, "limit": "min_gain",
                             "threshold": c.min_gain, "measured": measured,
                             "passed": measured >= c.min_gain})
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
        lines.append(f"  {'PASS' if v['passed'] else 'FAIL'} {v['technique']} at {v['spp']} spp: "
                     f"{what} {v['measured']:.4g} (must be {relation} {v['threshold']:.4g})")
    return "\n".join(lines)


def _round_up(x, digits=3):
    scale = 10 ** (digits - 1 - math.floor(math.log10(x)))
    return math.ceil(x * scale) / scale


def _round_down(x, digits=3):
    scale = 10 ** (digits - 1 - math.floor(math.log10(x)))
    return math.floor(x * scale) / scale


def calibrate(exp, results, spps):
    """A thresholds block from measured results: max_error = mean + 4 sd over seeds (rounded
    up), min_gain = gain - 4 standard errors (rounded down; omitted when not positive). A
    floor below 1 still guards a technique that is meant to lose to the baseline, or to tie
    with it, against losing more."""
    metric = exp.primary_metric
    checks = []
    for s in results["summary"]:
        if s["kind"] != "spp" or s["budget"] not in spps:
            continue
        e = s["metrics"][metric]
        check = {"technique": s["technique"], "spp": int(s["budget"]),
                 "max_error": _round_up(e["mean"] + SIGMAS * e["sd"])}
        g = s["gain"].get(metric)
        if g and g["value"] - SIGMAS * g["stderr"] > 0:
            check["min_gain"] = _round_down(g["value"] - SIGMAS * g["stderr"])
        checks.append(check)
    method = (f"max_error = mean + {SIGMAS} sd of {metric} over the {len(results['seeds'])} seeds; "
              f"min_gain = gain - {SIGMAS} standard errors (delta method); measured with "
              f"`experiments/run.py calibrate` on the {results['profile']} profile at commit "
              f"{(results['provenance']['git_commit'] or 'unknown')[:10]}, "
              f"{results['provenance']['started'][:10]}")
    return {"profile": results["profile"], "method": method, "checks": checks}


def format_block(block):
    return json.dumps({"thresholds": block}, indent=2, ensure_ascii=False)
