"""Fixed-spp techniques and equal time matched to their render times: the budgets, the
second phase of runs, the duplicated records (summarised with gains, counted once by slopes),
then a small run end to end with the real renderer, `path_mis` standing in for a fixed-spp
technique, through summary, slopes, tables and plots."""
import contextlib
import csv
import dataclasses
import io
import json
import tempfile
import unittest
from pathlib import Path
from unittest import mock

from fixtures import load_config, results_document, summary_entry, tiny_matched, valid
from harness import (experiment, fingerprints, jobs, paths, references, stats, tables,
                     thresholds)
from harness.errors import ConfigError, HarnessFailure
from harness.records import (MatchedBudget, OriginalBudget, Run, RunRecord, TechniqueBudget,
                             index_by_key, to_json)
from harness.results import Results, TableBudgets, TechniqueEntry

SEEDS = range(5)


def fixed_config(**profile):
    """The fixture config with "better" fixed-spp, matched at 4 and 16 spp."""
    doc = valid()
    doc["techniques"]["better"]["fixed_spp"] = True
    doc["profiles"]["quick"].update(matched_spp=[4, 16], **profile)
    return load_config(doc)


def record(technique, kind, budget, seed, time, error):
    return RunRecord(technique, kind, budget, seed, spp=budget if kind == "spp" else 7,
                     time=time, file=f"renders/{technique}/{budget}_seed{seed}.exr",
                     metrics={"sigma_over_mu": error, "tvi_err": error, "rmse": error})


def fixed_records(times4, times16):
    """The first phase: both techniques at 4 and 16 spp, the baseline at 0.5 s."""
    out = []
    for seed in SEEDS:
        out += [record("base", "spp", 4, seed, 0.002, 1.0 + 0.01 * seed),
                record("better", "spp", 4, seed, times4[seed], 0.5 + 0.01 * seed),
                record("base", "spp", 16, seed, 0.008, 0.5 + 0.01 * seed),
                record("better", "spp", 16, seed, times16[seed], 0.2 + 0.01 * seed),
                record("base", "time", 0.5, seed, 0.5, 0.1 + 0.01 * seed)]
    return out


class AlsoBaselineTest(unittest.TestCase):
    def test_every_technique_gets_a_gain_over_the_second_baseline_too(self):
        doc = valid()
        doc["techniques"]["third"] = {"integrator": {"type": "path_mis"}}
        doc["also_baseline"] = "better"
        exp = load_config(doc)
        errors = {"base": 1.0, "better": 0.5, "third": 0.25}
        records = [record(t, "spp", 16, seed, 0.01, e * (1 + 0.01 * seed))
                   for t, e in errors.items() for seed in SEEDS]
        summary = index_by_key(experiment.summarise(exp, records))
        third = summary[TechniqueBudget("third", "spp", 16)]
        self.assertAlmostEqual(third.gain["sigma_over_mu"].value, 4.0)
        self.assertAlmostEqual(third.also_gain["sigma_over_mu"].value, 2.0)
        self.assertEqual(summary[TechniqueBudget("better", "spp", 16)].also_gain, {})
        self.assertAlmostEqual(
            summary[TechniqueBudget("base", "spp", 16)].also_gain["sigma_over_mu"].value, 0.5)
        without = experiment.summarise(load_config(valid()), records[:10])
        self.assertTrue(all(s.also_gain is None for s in without))


class SignedMetricTest(unittest.TestCase):
    def test_a_bias_is_summarised_over_seeds_without_a_gain(self):
        doc = valid()
        doc["metrics"] = ["sigma_over_mu", "relative_bias"]
        exp = load_config(doc)
        records = [dataclasses.replace(r, metrics={**r.metrics, "relative_bias": bias})
                   for t, bias in (("base", 0.0), ("better", -0.02))
                   for r in [record(t, "spp", 16, seed, 0.01, 0.5 + 0.01 * seed)
                             for seed in SEEDS]]
        summary = index_by_key(experiment.summarise(exp, records))
        better = summary[TechniqueBudget("better", "spp", 16)]
        self.assertAlmostEqual(better.metrics["relative_bias"].mean, -0.02)
        self.assertIn("sigma_over_mu", better.gain)
        self.assertNotIn("relative_bias", better.gain)


class MatchedBudgetsTest(unittest.TestCase):
    def test_fixed_spp_techniques_get_no_time_limit(self):
        exp = fixed_config()
        runs = experiment.expand(exp, exp.profiles["quick"])
        self.assertEqual(len(runs), 5 * (2 * 2 + 1))  # seeds x (2 spp x 2 techniques + base)
        self.assertEqual({(r.technique, r.budget) for r in runs if r.kind == "time"},
                         {("base", 0.5)})
        with self.assertRaises(ValueError):
            experiment.execute(exp, exp.profiles["quick"],
                               [Run("better", "time", 0.5, 0)], Path("unused"),
                               Path("unused"), 1)

    def test_mean_time_over_seeds_to_one_millisecond_never_zero(self):
        exp = fixed_config()
        records = fixed_records([1e-5] * 5, [0.0101, 0.0119, 0.011, 0.0112, 0.0108])
        self.assertEqual(experiment.matched_budgets(exp, exp.profiles["quick"], records),
                         [MatchedBudget("better", 4, 0.001), MatchedBudget("better", 16, 0.011)])
        self.assertEqual(experiment.matched_seconds([0.01234, 0.01236]), 0.012)

    def test_a_technique_without_equal_time_sets_no_budget(self):
        doc = valid()
        doc["techniques"]["better"].update(fixed_spp=True, equal_time=False)
        doc["techniques"]["other"] = {"integrator": {"type": "path"}, "fixed_spp": True}
        doc["profiles"]["quick"].update(matched_spp=[4])
        exp = load_config(doc)
        records = [record(t, "spp", 4, s, 0.5, 1.0) for t in ("better", "other")
                   for s in SEEDS]
        self.assertEqual(experiment.matched_budgets(exp, exp.profiles["quick"], records),
                         [MatchedBudget("other", 4, 0.5)])

    def test_a_time_capable_technique_that_sets_time_is_rendered_at_its_own_budget(self):
        # the cross-paper matrix: the baseline's time at 4 spp is every technique's budget
        doc = valid()
        doc["techniques"]["base"]["sets_time"] = True
        doc["techniques"]["fixed"] = {"integrator": {"type": "path"}, "fixed_spp": True,
                                      "equal_time": "baseline"}
        doc["profiles"]["quick"].update(matched_spp=[4])
        exp = load_config(doc)
        records = [record(t, "spp", 4, s, time, 1.0) for t, time in
                   (("base", 0.25), ("better", 0.5), ("fixed", 0.75)) for s in SEEDS]
        matched = experiment.matched_budgets(exp, exp.profiles["quick"], records)
        self.assertEqual(matched, [MatchedBudget("base", 4, 0.25),
                                   MatchedBudget("fixed", 4, 0.75)])
        runs = experiment.matched_runs(exp, exp.profiles["quick"], matched, records)
        # at the baseline's budget every time-capable technique, itself included; at the
        # "baseline"-only technique's budget only the baseline
        self.assertEqual({(r.technique, r.budget) for r in runs},
                         {("base", 0.25), ("better", 0.25), ("base", 0.75)})
        self.assertEqual(len(runs), 3 * len(SEEDS))
        timed = [record(r.technique, "time", r.budget, r.seed, r.budget, 0.9) for r in runs]
        copies = experiment.matched_duplicates(exp, matched, records + timed)
        # the fixed-spp technique's renders stand for it at its time; the baseline keeps the
        # renders it made at its own budget
        self.assertEqual({(c.technique, c.budget) for c in copies}, {("fixed", 0.75)})

    def test_sets_time_and_a_baseline_only_budget_are_checked(self):
        doc = valid()
        doc["techniques"]["better"].update(fixed_spp=True, sets_time=True)
        with self.assertRaises(ConfigError) as caught:
            load_config(doc)
        self.assertEqual(caught.exception.pointer, "/techniques/better/sets_time")
        doc = valid()
        doc["techniques"]["better"].update(fixed_spp=True, equal_time="base")
        with self.assertRaises(ConfigError) as caught:
            load_config(doc)
        self.assertEqual(caught.exception.pointer, "/techniques/better/equal_time")

    def test_slopes_can_be_fitted_over_the_time_range_every_technique_covers(self):
        # budgets by their mean times over seeds: fixed 4 spp 0.55 s, 16 spp 2 s (its seeds
        # 1.8 and 2.2 s); timed 1 s and 4 s
        runs = {"fixed": [record("fixed", "spp", 4, 0, 0.5, 1.0),
                          record("fixed", "spp", 4, 1, 0.6, 1.0),
                          record("fixed", "spp", 16, 0, 1.8, 0.5),
                          record("fixed", "spp", 16, 1, 2.2, 0.5)],
                "timed": [record("timed", "time", 1.0, 0, 1.0, 1.0),
                          record("timed", "time", 4.0, 0, 4.0, 0.4)]}
        window = experiment.common_time_range(runs)
        self.assertEqual(window, (1.0, 2.0))
        # whole budgets: 16 spp with both its seeds (one of them slower than the window's end)
        kept = experiment.in_time_range(runs["fixed"], window)
        self.assertEqual([(r.budget, r.seed) for r in kept], [(16, 0), (16, 1)])
        runs["timed"] = [record("timed", "time", 3.0, 0, 3.0, 1.0)]
        self.assertIsNone(experiment.common_time_range(runs))

    def test_second_phase_renders_the_time_capable_techniques_interleaved(self):
        exp = fixed_config()
        records = fixed_records([0.003] * 5, [0.011] * 5)
        matched = experiment.matched_budgets(exp, exp.profiles["quick"], records)
        runs = experiment.matched_runs(exp, exp.profiles["quick"], matched, records)
        self.assertEqual([(r.technique, r.kind, r.budget, r.seed) for r in runs],
                         [("base", "time", t, seed) for seed in SEEDS for t in (0.003, 0.011)])

    def test_a_matched_time_equal_to_a_seconds_budget_reuses_its_runs(self):
        exp = fixed_config()
        records = fixed_records([0.003] * 5, [0.5002] * 5)
        matched = experiment.matched_budgets(exp, exp.profiles["quick"], records)
        self.assertEqual(matched[1].seconds, 0.5)
        runs = experiment.matched_runs(exp, exp.profiles["quick"], matched, records)
        self.assertEqual({r.budget for r in runs}, {0.003})

    def test_two_spp_of_one_technique_with_the_same_time_are_refused(self):
        exp = fixed_config()
        with self.assertRaises(HarnessFailure) as caught:
            experiment.matched_budgets(exp, exp.profiles["quick"],
                                       fixed_records([0.0104] * 5, [0.0096] * 5))
        self.assertIn("at both 4 and 16 spp", str(caught.exception))

    def test_duplicates_are_summarised_with_a_gain_and_counted_once_by_slopes(self):
        exp = fixed_config()
        records = fixed_records([0.003] * 5, [0.011] * 5)
        matched = experiment.matched_budgets(exp, exp.profiles["quick"], records)
        records += [record("base", "time", m.seconds, seed, m.seconds, 0.4 + 0.01 * seed)
                    for seed in SEEDS for m in matched]
        duplicates = experiment.matched_duplicates(exp, matched, records)
        self.assertEqual(len(duplicates), 2 * 5)
        originals = [r for r in records if r.technique == "better" and r.budget == 16]
        copies = [r for r in duplicates if r.budget == 0.011]
        for original, copy in zip(originals, copies):
            self.assertEqual(copy, dataclasses.replace(
                original, kind="time", budget=0.011, duplicate_of=OriginalBudget("spp", 16)))
            self.assertEqual(to_json(copy), {**to_json(original), "kind": "time",
                                             "budget": 0.011,
                                             "duplicate_of": {"kind": "spp", "budget": 16}})
        summary = index_by_key(experiment.summarise(exp, records + duplicates))
        at_time = summary[TechniqueBudget("better", "time", 0.011)]
        at_spp = summary[TechniqueBudget("better", "spp", 16)]
        self.assertEqual(at_time.metrics, at_spp.metrics)
        self.assertEqual(at_time.duplicate_of, OriginalBudget("spp", 16))
        # base 0.4..0.44 against better 0.2..0.24 at 0.011 s: gain 0.42 / 0.22
        self.assertAlmostEqual(at_time.gain["sigma_over_mu"].value, 0.42 / 0.22)
        # Each technique's fit gets its points' count instead of a `metrics slope` call.
        def count(points, _):
            fit = {"intercept": 0.0, "n": len(points), "r2": 1.0, "slope": -0.5,
                   "slope_stderr": 0.0}
            return {"vs_spp": fit, "vs_time": fit}
        with mock.patch.object(experiment.renders, "slope", count):
            counted = experiment.slopes(exp, records + duplicates, "unused")
            self.assertEqual(counted, experiment.slopes(exp, records, "unused"))
        self.assertEqual(counted["better"].vs_spp.n, 2 * 5)


def _time_entry(technique, budget, values, gain=None, duplicate_of=None):
    e = summary_entry(technique, "time", budget, values, gain)
    return dataclasses.replace(e, duplicate_of=duplicate_of)


class MatchedTablesTest(unittest.TestCase):
    def document(self, seconds):
        base, better = [1.0, 1.1, 0.9, 1.05, 0.95], [0.2, 0.22, 0.18, 0.21, 0.19]
        g = stats.gain(base, better, False)
        return results_document(
            techniques={"base": TechniqueEntry("base", {"type": "path"}),
                        "better": TechniqueEntry("better", {"type": "path_mis"}, fixed_spp=True)},
            metrics=["sigma_over_mu"], table=TableBudgets(16, seconds),
            matched=[MatchedBudget("better", 16, 0.012)],
            summary=[summary_entry("base", "spp", 16, base),
                     summary_entry("better", "spp", 16, better, g),
                     _time_entry("base", 0.5, base),
                     _time_entry("base", 0.012, base),
                     _time_entry("better", 0.012, better, g, OriginalBudget("spp", 16))])

    def rows(self, text):
        return [line.split(" | ")[1:3] for line in text.split("## Other metrics")[0].splitlines()
                if line.startswith("| fig5 |")]

    def test_matched_rows_follow_the_equal_sample_rows(self):
        text = tables.markdown("paper", [self.document("matched")])
        matched = "0.012 s (time of better at 16 spp)"
        self.assertEqual(self.rows(text), [["base", "16 spp"], ["better", "16 spp"],
                                           ["base", matched], ["better", matched]])
        row = [line for line in text.splitlines() if line.startswith("| fig5 | better | 0.012")]
        self.assertIn("×5 [", row[0])
        self.assertIn("Equal time matched to better at 16 spp: 0.012 s.", text)
        self.assertIn(r"0.012 s (time of better at 16 spp)", tables.latex("paper", [
            self.document("matched")]))

    def test_a_seconds_budget_has_no_row_for_a_fixed_spp_technique(self):
        text = tables.markdown("paper", [self.document(0.5)])
        self.assertEqual(self.rows(text), [["base", "16 spp"], ["base", "0.5 s"],
                                           ["better", "16 spp"]])

    def test_csv_names_what_a_time_budget_was_matched_to(self):
        rows = list(csv_rows(self.document("matched")))
        self.assertEqual({(r["technique"], r["budget"], r["matched_to"]) for r in rows},
                         {("base", "16", ""), ("better", "16", ""), ("base", "0.5", ""),
                          ("base", "0.012", "better at 16 spp"),
                          ("better", "0.012", "better at 16 spp")})


def csv_rows(doc):
    return csv.DictReader(io.StringIO(tables.csv_text([doc])))


@unittest.skipUnless(paths.renderer_binary().exists() and paths.metrics_binary().exists(),
                     "needs the renderer and metrics binaries (make build)")
class MatchedRunTest(unittest.TestCase):
    """fixtures.tiny_matched() end to end, in a few seconds."""

    @classmethod
    def setUpClass(cls):
        scratch = tempfile.TemporaryDirectory()
        cls.addClassCleanup(scratch.cleanup)
        root = Path(scratch.name)
        for name, value in (("RESULTS", root / "results"), ("RENDERS", root / "renders"),
                            ("REFERENCE", root / "reference"),
                            ("MANIFEST", root / "reference" / "manifest.json")):
            cls.addClassCleanup(setattr, paths, name, getattr(paths, name))
            setattr(paths, name, value)
        cls.exp = load_config(tiny_matched())
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            references.ensure([cls.exp], "quick")
            out = experiment.run(cls.exp, "quick", jobs.default_jobs())
        cls.doc = json.loads(out.read_text())
        cls.results = Results.from_json(cls.doc)
        cls.runs = cls.doc["runs"]
        cls.T = cls.doc["matched"][0]["seconds"]

    def select(self, technique, kind, budget, copies=False):
        return [r for r in self.runs if (r["technique"], r["kind"], r["budget"])
                == (technique, kind, budget) and ("duplicate_of" in r) == copies]

    def test_fingerprints_hash_each_techniques_seed_0_at_the_smallest_budget(self):
        prints = [fingerprints.Fingerprint.from_json(f) for f in self.doc["fingerprints"]]
        self.assertEqual([(f.technique, f.spp, f.seed, f.pinned) for f in prints],
                         [("path", 2, 0, {}), ("path_mis", 2, 0, {})])
        for f in prints:
            (run,) = [r for r in self.select(f.technique, "spp", 2) if r["seed"] == 0]
            self.assertEqual(f.pixels_sha256, fingerprints.pixels_sha256(paths.output(run["file"])))

    def test_the_fingerprints_find_a_render_that_changed_and_only_that(self):
        prints = [fingerprints.Fingerprint.from_json(f) for f in self.doc["fingerprints"]]
        profile = self.exp.profiles["quick"]
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            self.assertEqual(fingerprints.stale(self.exp, profile, prints, 2), [])
            # The same hash claimed for another budget: the re-render's pixels differ.
            moved = [prints[0], dataclasses.replace(prints[1], spp=8)]
            self.assertEqual(fingerprints.stale(self.exp, profile, moved, 2),
                             ["path_mis at 8 spp, seed 0: pixels differ"])
            self.assertEqual(fingerprints.stale(self.exp, profile, [], 2),
                             ["the results have no fingerprint"])

    def test_matched_time_is_the_fixed_techniques_mean_render_time(self):
        times = [r["time"] for r in self.select("path_mis", "spp", 8)]
        self.assertEqual(len(times), 5)
        self.assertEqual(self.doc["matched"], [{"technique": "path_mis", "spp": 8,
                                                "seconds": max(round(sum(times) / 5, 3), 0.001)}])
        self.assertEqual(self.doc["budgets"]["matched_spp"], [8])
        self.assertEqual(self.doc["table"], {"spp": 8, "seconds": "matched"})
        self.assertTrue(self.doc["techniques"]["path_mis"]["fixed_spp"])

    def test_the_baseline_is_rendered_with_the_matched_time_limit(self):
        runs = self.select("path", "time", self.T)
        self.assertEqual([r["seed"] for r in runs], list(SEEDS))
        for r in runs:
            self.assertTrue(r["file"].endswith(f"path/{self.T:.12g}s_seed{r['seed']}.exr"))
            self.assertTrue((paths.ROOT / r["file"]).exists())
            self.assertGreaterEqual(r["spp"], 1)
        # the fixed-spp technique was never given a time limit
        self.assertEqual([r for r in self.runs if r["technique"] == "path_mis"
                          and r["kind"] == "time" and "duplicate_of" not in r], [])

    def test_fixed_spp_records_are_entered_again_at_the_matched_time(self):
        copies = self.select("path_mis", "time", self.T, copies=True)
        originals = self.select("path_mis", "spp", 8)
        self.assertEqual(len(copies), 5)
        for original, copy in zip(originals, copies):
            self.assertEqual(copy, {**original, "kind": "time", "budget": self.T,
                                    "duplicate_of": {"kind": "spp", "budget": 8}})

        summary = {(s["technique"], s["kind"], s["budget"]): s for s in self.doc["summary"]}
        entry = summary[("path_mis", "time", self.T)]
        self.assertEqual(entry["metrics"], summary[("path_mis", "spp", 8)]["metrics"])
        self.assertIsNotNone(entry["gain"]["sigma_over_mu"])
        self.assertIsNotNone(entry["gain"]["p_eff"])

    def test_the_results_read_back_as_they_were_written(self):
        self.assertEqual(json.dumps(Results.from_json(self.doc).to_json()), json.dumps(self.doc))

    def test_slopes_count_each_render_once(self):
        self.assertEqual(self.doc["slopes"]["path_mis"]["vs_spp"]["n"], 2 * 5)
        with tempfile.TemporaryDirectory() as scratch:
            without_copies = experiment.slopes(
                self.exp, [r for r in self.results.runs if r.duplicate_of is None],
                scratch)
        self.assertEqual(self.doc["slopes"], {t: s.to_json() for t, s in without_copies.items()})

    def test_tables_show_the_matched_rows(self):
        text = tables.markdown("paper", [self.results])
        budget = f"{self.T:g} s (time of path_mis at 8 spp)"
        rows = [line.split(" | ")[1:3] for line in text.split("## Other")[0].splitlines()
                if line.startswith("| figure | path")]
        self.assertEqual(rows, [["path", "8 spp"], ["path_mis", "8 spp"], ["path", budget],
                                ["path_mis", budget]])
        row = [line for line in text.splitlines() if f"| path_mis | {budget}" in line][0]
        self.assertRegex(row, r"\| ×[0-9.]+ \[")
        self.assertIn("time of path\\_mis at 8 spp", tables.latex("paper", [self.results]))

    def test_calibration_uses_equal_sample_budgets_only(self):
        block = thresholds.calibrate(self.exp, self.results, [8])
        self.assertEqual([(c.technique, c.spp) for c in block.checks],
                         [("path", 8), ("path_mis", 8)])

    def test_plots_draw_the_fixed_technique_against_time_from_its_spp_runs(self):
        from harness import plots
        x, mean, _, _ = plots._series(self.results, "path_mis", "time")
        spp_entries = sorted((s for s in self.doc["summary"] if s["technique"] == "path_mis"
                              and s["kind"] == "spp"), key=lambda s: s["time"]["mean"])
        self.assertEqual(list(x), [s["time"]["mean"] for s in spp_entries])
        with tempfile.TemporaryDirectory() as scratch:
            out = Path(scratch) / "convergence.png"
            plots.convergence(self.results, out)
            self.assertTrue(out.exists())


if __name__ == "__main__":
    unittest.main()
