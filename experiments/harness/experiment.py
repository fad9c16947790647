"""One experiment end to end: expand into renders (techniques × budgets × seeds), run them in
parallel, measure each against the reference, summarise over seeds, fit convergence slopes.

Equal-sample budgets are deterministic (bit-identical pixels for a seed); equal-time budgets
depend on the machine's speed, so CI thresholds only ever use equal-sample budgets."""
import datetime
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from . import config, jobs, paths, provenance, references, renders, stats
from .errors import HarnessFailure


@dataclass(frozen=True)
class Run:
    technique: str
    kind: str  # "spp" (equal samples) or "time" (equal time)
    budget: float  # samples per pixel or seconds
    seed: int

    def file_name(self):
        budget = f"{self.budget:.12g}{'spp' if self.kind == 'spp' else 's'}"
        return Path(self.technique) / f"{budget}_seed{self.seed}.exr"


def expand(exp, profile, only=None):
    """Every run of the profile, or only those whose (technique, kind, budget) is in `only`.
    Interleaved (seed, then budget, then technique innermost) so that the techniques share
    the machine's load pattern: consecutive runs of one budget differ only in technique."""
    budgets = [("spp", s) for s in profile.spp] + [("time", s) for s in profile.seconds]
    runs = []
    for seed in range(profile.seeds):
        for kind, budget in budgets:
            for technique in exp.techniques:
                if only is None or (technique, kind, budget) in only:
                    runs.append(Run(technique, kind, budget, seed))
    return runs


def parallel_jobs(profile, requested):
    """Renders at once: never more threads in all than cores, so every render has its
    threads' cores to itself and an equal-time budget means equal compute."""
    return max(1, min(requested, jobs.default_jobs() // profile.threads_per_job))


def _estimated_cost(run, profile):
    """Seconds, roughly (1 µs per sample and a fixed process cost), for the ETA only."""
    if run.kind == "time":
        return run.budget + 0.3
    return run.budget * profile.resolution[0] * profile.resolution[1] * 1e-6 + 0.3


def execute(exp, profile, runs, out_dir, reference_file, workers):
    """Renders and measures every run; returns one record per run, in run order."""

    def job(run):
        def work():
            out = out_dir / run.file_name()
            out.parent.mkdir(parents=True, exist_ok=True)
            integrator = exp.techniques[run.technique].integrator
            if run.kind == "spp":
                renders.render(exp, profile, integrator, out, run.seed, spp=int(run.budget),
                               threads=profile.threads_per_job)
            else:
                renders.render(exp, profile, integrator, out, run.seed, seconds=run.budget,
                               threads=profile.threads_per_job)
            m = renders.compare(out, reference_file, exp.relmse_reject)
            if "time" not in m or "spp" not in m:
                raise HarnessFailure(f"{out}: no renderer.renderTime or renderer.spp metadata")
            return {"technique": run.technique, "kind": run.kind, "budget": run.budget,
                    "seed": run.seed, "spp": m["spp"], "time": m["time"],
                    "file": paths.relative(out),
                    "metrics": {name: m.get(name) for name in config.METRICS}}
        return work

    costs = [_estimated_cost(r, profile) for r in runs]
    return jobs.run_parallel(f"{exp.id} {profile.name}", [job(r) for r in runs], costs,
                             parallel_jobs(profile, workers))


def _groups(records):
    """(technique, kind, budget) -> that budget's records, ordered by seed."""
    groups = {}
    for r in sorted(records, key=lambda r: r["seed"]):
        groups.setdefault((r["technique"], r["kind"], r["budget"]), []).append(r)
    return groups


def _column(group, metric):
    values = [r["metrics"][metric] for r in group]
    return None if any(v is None for v in values) else values


def _efficiency_columns(group, metric):
    """The (time, error) columns of efficiency 1/(T·error)."""
    error = _column(group, config.EFFICIENCY_OF[metric])
    return None if error is None else [[r["time"] for r in group], error]


def _metric_summary(group, metric):
    """Mean and interval of a metric over seeds. An efficiency is 1/(mean T · mean error)
    with a paired delta-method interval, not a mean of per-seed efficiencies."""
    if metric in config.EFFICIENCY_OF:
        columns = _efficiency_columns(group, metric)
        if columns is None or min(sum(c) for c in columns) <= 0:
            return None
        e = stats.mean_power_product(columns, (-1, -1))
        return {"mean": e.value, "stderr": e.stderr, "ci95": list(e.ci95), "n": len(group),
                "estimator": "1/(mean time x mean error)"}
    values = _column(group, metric)
    return None if values is None else stats.estimate(values).to_json()


def _gain(base_group, group, metric):
    """The technique's gain over the baseline at one budget, paired by seed; None when it is
    undefined (a zero error, a missing metric)."""
    if [r["seed"] for r in base_group] != [r["seed"] for r in group]:
        raise ValueError("the baseline and the technique were run with different seeds")
    try:
        if metric in config.EFFICIENCY_OF:
            b, t = _efficiency_columns(base_group, metric), _efficiency_columns(group, metric)
            if b is None or t is None:
                return None
            return stats.mean_power_product(b + t, (1, 1, -1, -1)).to_json()
        b, t = _column(base_group, metric), _column(group, metric)
        if b is None or t is None:
            return None
        return stats.gain(b, t, config.METRICS[metric]).to_json()
    except ValueError:  # a zero mean
        return None


def summarise(exp, records):
    """Per (technique, budget): each metric's mean and 95 % interval over seeds, the spp and
    time reached, and the gain over the baseline at the same budget."""
    groups = _groups(records)
    summary = []
    for (technique, kind, budget), group in groups.items():
        entry = {
            "technique": technique, "kind": kind, "budget": budget,
            "spp": stats.estimate([r["spp"] for r in group]).to_json(),
            "time": stats.estimate([r["time"] for r in group]).to_json(),
            "metrics": {m: _metric_summary(group, m) for m in exp.metrics},
            "gain": {},
        }
        base_group = groups.get((exp.baseline, kind, budget))
        if technique != exp.baseline and base_group:
            entry["gain"] = {m: _gain(base_group, group, m) for m in exp.metrics}
        summary.append(entry)
    return summary


def slopes(exp, records, scratch_dir):
    """Least-squares slope of log(primary error) against log(spp) and log(time), over every
    run of each technique (all seeds and budgets), from `metrics slope`."""
    out = {}
    for technique in exp.techniques:
        points = [{"spp": r["spp"], "time": r["time"], "error": r["metrics"][exp.primary_metric]}
                  for r in records if r["technique"] == technique]
        if len({p["spp"] for p in points}) >= 2 and all(p["error"] and p["error"] > 0
                                                         for p in points):
            out[technique] = renders.slope(points, Path(scratch_dir) / f"{technique}.json")
    return out


def smallest_rmse(records):
    return min(r["metrics"]["rmse"] for r in records)


def run(exp, profile_name, workers):
    """Runs the whole profile and writes results/<paper>/<figure>.json. Returns its path."""
    profile = exp.profiles[profile_name]
    entry, reference_file = references.lookup(exp, profile)
    started_at = datetime.datetime.now().astimezone().isoformat(timespec="seconds")
    started = time.monotonic()
    out_dir = paths.RENDERS / profile.name / exp.id
    shutil.rmtree(out_dir, ignore_errors=True)
    runs = expand(exp, profile)
    records = execute(exp, profile, runs, out_dir, reference_file, workers)
    ratio = references.check_noise(exp, profile, entry, smallest_rmse(records))
    with tempfile.TemporaryDirectory() as scratch:
        fitted = slopes(exp, records, scratch)
    document = {
        "experiment": exp.id,
        "profile": profile.name,
        "description": exp.description,
        "config": {"file": paths.relative(exp.file), "sha256": exp.config_sha256},
        "scene": paths.relative(exp.scene),
        "set": exp.overrides,
        "techniques": {t.name: {"label": t.label, "integrator": t.integrator}
                       for t in exp.techniques.values()},
        "baseline": exp.baseline,
        "metrics": exp.metrics,
        "relmse_reject": exp.relmse_reject,
        "resolution": list(profile.resolution),
        "seeds": list(range(profile.seeds)),
        "budgets": {"spp": profile.spp, "seconds": profile.seconds},
        "table": {"spp": profile.table_spp, "seconds": profile.table_seconds},
        "crop": list(profile.crop) if profile.crop else None,
        "reference": {"file": paths.relative(reference_file), "sha256": entry["sha256"],
                      "integrator": entry["integrator"], "spp": entry["spp"],
                      "noise_rmse": entry["noise_rmse"],
                      "noise_sigma_over_mu": entry["noise_sigma_over_mu"],
                      "noise_ratio_to_smallest_error": ratio},
        "paper": [vars(p) for p in exp.paper],
        "provenance": {
            "git_commit": provenance.git_commit(),
            "git_dirty": provenance.git_dirty(),
            "started": started_at,
            "wall_seconds": round(time.monotonic() - started, 2),
            "machine": provenance.machine(),
            "parallel_jobs": parallel_jobs(profile, workers),
            "threads_per_job": profile.threads_per_job,
            "command": " ".join(sys.argv),
        },
        "summary": summarise(exp, records),
        "slopes": fitted,
        "runs": records,
    }
    out = paths.results_file(exp, profile.name)
    provenance.write_json_atomically(out, document)
    return out
