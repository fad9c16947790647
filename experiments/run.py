#!/usr/bin/python3
"""The experiment harness's command line.

  run.py validate   [CONFIG ...]                 check experiment configs (and, by default,
                                                 every scene in configs/scenes/)
  run.py references [CONFIG ...] [--force]       render missing or stale references
  run.py run        [CONFIG ...]                 run experiments -> results/<paper>/<figure>.json
  run.py tables                                  results -> results/tables/<paper>.{md,csv,tex}
  run.py plots                                   results -> results/plots/<paper>/*.png
  run.py check      [CONFIG ...]                 CI: fail when an error exceeds its threshold
  run.py check-results [CONFIG ...]              list results that HEAD's renderer would not
                                                 regenerate (their fingerprints differ)
  run.py calibrate  CONFIG [--spp N ...]         propose thresholds from the results file
  run.py reproduce                               references, run, tables and plots
  run.py overhead                                each experiment's time outside render loops
  run.py report [--only ID ...] [--out DIR]      the results page, results/report/index.html
  run.py matrix-configs [--check]                the cross-paper matrix's experiments,
                                                 configs/experiments/matrix/*.json, from the
                                                 renderer's registry and configs/matrix.json
                                                 (--check: list those that differ; exit 1)
  run.py matrix                                  its results -> results/tables/matrix.*, the
                                                 heat map and the measured part of
                                                 results/matrix/analysis.md

The units of work of the workflow engine (experiments/Snakefile; harness/workflow.py):
  run.py render-one      CONFIG --run T/B_seedN.exr  one render, its record beside it
  run.py matched         CONFIG                      the equal-time budgets after phase one
  run.py assemble        CONFIG                      the records -> results/<paper>/<figure>.json
  run.py reference-half  CONFIG --half 0|1 [--threads N] [--if-needed]
  run.py reference-merge CONFIG --stamp FILE         the halves -> the reference, or a copy

CONFIG defaults to every configs/experiments/<paper>/<figure>.json. --profile quick|full
(default quick, or $PROFILE). Exit status: 0 done, 1 a step failed (or a threshold), 2 bad
input (one message naming the JSON pointer)."""
import argparse
import functools
import os
import sys
from collections.abc import Callable
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from harness import (config, experiment, fingerprints, jobs, matrix_configs,  # noqa: E402
                     matrix_tables, paths, references, renders, results, tables, thresholds,
                     workflow)
from harness.config import Experiment  # noqa: E402
from harness.errors import ConfigError, HarnessFailure, SceneRejected  # noqa: E402


def load_configs(files: list[Path]) -> list[Experiment]:
    files = files or paths.all_experiment_configs()
    return [config.load(f) for f in files]


def report_skipped(what: Path, rejection: SceneRejected) -> None:
    print(f"{paths.relative(what)}: skipped, an asset is absent ({rejection.message})")


def validate_scenes() -> None:
    """`renderer check` on every configs/scenes/*.json. A scene whose asset is absent is
    skipped with a message, unless REQUIRE_ASSETS=1 (CI has ../shared beside the checkout)."""
    for scene in sorted(paths.SCENES.glob("*.json")):
        try:
            renders.check([scene])
        except SceneRejected as e:
            if not e.skippable:
                raise
            report_skipped(scene, e)
            continue
        print(f"{paths.relative(scene)}: valid")


def validate_experiment(exp: Experiment) -> None:
    """The scene documents of every technique and of the reference, in both profiles. An
    absent asset that may be skipped (see SceneRejected.skippable) is raised as it is."""
    for profile in exp.profiles.values():
        checks = [functools.partial(renders.check_technique, exp, profile, t)
                  for t in exp.techniques.values()]
        checks.append(functools.partial(renders.check_scene, exp, profile,
                                        exp.reference_integrator))
        for check in checks:
            try:
                check()
            except SceneRejected as e:
                if e.skippable:
                    raise
                raise ConfigError(exp.file, "", f"the scene does not validate: {e}") from None


def cmd_validate(args: argparse.Namespace) -> int:
    if not args.configs:
        validate_scenes()
    for exp in load_configs(args.configs):
        try:
            validate_experiment(exp)
        except SceneRejected as e:
            report_skipped(exp.file, e)
            continue
        print(f"{paths.relative(exp.file)}: valid")
    return 0


def cmd_references(args: argparse.Namespace) -> int:
    references.ensure(load_configs(args.configs), args.profile, force=args.force)
    return 0


def cmd_run(args: argparse.Namespace) -> int:
    experiments = load_configs(args.configs)
    for exp in experiments:
        validate_experiment(exp)
    for exp in experiments:
        out = experiment.run(exp, args.profile, args.jobs)
        print(f"[{exp.id}] wrote {paths.relative(out)}", flush=True)
    return 0


def cmd_tables(args: argparse.Namespace) -> int:
    for out in tables.write_all(args.profile) + matrix_tables.write_all(args.profile):
        print(f"wrote {paths.relative(out)}")
    return 0


def cmd_matrix_configs(args: argparse.Namespace) -> int:
    if args.check:
        differences = matrix_configs.differences(args.jobs)
        if differences is None:
            print("the matrix's configs were not checked: an asset is absent on this machine")
            return 0
        for line in differences:
            print(line)
        if differences:
            print("run `experiments/run.py matrix-configs` (or `make matrix`) and commit the "
                  "result with fresh matrix results", file=sys.stderr)
        return 1 if differences else 0
    for out in matrix_configs.write(args.jobs):
        print(f"wrote {paths.relative(out)}")
    return 0


def cmd_matrix(args: argparse.Namespace) -> int:
    from harness import matrix_plot
    rows = matrix_tables.rows(args.profile)
    if not rows:
        raise HarnessFailure(f"no {args.profile} results in results/matrix/: run the matrix "
                             "experiments first (`make matrix`)")
    for out in matrix_tables.write_all(args.profile) + matrix_plot.write_all(rows, args.profile):
        print(f"wrote {paths.relative(out)}")
    return 0


def cmd_plots(args: argparse.Namespace) -> int:
    import figures
    from harness import matrix_plot, plots
    written = plots.write_all(args.profile) + figures.write_all(args.profile)
    written += matrix_plot.write_all(matrix_tables.rows(args.profile), args.profile)
    for out in written:
        print(f"wrote {paths.relative(out)}")
    return 0


def cmd_check(args: argparse.Namespace) -> int:
    failed = 0
    for exp in load_configs(args.configs):
        if exp.thresholds is None:
            continue
        verdicts = thresholds.run_check(exp, args.jobs)
        print(f"[{exp.id}] thresholds ({exp.thresholds.profile} profile):")
        print(thresholds.format_verdicts(exp, verdicts), flush=True)
        failed += sum(not v.passed for v in verdicts)
    if failed:
        print(f"{failed} threshold(s) failed", file=sys.stderr)
    return 1 if failed else 0


def stale_reasons(exp: Experiment, profile_name: str, workers: int) -> list[str]:
    """Why the experiment's results file is not what HEAD would write (fixed-spp numbers):
    absent, made by another config, or a fingerprint render whose pixels differ."""
    results_file = exp.results_file(profile_name)
    if not results_file.exists():
        return ["no results file"]
    doc = results.read(results_file)
    if tables.config_changed(doc):
        return ["its config has changed"]
    return fingerprints.stale(exp, exp.profiles[profile_name], doc.fingerprints, workers)


def cmd_check_results(args: argparse.Namespace) -> int:
    stale = 0
    for exp in load_configs(args.configs):
        try:
            reasons = stale_reasons(exp, args.profile, args.jobs)
        except SceneRejected as e:
            if not e.skippable:
                raise
            report_skipped(exp.file, e)
            continue
        if reasons:
            stale += 1
            print(f"[{exp.id}] STALE: " + "; ".join(reasons), flush=True)
        else:
            print(f"[{exp.id}] current", flush=True)
    if stale:
        print(f"{stale} {args.profile}-profile results file(s) stale: run them again "
              "(`make run ONLY=...`)", file=sys.stderr)
    return 1 if stale else 0


def cmd_report(args: argparse.Namespace) -> int:
    from harness import report
    page = report.write(args.profile, args.jobs, args.only or None, args.out)
    print(f"wrote {paths.relative(page)}: open it in a browser (file:// works)")
    return 0


def cmd_overhead(args: argparse.Namespace) -> int:
    from harness import overhead
    print(overhead.report(args.profile))
    return 0


def cmd_calibrate(args: argparse.Namespace) -> int:
    exp = config.load(args.config)
    results_file = exp.results_file(args.profile)
    if not results_file.exists():
        raise HarnessFailure(f"no results at {paths.relative(results_file)}: run it first")
    doc = results.read(results_file)
    spps = args.spp or [doc.table.spp or max(doc.budgets.spp), max(doc.budgets.spp)]
    print(thresholds.format_block(thresholds.calibrate(exp, doc, spps)))
    return 0


def cmd_reproduce(args: argparse.Namespace) -> int:
    cmd_references(args)
    cmd_run(args)
    cmd_tables(args)
    cmd_plots(args)
    print(f"\n{args.profile} profile reproduced. Tables: {paths.relative(paths.TABLES)}/, "
          f"plots: {paths.relative(paths.PLOTS)}/, results: {paths.relative(paths.RESULTS)}/"
          "<paper>/<figure>.json")
    return 0


def workflow_unit(args: argparse.Namespace) -> tuple[Experiment, config.Profile]:
    """The experiment and profile a workflow job's subcommand works on."""
    exp = config.load(args.config)
    return exp, exp.profiles[args.profile]


def cmd_render_one(args: argparse.Namespace) -> int:
    workflow.render_one(*workflow_unit(args), args.run)
    return 0


def cmd_matched(args: argparse.Namespace) -> int:
    workflow.write_matched(*workflow_unit(args))
    return 0


def cmd_assemble(args: argparse.Namespace) -> int:
    exp, profile = workflow_unit(args)
    print(f"[{exp.id}] wrote {paths.relative(workflow.assemble(exp, profile))}", flush=True)
    return 0


def cmd_reference_half(args: argparse.Namespace) -> int:
    workflow.render_reference_half(*workflow_unit(args), args.half, args.threads, args.if_needed)
    return 0


def cmd_reference_merge(args: argparse.Namespace) -> int:
    exp, profile = workflow_unit(args)
    outcome = workflow.reference_merge(exp, profile, args.stamp)
    print(f"[references] {exp.id}/{profile.name}: {outcome}", flush=True)
    return 0


def positive_int(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text}")
    return value


def parser() -> argparse.ArgumentParser:
    """The command line; each subcommand's parser sets `func`, the cmd_ function it runs."""
    top = argparse.ArgumentParser(description=__doc__,
                                  formatter_class=argparse.RawDescriptionHelpFormatter)
    top.add_argument("--profile", choices=config.PROFILES,
                     default=os.environ.get("PROFILE") or "quick")
    top.add_argument("--jobs", type=positive_int, default=jobs.default_jobs(),
                     help="renders run in parallel (default: the number of cores)")
    sub = top.add_subparsers(dest="command", required=True)

    def on_configs(name: str, func: Callable[[argparse.Namespace], int],
                   force: bool = False) -> None:
        p = sub.add_parser(name)
        p.add_argument("configs", nargs="*", type=Path)
        if force:
            p.add_argument("--force", action="store_true", help="re-render current references")
        p.set_defaults(func=func)

    on_configs("validate", cmd_validate)
    on_configs("references", cmd_references, force=True)
    on_configs("run", cmd_run)
    on_configs("check", cmd_check)
    on_configs("check-results", cmd_check_results)
    on_configs("reproduce", cmd_reproduce, force=True)
    sub.add_parser("tables").set_defaults(func=cmd_tables)
    sub.add_parser("plots").set_defaults(func=cmd_plots)
    sub.add_parser("overhead").set_defaults(func=cmd_overhead)
    p = sub.add_parser("matrix-configs")
    p.add_argument("--check", action="store_true",
                   help="list the configs that differ from what they would be; write nothing")
    p.set_defaults(func=cmd_matrix_configs)
    sub.add_parser("matrix").set_defaults(func=cmd_matrix)
    p = sub.add_parser("report")
    p.add_argument("--only", nargs="*", help="experiment ids (<paper>/<figure>) to include")
    p.add_argument("--out", type=Path, help="the page's folder (default results/report/)")
    p.set_defaults(func=cmd_report)
    p = sub.add_parser("render-one")
    p.add_argument("config", type=Path)
    p.add_argument("--run", required=True, help="the render, <technique>/<budget>_seed<n>.exr")
    p.set_defaults(func=cmd_render_one)
    for name, func in (("matched", cmd_matched), ("assemble", cmd_assemble)):
        sub.add_parser(name).add_argument("config", type=Path)
        sub.choices[name].set_defaults(func=func)
    p = sub.add_parser("reference-merge")
    p.add_argument("config", type=Path)
    p.add_argument("--stamp", type=Path, required=True,
                   help="written once the reference is current: its hash")
    p.set_defaults(func=cmd_reference_merge)
    p = sub.add_parser("reference-half")
    p.add_argument("config", type=Path)
    p.add_argument("--half", type=int, choices=[0, 1], required=True)
    p.add_argument("--threads", type=positive_int, default=jobs.default_jobs())
    p.add_argument("--if-needed", action="store_true",
                   help="only if reference-merge will need it; else leave empty files")
    p.set_defaults(func=cmd_reference_half)
    p = sub.add_parser("calibrate")
    p.add_argument("config", type=Path)
    p.add_argument("--spp", type=int, nargs="*", help="budgets to set thresholds at")
    p.set_defaults(func=cmd_calibrate)
    return top


def main() -> int:
    args = parser().parse_args()
    if args.profile not in config.PROFILES:
        print(f"error: unknown profile {args.profile}", file=sys.stderr)
        return 2
    try:
        return args.func(args)
    except ConfigError as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    except HarnessFailure as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("\ninterrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
