"""One experiment end to end: expand into renders (techniques × budgets × seeds), run them in
parallel, measure each against the reference, summarise over seeds, fit convergence slopes.

Equal-sample budgets are deterministic (bit-identical pixels for a seed); equal-time budgets
depend on the machine's speed, so CI thresholds only ever use equal-sample budgets.

A fixed-spp technique (one that cannot honour --time-limit) has no equal-time runs of its
own. With a profile's matched_spp, its measured render time at each of those spp becomes an
equal-time budget: once the first phase (every equal-sample and equal-time run) is done, a
second phase renders every time-capable technique with that time limit, and the fixed-spp
technique's runs at that spp are entered again as equal-time records at that budget."""
import dataclasses
import datetime
import functools
import math
import resource
import shutil
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from . import (config, fingerprints, jobs, paths, provenance, references, render_server, renders,
               stats)
from .config import Experiment, Profile
from .errors import HarnessFailure
from .records import (SPP, TIME, MatchedBudget, OriginalBudget, Run, RunRecord, SummaryEntry,
                      TechniqueBudget, group_by_key)
from .results import (Budgets, ConfigFile, LineFit, Provenance, ReferenceEntry, Results,
                      TableBudgets, TechniqueEntry, TechniqueSlopes)


def expand(exp: Experiment, profile: Profile,
           only: set[TechniqueBudget] | None = None) -> list[Run]:
    """Every run of the profile, or only those whose technique and budget are in `only`.
    Interleaved (seed, then budget, then technique innermost) so that the techniques share
    the machine's load pattern: consecutive runs of one budget differ only in technique.
    Fixed-spp techniques have no equal-time runs (see matched_runs)."""
    budgets = [(SPP, s) for s in profile.spp] + [(TIME, s) for s in profile.seconds]
    runs = []
    for seed in range(profile.seeds):
        for kind, budget in budgets:
            for name, technique in exp.techniques.items():
                if kind == TIME and technique.fixed_spp:
                    continue
                run = Run(name, kind, budget, seed)
                if only is None or run.key in only:
                    runs.append(run)
    return runs


def matched_seconds(times: list[float]) -> float:
    """The equal-time budget matched to render times over seeds: their mean, to 1 ms, at
    least 1 ms (the renderer takes a time limit of 0 as none)."""
    return max(round(math.fsum(times) / len(times), 3), 0.001)


def matched_budgets(exp: Experiment, profile: Profile,
                    records: list[RunRecord]) -> list[MatchedBudget]:
    """For each fixed-spp technique and each of the profile's matched_spp, the equal-time
    budget of its measured render times at that spp."""
    groups = group_by_key(records)
    matched = []
    for name, technique in exp.techniques.items():
        if not technique.sets_budgets:
            continue
        spp_of: dict[float, int] = {}
        for spp in profile.matched_spp:
            times = [r.time for r in groups.get(TechniqueBudget(name, SPP, spp), [])]
            if not times:
                raise HarnessFailure(f"{exp.id}: no {spp}-spp runs of {name} to match time to")
            seconds = matched_seconds(times)
            if seconds in spp_of:
                raise HarnessFailure(
                    f"{exp.id}: {name} took {seconds:g} s (to 1 ms) at both {spp_of[seconds]} "
                    f"and {spp} spp, so the two equal-time budgets would be one; render larger "
                    "images or drop one of matched_spp")
            spp_of[seconds] = spp
            matched.append(MatchedBudget(name, spp, seconds))
    return matched


def matched_runs(exp: Experiment, profile: Profile, matched: list[MatchedBudget],
                 records: list[RunRecord]) -> list[Run]:
    """The runs of every time-capable technique at the matched budgets, every seed, except
    those `records` already hold (a matched time equal to one of the profile's seconds
    budgets is the same budget). Interleaved as in expand."""
    done = {r.key for r in records}
    baselines = {exp.baseline, exp.also_baseline}
    rendered: dict[float, set[str]] = {}  # budget -> the techniques rendered at it
    for m in matched:
        everyone = exp.techniques[m.technique].equal_time != config.BASELINE_ONLY
        rendered.setdefault(m.seconds, set()).update(
            name for name, t in exp.techniques.items()
            if not t.fixed_spp and (everyone or name in baselines))
    runs = []
    for seed in range(profile.seeds):
        for budget in sorted(rendered):
            for name in exp.techniques:
                run = Run(name, TIME, budget, seed)
                if name in rendered[budget] and run.key not in done:
                    runs.append(run)
    return runs


def matched_duplicates(exp: Experiment, matched: list[MatchedBudget],
                       records: list[RunRecord]) -> list[RunRecord]:
    """Each fixed-spp technique's records at a matched spp entered again as equal-time records
    at the matched seconds (the same renders, files and metrics), so that summaries and gains
    at equal time need nothing special. duplicate_of marks them for slopes and plots. A
    time-capable technique that set a budget (sets_time) was rendered at it, and keeps those
    runs."""
    groups = group_by_key(records)
    return [dataclasses.replace(r, kind=TIME, budget=m.seconds,
                                duplicate_of=OriginalBudget(SPP, m.spp))
            for m in matched if exp.techniques[m.technique].fixed_spp
            for r in groups.get(TechniqueBudget(m.technique, SPP, m.spp), [])]


def parallel_jobs(profile: Profile, requested: int) -> int:
    """Renders at once: never more threads in all than cores, so every render has its
    threads' cores to itself and an equal-time budget means equal compute."""
    return max(1, min(requested, jobs.default_jobs() // profile.threads_per_job))


def _estimated_cost(run: Run, profile: Profile) -> float:
    """Seconds, roughly (1 µs per sample and a fixed process cost), for the ETA only."""
    if run.kind == TIME:
        return run.budget + 0.3
    return run.budget * profile.resolution[0] * profile.resolution[1] * 1e-6 + 0.3


def render_run(exp: Experiment, profile: Profile, run: Run, out_dir: Path,
               reference_file: Path) -> RunRecord:
    """Renders one run into out_dir and measures it against the reference: the unit of work
    whichever engine schedules the runs."""
    out = out_dir / run.file_name()
    out.parent.mkdir(parents=True, exist_ok=True)
    technique = exp.techniques[run.technique]
    if run.kind == SPP:
        renders.render_at_spp(exp, profile, technique, out, run.seed, int(run.budget),
                              threads=profile.threads_per_job)
    else:
        renders.render_technique(exp, profile, technique, out, run.seed, seconds=run.budget,
                                 threads=profile.threads_per_job)
    m = renders.compare(out, reference_file, exp.relmse_reject)
    # A sweep of samples per primary ray counts its samples, not its one pixel sample.
    spp = m.spp * int(run.budget) if technique.samples_at else m.spp
    return RunRecord(run.technique, run.kind, run.budget, run.seed, spp=spp, time=m.time,
                     file=paths.relative(out), metrics=m.metrics)


def execute(exp: Experiment, profile: Profile, runs: list[Run], out_dir: Path,
            reference_file: Path, workers: int, phase: str | None = None) -> list[RunRecord]:
    """Renders and measures every run; returns one record per run, in run order."""
    for run in runs:
        if run.kind == TIME and exp.techniques[run.technique].fixed_spp:
            raise ValueError(f"{run.technique} renders a fixed spp; it takes no time limit")
    work = [functools.partial(render_run, exp, profile, r, out_dir, reference_file) for r in runs]
    costs = [_estimated_cost(r, profile) for r in runs]
    label = f"{exp.id} {profile.name}" + (f" {phase}" if phase else "")
    return jobs.run_parallel(label, work, costs, parallel_jobs(profile, workers))


def _column(group: list[RunRecord], metric: str) -> list[float] | None:
    values = [v for r in group if (v := r.metrics[metric]) is not None]
    return values if len(values) == len(group) else None


def _efficiency_columns(group: list[RunRecord], metric: str) -> list[list[float]] | None:
    """The (time, error) columns of efficiency 1/(T·error)."""
    error = _column(group, config.EFFICIENCY_OF[metric])
    return None if error is None else [[r.time for r in group], error]


def _metric_summary(group: list[RunRecord], metric: str) -> stats.MetricSummary | None:
    """Mean and interval of a metric over seeds. An efficiency is 1/(mean T · mean error)
    with a paired delta-method interval, not a mean of per-seed efficiencies."""
    if metric in config.EFFICIENCY_OF:
        columns = _efficiency_columns(group, metric)
        if columns is None or min(sum(c) for c in columns) <= 0:
            return None
        return stats.efficiency(*columns)
    values = _column(group, metric)
    return None if values is None else stats.estimate(values)


def _gain(base_group: list[RunRecord], group: list[RunRecord], metric: str) -> stats.Gain | None:
    """The technique's gain over the baseline at one budget, paired by seed; None when it is
    undefined (a zero error, a missing metric)."""
    if [r.seed for r in base_group] != [r.seed for r in group]:
        raise ValueError("the baseline and the technique were run with different seeds")
    try:
        if metric in config.EFFICIENCY_OF:
            bt, tt = _efficiency_columns(base_group, metric), _efficiency_columns(group, metric)
            if bt is None or tt is None:
                return None
            return stats.mean_power_product(bt + tt, (1, 1, -1, -1))
        b, t = _column(base_group, metric), _column(group, metric)
        if b is None or t is None:
            return None
        return stats.gain(b, t, config.METRICS[metric])
    except ValueError:  # a zero mean
        return None


def summarise(exp: Experiment, records: list[RunRecord]) -> list[SummaryEntry]:
    """Per technique and budget: each metric's mean and 95 % interval over seeds, the spp and
    time reached, and the gain over the baseline (and the also_baseline) at the same budget.
    Duplicated records (see matched_duplicates) make a fixed-spp technique's entry at a
    matched time budget."""
    groups = group_by_key(sorted(records, key=lambda r: r.seed))

    def gains(baseline: str, key: TechniqueBudget, group: list[RunRecord]) -> dict[str, Any]:
        base_group = groups.get(TechniqueBudget(baseline, key.kind, key.budget))
        if key.technique == baseline or not base_group:
            return {}
        return {m: _gain(base_group, group, m) for m in exp.metrics
                if m not in config.SIGNED_METRICS}

    summary = []
    for key, group in groups.items():
        summary.append(SummaryEntry(
            key.technique, key.kind, key.budget,
            spp=stats.estimate([r.spp for r in group]),
            time=stats.estimate([r.time for r in group]),
            metrics={m: _metric_summary(group, m) for m in exp.metrics},
            gain=gains(exp.baseline, key, group),
            duplicate_of=group[0].duplicate_of,
            also_gain=gains(exp.also_baseline, key, group) if exp.also_baseline else None))
    return summary


def budget_times(runs: list[RunRecord]) -> dict[tuple[str, float], float]:
    """The mean render time of each budget (kind, budget) of one technique's runs."""
    times: dict[tuple[str, float], list[float]] = {}
    for r in runs:
        times.setdefault((r.kind, r.budget), []).append(r.time)
    return {budget: math.fsum(t) / len(t) for budget, t in times.items()}


def common_time_range(runs: dict[str, list[RunRecord]]) -> tuple[float, float] | None:
    """The render times every technique covers, by the mean times of its budgets: from the
    latest first budget to the earliest last one; None when they share no range."""
    covered = [(min(t.values()), max(t.values()))
               for t in (budget_times(rs) for rs in runs.values() if rs)]
    low, high = max(c[0] for c in covered), min(c[1] for c in covered)
    return (low, high) if low < high else None


def in_time_range(runs: list[RunRecord], window: tuple[float, float]) -> list[RunRecord]:
    """The runs of the budgets whose mean time lies in `window`: whole budgets, every seed, so
    that a window's edge does not keep a budget's fast seeds and drop its slow ones."""
    times = budget_times(runs)
    return [r for r in runs if window[0] <= times[(r.kind, r.budget)] <= window[1]]


def slopes(exp: Experiment, records: list[RunRecord],
           scratch_dir: str | Path) -> dict[str, TechniqueSlopes]:
    """Least-squares slope of log(primary error) against log(spp) and log(time), over every
    run of each technique (all seeds and budgets), or with `slope_time_range: common` over the
    runs in the common time range, from `metrics slope`. A render entered twice
    (matched_duplicates) counts once."""
    runs = {t: [r for r in records if r.technique == t and r.duplicate_of is None]
            for t in exp.techniques}
    common = exp.slope_time_range == "common"
    window = common_time_range(runs) if common else None
    if common and window is None:
        print(f"[{exp.id}] warning: the techniques' render times share no range; slopes over "
              "every run", file=sys.stderr)
    out = {}
    for technique, rs in runs.items():
        if window:
            rs = in_time_range(rs, window)
        points = [(r.spp, r.time, r.metrics[exp.primary_metric]) for r in rs]
        errors = [e for _, _, e in points if e is not None and e > 0]
        if len({spp for spp, _, _ in points}) >= 2 and len(errors) == len(points):
            fit = renders.slope([{"spp": spp, "time": time, "error": error}
                                 for (spp, time, _), error in zip(points, errors)],
                                Path(scratch_dir) / f"{technique}.json")
            out[technique] = TechniqueSlopes(LineFit(**fit["vs_spp"]), LineFit(**fit["vs_time"]),
                                             windowed=common, time_range=window)
    return out


def smallest_rmse(records: list[RunRecord]) -> float:
    """The smallest RMSE of the renders (`metrics compare` computes one for every render)."""
    values = [r.metrics["rmse"] for r in records]
    return min(v for v in values if v is not None) if None not in values else float("nan")


def children_cpu_seconds() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def results_document(exp: Experiment, profile: Profile, records: list[RunRecord],
                     matched: list[MatchedBudget], entry: dict[str, Any], reference_file: Path,
                     engine: dict[str, Any]) -> Results:
    """The results of a finished profile from its records (in run order, matched duplicates
    last), whichever engine rendered them; refuses a too-noisy reference. `engine` holds what
    only the engine knows: its name ("engine"), started, wall_seconds, cpu_seconds,
    parallel_jobs, and optionally the hosts its jobs ran on."""
    ratio = references.check_noise(exp, profile, entry, smallest_rmse(records))
    with tempfile.TemporaryDirectory() as scratch:
        fitted = slopes(exp, records, scratch)
    return Results(
        experiment=exp.id,
        profile=profile.name,
        description=exp.description,
        config=ConfigFile(paths.relative(exp.file), exp.profile_sha256[profile.name]),
        scene=paths.relative(exp.scene),
        set=exp.overrides,
        techniques={t.name: TechniqueEntry(t.label, t.integrator, t.fixed_spp,
                                           samples_at=t.samples_at or None,
                                           set=t.overrides or None,
                                           equal_time=None if t.equal_time is True
                                           else t.equal_time,
                                           sets_time=True if t.sets_time else None)
                    for t in exp.techniques.values()},
        baseline=exp.baseline,
        also_baseline=exp.also_baseline,
        metrics=exp.metrics,
        relmse_reject=exp.relmse_reject,
        resolution=profile.resolution,
        seeds=list(range(profile.seeds)),
        budgets=Budgets(profile.spp, profile.seconds, profile.matched_spp),
        table=TableBudgets(profile.table_spp, profile.table_seconds),
        matched=matched,
        crop=profile.crop,
        reference=ReferenceEntry(paths.relative(reference_file), entry["sha256"],
                                 entry["integrator"], entry["spp"], entry["noise_rmse"],
                                 entry["noise_sigma_over_mu"], ratio),
        paper=exp.paper,
        provenance=Provenance(
            git_commit=provenance.git_commit(),
            git_dirty=provenance.git_dirty(),
            engine=engine["engine"],
            started=engine["started"],
            wall_seconds=engine["wall_seconds"],
            cpu_seconds=engine["cpu_seconds"],
            machine=provenance.machine(),
            parallel_jobs=engine["parallel_jobs"],
            threads_per_job=profile.threads_per_job,
            command=" ".join(sys.argv),
            hosts=engine.get("hosts")),
        fingerprints=fingerprints.record(exp, profile, records, engine["parallel_jobs"]),
        summary=summarise(exp, records),
        slopes=fitted,
        runs=records,
    )


def run(exp: Experiment, profile_name: str, workers: int) -> Path:
    """Runs the whole profile and writes results/<paper>/<figure>.json. Returns its path."""
    profile = exp.profiles[profile_name]
    entry, reference_file = references.lookup(exp, profile)
    started_at = datetime.datetime.now().astimezone().isoformat(timespec="seconds")
    started = time.monotonic()
    cpu_started = children_cpu_seconds()
    out_dir = paths.RENDERS / profile.name / exp.id
    shutil.rmtree(out_dir, ignore_errors=True)
    try:
        records = execute(exp, profile, expand(exp, profile), out_dir, reference_file, workers)
        matched = matched_budgets(exp, profile, records)
        if matched:
            runs = matched_runs(exp, profile, matched, records)
            if runs:
                records += execute(exp, profile, runs, out_dir, reference_file, workers,
                                   phase="matched time")
            records += matched_duplicates(exp, matched, records)
    finally:
        render_server.close_all()  # their CPU time counts once they have exited
    document = results_document(exp, profile, records, matched, entry, reference_file, {
        "engine": "harness",
        "started": started_at,
        "wall_seconds": round(time.monotonic() - started, 2),
        # CPU time of every render and measurement (user + system), the cost to budget when
        # the profile is split into chunks.
        "cpu_seconds": round(children_cpu_seconds() - cpu_started, 1),
        "parallel_jobs": parallel_jobs(profile, workers)})
    out = exp.results_file(profile.name)
    provenance.write_json_atomically(out, document.to_json())
    return out
