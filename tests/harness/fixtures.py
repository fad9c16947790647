"""Shared test data: a minimal valid experiment config and a synthetic results document."""
import copy
import json
import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "experiments"))

from harness import config, paths, records, results, stats  # noqa: E402

VALID = {
    "description": "test experiment",
    "scene": "configs/scenes/cornell_spheres.json",
    "set": {"/render/sampler": "independent"},
    "techniques": {
        "base": {"integrator": {"type": "path"}},
        "better": {"label": "better", "integrator": {"type": "path_mis"}},
    },
    "baseline": "base",
    "metrics": ["sigma_over_mu", "p_eff"],
    "reference": {"integrator": {"type": "path_mis"}},
    "profiles": {
        name: {"resolution": [8, 8], "spp": [4, 16], "seconds": [0.5], "seeds": 5,
               "reference_spp": 64, "table": {"spp": 16, "seconds": 0.5}}
        for name in ("quick", "full")
    },
    "paper": {"source": "a paper", "metric": "sigma_over_mu", "spp": 16,
              "values": {"base": 1.0, "better": 0.5}},
    "thresholds": {"profile": "quick", "method": "by hand",
                   "checks": [{"technique": "better", "spp": 16, "max_error": 0.3,
                               "min_gain": 2.0}]},
}


def valid():
    return copy.deepcopy(VALID)


def tiny_matched():
    """A config small enough to run end to end in a few seconds with the real renderer: 32×32
    pixels, 2 and 8 spp, 5 seeds; `path_mis` is marked fixed-spp and matched at 8 spp. No
    seconds budget: on a fast machine its renders could get so many samples that the
    reference's noise check would refuse them; matched times scale with the machine."""
    return {
        "description": "Matched equal time, end to end.",
        "scene": "configs/scenes/cornell_spheres.json",
        "set": {"/render/sampler": "independent"},
        "techniques": {"path": {"integrator": {"type": "path"}},
                       "path_mis": {"integrator": {"type": "path_mis"}, "fixed_spp": True}},
        "baseline": "path",
        "metrics": ["sigma_over_mu", "p_eff"],
        "reference": {"integrator": {"type": "path_mis"}},
        "profiles": {name: {"resolution": [32, 32], "spp": [2, 8], "seconds": [],
                            "matched_spp": [8], "seeds": 5, "reference_spp": 1024,
                            "table": {"spp": 8, "seconds": "matched"}}
                     for name in ("quick", "full")},
    }


def write_config(document, figure="figure"):
    """Writes `document` (a dict, or raw text or bytes) as <tmp>/paper/<figure>.json; returns
    its path."""
    directory = Path(tempfile.mkdtemp()) / "paper"
    directory.mkdir()
    file = directory / f"{figure}.json"
    if isinstance(document, bytes):
        file.write_bytes(document)
    else:
        file.write_text(document if isinstance(document, str) else json.dumps(document))
    return file


def load_config(document, figure="figure"):
    """Writes `document` as write_config does and loads it."""
    return config.load(write_config(document, figure))


def from_root(file):
    """A path as a variant's "variant_of" names it: relative to the repository root."""
    return os.path.relpath(file, paths.ROOT)


def summary_entry(technique, kind, budget, metric_values, gain=None):
    """A summary entry with σ/µ over seeds `metric_values` and `gain` (a stats.Gain) over the
    baseline in it."""
    return records.SummaryEntry(
        technique, kind, budget, spp=stats.estimate([budget] * 2),
        time=stats.estimate([1.0, 1.0]),
        metrics={"sigma_over_mu": stats.estimate(metric_values), "p_eff": None},
        gain={"sigma_over_mu": gain} if gain else {})


def results_document(**fields):
    """A complete results file's contents (harness.results.Results) with placeholder values,
    `fields` replacing them: what tables and calibrate read, without running anything."""
    defaults = dict(
        experiment="paper/fig5", profile="quick", description="synthetic",
        config=results.ConfigFile("configs/experiments/core/path_vs_mis.json", "0" * 64),
        scene="configs/scenes/cornell_spheres.json", set={},
        techniques={"base": results.TechniqueEntry("base", {"type": "path"}),
                    "better": results.TechniqueEntry("better", {"type": "path_mis"})},
        baseline="base", metrics=["sigma_over_mu", "p_eff"], relmse_reject=0.0,
        resolution=(8, 8), seeds=[0, 1, 2, 3, 4],
        budgets=results.Budgets([16], []), table=results.TableBudgets(16, None), crop=None,
        reference=results.ReferenceEntry("reference/paper/fig5.quick.exr", "0" * 64,
                                         {"type": "path_mis"}, 1024, 0.001, 0.01, 0.05),
        paper=[],
        provenance=results.Provenance(git_commit=None, git_dirty=False,
                                      started="2026-11-22T10:00", wall_seconds=1.0,
                                      machine={}, parallel_jobs=2, threads_per_job=1,
                                      command="run.py run"),
        summary=[], slopes={}, runs=[])
    return results.Results(**{**defaults, **fields})
