"""Experiment configs: a valid one loads; every kind of bad input names its JSON pointer;
the schema is a valid schema that every committed config satisfies; a variant is merged onto
its parent."""
import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import jsonschema

from fixtures import from_root, load_config, results_document, summary_entry, valid, write_config
from harness import config, paths, renders, stats
from harness.errors import ConfigError
from harness.results import ConfigFile


class ValidConfigTest(unittest.TestCase):
    def test_loads_with_derived_names(self):
        exp = load_config(valid(), figure="fig5")
        self.assertEqual(exp.id, "paper/fig5")
        self.assertEqual(exp.primary_metric, "sigma_over_mu")
        self.assertEqual(list(exp.techniques), ["base", "better"])
        self.assertEqual(exp.techniques["base"].label, "base")
        self.assertEqual(exp.profiles["quick"].table_spp, 16)
        self.assertEqual(exp.paper[0].values["better"], 0.5)
        self.assertEqual(exp.thresholds.checks[0].min_gain, 2.0)

    def test_fixed_spp_technique_with_matched_budgets(self):
        doc = valid()
        doc["techniques"]["better"]["fixed_spp"] = True
        doc["profiles"]["quick"].update(matched_spp=[4, 16], table={"spp": 16,
                                                                   "seconds": "matched"})
        exp = load_config(doc)
        self.assertTrue(exp.techniques["better"].fixed_spp)
        self.assertFalse(exp.techniques["base"].fixed_spp)
        self.assertEqual(exp.profiles["quick"].matched_spp, [4, 16])
        self.assertEqual(exp.profiles["quick"].table_seconds, "matched")
        self.assertEqual(exp.profiles["full"].matched_spp, [])
        self.assertEqual(exp.profiles["full"].table_seconds, 0.5)

    def test_samples_at_sweeps_the_integrator_with_one_pixel_sample(self):
        doc = valid()
        doc["techniques"]["better"]["integrator"] = {
            "type": "direct", "estimator": {"type": "two_stage", "samples": 1}}
        doc["techniques"]["better"]["samples_at"] = ["/estimator/samples"]
        better = load_config(doc).techniques["better"]
        self.assertTrue(better.fixed_spp)
        integrator, spp = better.integrator_for(16)
        self.assertEqual(integrator["estimator"]["samples"], 16)
        self.assertEqual(spp, 1)
        self.assertEqual(better.integrator["estimator"]["samples"], 1)  # not changed in place
        base = load_config(doc).techniques["base"]
        self.assertEqual(base.integrator_for(16), (base.integrator, 16))

    def test_thresholds_and_paper_are_optional(self):
        doc = valid()
        del doc["thresholds"], doc["paper"]
        exp = load_config(doc)
        self.assertIsNone(exp.thresholds)
        self.assertEqual(exp.paper, [])

    def test_a_profile_hash_ignores_thresholds_and_the_other_profile(self):
        before = load_config(valid()).profile_sha256
        doc = valid()
        doc["thresholds"]["checks"][0]["max_error"] = 0.4
        doc["profiles"]["full"]["seeds"] = 8
        after = load_config(doc).profile_sha256
        self.assertEqual(after["quick"], before["quick"])
        self.assertNotEqual(after["full"], before["full"])
        doc["techniques"]["better"]["label"] = "renamed"
        self.assertNotEqual(load_config(doc).profile_sha256["quick"], before["quick"])


class BadConfigTest(unittest.TestCase):
    def assertRejects(self, doc, pointer, fragment):
        with self.assertRaises(ConfigError) as caught:
            load_config(doc)
        self.assertEqual(caught.exception.pointer, pointer, str(caught.exception))
        self.assertIn(fragment, caught.exception.message)

    def mutated(self, change):
        doc = valid()
        change(doc)
        return doc

    def test_malformed_json(self):
        self.assertRejects('{"description": ', "", "malformed JSON")

    def test_non_json_constants(self):
        self.assertRejects('{"description": Infinity}', "", "Infinity is not JSON")

    def test_not_utf8(self):
        self.assertRejects(b'{"description": "\xff"}', "", "not UTF-8")

    def test_duplicate_key(self):
        self.assertRejects('{"description": "a", "description": "b"}', "", "duplicate key")

    def test_unknown_keys_at_every_level(self):
        self.assertRejects(self.mutated(lambda d: d.update(extra=1)), "/extra", "unknown key")
        self.assertRejects(self.mutated(lambda d: d["profiles"]["quick"].update(sppp=1)),
                           "/profiles/quick/sppp", "unknown key")
        self.assertRejects(
            self.mutated(lambda d: d["thresholds"]["checks"][0].update(max_eror=1)),
            "/thresholds/checks/0/max_eror", "unknown key")

    def test_missing_required_key(self):
        self.assertRejects(self.mutated(lambda d: d.pop("baseline")), "/baseline", "missing")
        self.assertRejects(self.mutated(lambda d: d["profiles"].pop("full")), "/profiles/full",
                           "missing")

    def test_impossible_values(self):
        cases = [
            (lambda d: d["profiles"]["quick"].update(seeds=4), "/profiles/quick/seeds", ">= 5"),
            (lambda d: d["profiles"]["quick"].update(spp=[16, 4]), "/profiles/quick/spp",
             "increasing"),
            (lambda d: d["profiles"]["quick"].update(seconds=[-1]),
             "/profiles/quick/seconds/0", "positive"),
            (lambda d: d["profiles"]["quick"].update(reference_spp=63),
             "/profiles/quick/reference_spp", "even"),
            (lambda d: d["profiles"]["quick"]["table"].update(spp=8),
             "/profiles/quick/table/spp", "one of the profile's spp"),
            (lambda d: d["profiles"]["quick"].update(crop=[4, 4, 8, 8]),
             "/profiles/quick/crop", "inside the image"),
            (lambda d: d.update(baseline="nope"), "/baseline", "one of the techniques"),
            (lambda d: d.update(also_baseline="nope"), "/also_baseline",
             "one of the techniques"),
            (lambda d: d.update(also_baseline="base"), "/also_baseline", "differ"),
            (lambda d: d.update(metrics=["relative_bias", "sigma_over_mu"]), "/metrics/0",
             "signed"),
            (lambda d: d.update(metrics=["sigma_over_mu", "psnr"]), "/metrics/1",
             "unknown metric"),
            (lambda d: d.update(scene="configs/scenes/missing.json"), "/scene", "not found"),
            (lambda d: d.update(set={"render/spp": 1}), "/set/render~1spp", "JSON pointers"),
            (lambda d: d["techniques"]["base"].update(integrator={}),
             "/techniques/base/integrator/type", "missing"),
            (lambda d: d["paper"]["values"].update(ghost=1.0), "/paper/values/ghost",
             "not one of the techniques"),
            (lambda d: d["thresholds"]["checks"][0].update(spp=8), "/thresholds/checks/0/spp",
             "spp budgets"),
            (lambda d: d["thresholds"]["checks"][0].update(technique="base"),
             "/thresholds/checks/0/min_gain", "baseline"),
            (lambda d: d.update(scene=None), "/scene", "non-empty string"),
            (lambda d: d["profiles"]["quick"].update(seeds=None), "/profiles/quick/seeds",
             ">= 5"),
            (lambda d: d["paper"]["values"].update(base=None), "/paper/values/base", "positive"),
            (lambda d: d.update(set={"/render/spp": 4}), "/set/~1render~1spp",
             "set by the harness"),
            (lambda d: d.update(set={"/integrator/type": "path"}), "/set/~1integrator~1type",
             "set by the harness"),
            (lambda d: d["techniques"]["better"].update(set={"/render/seed": 3}),
             "/techniques/better/set/~1render~1seed", "only how the scene is estimated"),
            (lambda d: d["techniques"]["better"].update(set={"/render/max_depth": 3}),
             "/techniques/better/set/~1render~1max_depth", "only how the scene is estimated"),
            (lambda d: d["techniques"]["better"].update(equal_time=False),
             "/techniques/better/equal_time", "only to a fixed-spp technique"),
            (lambda d: (d["techniques"]["better"].update(fixed_spp=True, equal_time=False),
                        d["profiles"]["quick"].update(matched_spp=[4])),
             "/profiles/quick/matched_spp", "and equal time"),
            (lambda d: d["techniques"]["better"].update(set=[]), "/techniques/better/set",
             "JSON pointer -> value"),
            (lambda d: d["techniques"].update({"bad name": {"integrator": {"type": "path"}}}),
             "/techniques/bad name", "letters, digits"),
            (lambda d: d["paper"].update(metric="rmse"), "/paper/metric",
             "not one of the experiment's metrics"),
            (lambda d: d["paper"].update(spp=8), "/paper/spp", "must include the paper's"),
            (lambda d: d.update(metrics=["p_eff", "sigma_over_mu"]), "/thresholds",
             "error as the primary metric"),
            (lambda d: d.update(relmse_reject=0.6), "/relmse_reject", "[0, 0.5)"),
            (lambda d: d["thresholds"]["checks"][0].update(max_error=0),
             "/thresholds/checks/0/max_error", "positive finite"),
            (lambda d: d["techniques"]["better"].update(fixed_spp="yes"),
             "/techniques/better/fixed_spp", "true or false"),
            (lambda d: d["techniques"]["better"].update(samples_at=["/light_samples"]),
             "/techniques/better/samples_at/0", "an integer the integrator already has"),
            (lambda d: d["techniques"]["better"].update(samples_at="/light_samples"),
             "/techniques/better/samples_at", "list of JSON pointers"),
            (lambda d: d["profiles"]["quick"]["table"].update(seconds=0.25),
             "/profiles/quick/table/seconds", "seconds budgets or \"matched\""),
            (lambda d: d["profiles"]["quick"]["table"].update(seconds="match"),
             "/profiles/quick/table/seconds", "seconds budgets or \"matched\""),
        ]
        for change, pointer, fragment in cases:
            with self.subTest(pointer=pointer):
                self.assertRejects(self.mutated(change), pointer, fragment)


class TechniqueOverridesTest(unittest.TestCase):
    def test_a_techniques_set_follows_the_experiments_in_its_renders_only(self):
        doc = valid()
        doc["techniques"]["better"]["set"] = {"/render/light_selection": "uniform",
                                              "/render/sampler": "stratified"}
        exp = load_config(doc)
        profile = exp.profiles["quick"]
        better = exp.techniques["better"]
        args = [str(a) for a in renders.scene_args(exp, profile, better.integrator,
                                                   better.overrides)]
        sets = [args[i + 1] for i, a in enumerate(args) if a == "--set"]
        self.assertEqual(sets[:3], ['/render/sampler="independent"',
                                    '/render/light_selection="uniform"',
                                    '/render/sampler="stratified"'])
        base = exp.techniques["base"]
        self.assertEqual(base.overrides, {})
        self.assertNotIn('/render/light_selection="uniform"',
                         [str(a) for a in renders.scene_args(exp, profile, base.integrator,
                                                             base.overrides)])

class MatchedConfigTest(unittest.TestCase):
    """matched_spp and "seconds": "matched", on a config whose "better" is fixed-spp."""
    assertRejects = BadConfigTest.assertRejects

    def mutated(self, change):
        doc = valid()
        doc["techniques"]["better"]["fixed_spp"] = True
        change(doc)
        return doc

    def test_impossible_values(self):
        quick = "/profiles/quick"
        cases = [
            (lambda d: d["profiles"]["quick"].update(matched_spp=[8]),
             f"{quick}/matched_spp/0", "one of the profile's spp budgets"),
            (lambda d: d["profiles"]["quick"].update(matched_spp=[4, 32]),
             f"{quick}/matched_spp/1", "one of the profile's spp budgets"),
            (lambda d: d["profiles"]["quick"].update(matched_spp=16), f"{quick}/matched_spp",
             "list"),
            (lambda d: d["profiles"]["quick"].update(matched_spp=[]), f"{quick}/matched_spp",
             "non-empty"),
            (lambda d: d["profiles"]["quick"].update(matched_spp=[16, 4]),
             f"{quick}/matched_spp", "increasing"),
            (lambda d: d["profiles"]["quick"].update(matched_spp=["16"]),
             f"{quick}/matched_spp/0", "integer"),
            (lambda d: d["profiles"]["quick"].update(matched_spp=[True]),
             f"{quick}/matched_spp/0", "integer"),
            (lambda d: d["profiles"]["quick"].update(matched_spp=None), f"{quick}/matched_spp",
             "list"),
            (lambda d: d["profiles"]["quick"]["table"].update(seconds="matched"),
             f"{quick}/table/seconds", "matched_spp"),
            (lambda d: d["profiles"]["quick"].update(matched_spp=[4],
                                                     table={"spp": 16, "seconds": "matched"}),
             f"{quick}/table/seconds", "the table's spp (16)"),
            (lambda d: (d["techniques"]["better"].pop("fixed_spp"),
                        d["profiles"]["full"].update(matched_spp=[16])),
             "/profiles/full/matched_spp", "\"fixed_spp\": true"),
        ]
        for change, pointer, fragment in cases:
            with self.subTest(pointer=pointer, fragment=fragment):
                self.assertRejects(self.mutated(change), pointer, fragment)


def parent_doc():
    """The fixture config with a third technique as the second baseline, two overrides and the
    paper's numbers in two entries."""
    doc = valid()
    doc["set"] = {"/render/sampler": "independent", "/render/rr_depth": 3}
    doc["techniques"]["third"] = {"label": "third", "integrator": {"type": "path_mis"}}
    doc["also_baseline"] = "third"
    doc["paper"] = [doc["paper"], {"source": "another table", "metric": "sigma_over_mu",
                                   "spp": 16, "values": {"third": 0.7}}]
    return doc


class VariantTest(unittest.TestCase):
    """"variant_of": a variant is merged onto its parent, then loaded as any experiment."""

    def setUp(self):
        self.parent_file = write_config(parent_doc(), figure="parent")

    def variant(self, **keys):
        doc = {"variant_of": from_root(self.parent_file), "description": "through another film",
               "set": {"/render/filter": {"type": "mitchell"}, "/render/sampler": "stratified"},
               "techniques": ["better", "base"]}
        doc.update(keys)
        return doc

    def test_merges_onto_the_parent(self):
        exp = load_config(self.variant(), figure="film")
        parent = config.load(self.parent_file)
        self.assertEqual(exp.id, "paper/film")
        self.assertEqual(exp.files, [exp.file, self.parent_file])
        self.assertEqual(exp.variant_of, self.parent_file)
        self.assertIsNone(parent.variant_of)
        self.assertEqual(exp.description, "through another film")
        # The parent's overrides, then the variant's: a pointer both set moves to its place.
        self.assertEqual(list(exp.overrides.items()),
                         [("/render/rr_depth", 3), ("/render/filter", {"type": "mitchell"}),
                          ("/render/sampler", "stratified")])
        self.assertEqual(list(exp.techniques), ["better", "base"])
        self.assertEqual(exp.techniques["better"], parent.techniques["better"])
        self.assertEqual(exp.baseline, "base")
        self.assertIsNone(exp.also_baseline)  # the parent's, "third", is not kept
        self.assertEqual([(p.source, p.values) for p in exp.paper],
                         [("a paper", {"base": 1.0, "better": 0.5})])
        self.assertIsNone(exp.thresholds)  # the parent's are not inherited
        for key in ("scene", "metrics", "reference_integrator", "profiles", "relmse_reject",
                    "slope_time_range"):
            self.assertEqual(getattr(exp, key), getattr(parent, key), key)

    def test_extra_techniques_follow_the_kept_and_a_kept_second_baseline_stays(self):
        extra = {"extra": {"label": "extra", "integrator": {"type": "path"}}}
        exp = load_config(self.variant(techniques=["third", "base"], extra_techniques=extra))
        self.assertEqual(list(exp.techniques), ["third", "base", "extra"])
        self.assertEqual(exp.techniques["extra"].label, "extra")
        self.assertEqual((exp.baseline, exp.also_baseline), ("base", "third"))
        self.assertEqual([p.values for p in exp.paper], [{"base": 1.0}, {"third": 0.7}])

    def test_a_paper_object_stays_an_object(self):
        doc = parent_doc()
        doc["paper"] = doc["paper"][0]
        self.parent_file.write_text(json.dumps(doc))
        exp = load_config(self.variant(techniques=["base", "third"]))
        self.assertEqual([p.values for p in exp.paper], [{"base": 1.0}])
        exp = load_config(self.variant(techniques=["third"], baseline="third"))
        self.assertEqual(exp.paper, [])

    def test_given_baselines_replace_the_parents(self):
        exp = load_config(self.variant(techniques=["base", "better", "third"],
                                       baseline="better", also_baseline="base"))
        self.assertEqual((exp.baseline, exp.also_baseline), ("better", "base"))
        # The parent's second baseline made the baseline is not also the second baseline.
        exp = load_config(self.variant(techniques=["third", "better"], baseline="third"))
        self.assertEqual((exp.baseline, exp.also_baseline), ("third", None))

    def test_given_keys_replace_the_parents_whole(self):
        profiles = valid()["profiles"]
        profiles["quick"].update(resolution=[4, 4], spp=[16])
        thresholds = {"profile": "quick", "method": "the variant's own",
                      "checks": [{"technique": "better", "spp": 16, "max_error": 0.2}]}
        exp = load_config(self.variant(
            metrics=["sigma_over_mu", "rmse"], reference={"integrator": {"type": "path"}},
            profiles=profiles, relmse_reject=0.001, slope_time_range="common",
            scene="configs/scenes/cornell_spheres.json", thresholds=thresholds))
        self.assertEqual(exp.metrics, ["sigma_over_mu", "rmse"])
        self.assertEqual(exp.reference_integrator, {"type": "path"})
        self.assertEqual(exp.profiles["quick"].spp, [16])
        self.assertEqual(exp.profiles["quick"].seconds, [0.5])  # not merged with the parent's
        self.assertEqual((exp.relmse_reject, exp.slope_time_range), (0.001, "common"))
        self.assertEqual(exp.thresholds.method, "the variant's own")

    def test_the_profile_hash_follows_the_merged_document(self):
        variant_file = write_config(self.variant())
        before = config.load(variant_file).profile_sha256
        self.assertNotEqual(before, config.load(self.parent_file).profile_sha256)

        def hash_after(change):
            doc = parent_doc()
            change(doc)
            self.parent_file.write_text(json.dumps(doc))
            return config.load(variant_file).profile_sha256

        self.assertEqual(hash_after(lambda d: d["thresholds"].update(method="again")), before)
        self.assertEqual(hash_after(lambda d: d.update(description="reworded")), before)
        self.assertNotEqual(hash_after(lambda d: d["techniques"]["better"].update(label="b")),
                            before)
        self.assertNotEqual(hash_after(lambda d: d["set"].update({"/render/rr_depth": 4})),
                            before)
        after = hash_after(lambda d: d["profiles"]["full"].update(seeds=6))
        self.assertEqual(after["quick"], before["quick"])
        self.assertNotEqual(after["full"], before["full"])

    def assertRejects(self, doc, pointer, fragment, file=None):
        """`file`: the file the error names, if not the variant's."""
        variant_file = write_config(doc)
        with self.assertRaises(ConfigError) as caught:
            config.load(variant_file)
        self.assertEqual(caught.exception.file, str(file or variant_file))
        self.assertEqual(caught.exception.pointer, pointer, str(caught.exception))
        self.assertIn(fragment, caught.exception.message)

    def test_errors_name_their_pointer(self):
        allowed = ("also_baseline, baseline, description, extra_techniques, metrics, profiles, "
                   "reference, relmse_reject, scene, set, slope_time_range, techniques, "
                   "thresholds, variant_of")
        cases = [
            (self.variant(variant_of="configs/experiments/none/missing.json"), "/variant_of",
             "not found"),
            (self.variant(variant_of=7), "/variant_of", "non-empty string"),
            (self.variant(paper={}), "/paper", f"unknown key (expected one of: {allowed})"),
            (self.variant(baselin="base"), "/baselin", "unknown key"),
            ({k: v for k, v in self.variant().items() if k != "description"}, "/description",
             "missing"),
            ({k: v for k, v in self.variant().items() if k != "techniques"}, "/techniques",
             "missing"),
            (self.variant(techniques=[]), "/techniques", "non-empty list"),
            (self.variant(techniques=["base", "base"]), "/techniques", "each once"),
            (self.variant(techniques=["base", "ghost"]), "/techniques/1",
             "techniques (known: base, better, third)"),
            (self.variant(extra_techniques={"base": {"integrator": {"type": "path"}}}),
             "/extra_techniques/base", "the name of a kept technique"),
            (self.variant(extra_techniques={"x": {"integrator": {}}}),
             "/extra_techniques/x/integrator/type", "missing"),
            (self.variant(extra_techniques={"x": {"integrator": {"type": "path"},
                                                  "equal_time": False}}),
             "/extra_techniques/x/equal_time", "only to a fixed-spp technique"),
            (self.variant(techniques=["better", "third"]), "/baseline",
             "the parent's baseline, base, is not kept"),
            (self.variant(baseline="third"), "/baseline", "one of the techniques"),
            (self.variant(also_baseline="base"), "/also_baseline", "differ"),
            (self.variant(set={"/render/spp": 4}), "/set/~1render~1spp", "set by the harness"),
            (self.variant(thresholds={"profile": "quick", "method": "m", "checks": [
                {"technique": "third", "spp": 16, "max_error": 1.0}]}),
             "/thresholds/checks/0/technique", "not one of the techniques"),
            # Inherited numbers that disagree with what the variant gives: named as inherited.
            (self.variant(metrics=["rmse"]), "/paper/0/metric",
             f"is not one of the experiment's metrics (/paper is inherited from "
             f"{from_root(self.parent_file)})"),
        ]
        for doc, pointer, fragment in cases:
            with self.subTest(pointer=pointer, fragment=fragment):
                self.assertRejects(doc, pointer, fragment)

    def test_no_chains(self):
        middle = write_config(self.variant(), figure="middle")
        self.assertRejects(self.variant(variant_of=from_root(middle)), "/variant_of",
                           "is itself a variant (of \"")
        # Nor itself.
        file = write_config(self.variant())
        file.write_text(json.dumps(self.variant(variant_of=from_root(file))))
        with self.assertRaises(ConfigError) as caught:
            config.load(file)
        self.assertEqual((caught.exception.file, caught.exception.pointer),
                         (str(file), "/variant_of"))
        self.assertIn("is itself a variant", caught.exception.message)

    def test_an_error_in_the_parent_names_the_parents_file(self):
        doc = parent_doc()
        doc["baseline"] = "nope"
        self.parent_file.write_text(json.dumps(doc))
        self.assertRejects(self.variant(), "/baseline", "one of the techniques",
                           file=self.parent_file)

    def test_an_inherited_matched_spp_needs_a_kept_fixed_spp_technique(self):
        doc = parent_doc()
        doc["techniques"]["third"]["fixed_spp"] = True
        doc["profiles"]["quick"]["matched_spp"] = [16]
        self.parent_file.write_text(json.dumps(doc))
        self.assertRejects(self.variant(), "/profiles/quick/matched_spp",
                           "(/profiles is inherited from")

    def test_calibrate_proposes_thresholds_for_the_variants_own_file(self):
        """`run.py calibrate` on a variant: its block, pasted into the variant's file as
        configs/README.md says, keeps the file a variant and its results current."""
        variant = self.variant(techniques=["base", "better"])
        variant_file = write_config(variant, figure="film")
        exp = config.load(variant_file)
        base, better = [0.58, 0.60, 0.62, 0.59, 0.61], [0.24, 0.25, 0.26, 0.245, 0.255]
        results = results_document(
            summary=[summary_entry("base", "spp", 16, base),
                     summary_entry("better", "spp", 16, better, stats.gain(base, better, False))],
            config=ConfigFile(paths.relative(variant_file), exp.profile_sha256["quick"]))
        parent_text = self.parent_file.read_text()
        with tempfile.TemporaryDirectory() as root:
            results_file = Path(root) / "results" / "paper" / "film.json"
            results_file.parent.mkdir(parents=True)
            results_file.write_text(json.dumps(results.to_json()))
            printed = subprocess.run(
                [sys.executable, paths.ROOT / "experiments" / "run.py", "calibrate",
                 variant_file, "--spp", "16"], env={**os.environ, "HARNESS_OUTPUT_ROOT": root},
                capture_output=True, text=True, check=True).stdout
        variant_file.write_text(json.dumps({**variant, **json.loads(printed)}))
        calibrated = config.load(variant_file)
        self.assertEqual(calibrated.variant_of, self.parent_file)
        self.assertEqual([c.technique for c in calibrated.thresholds.checks], ["base", "better"])
        self.assertEqual(calibrated.profile_sha256, exp.profile_sha256)
        self.assertEqual(self.parent_file.read_text(), parent_text)


class SchemaTest(unittest.TestCase):
    """configs/schema/experiment.schema.json on its own, as an editor uses it."""

    @classmethod
    def setUpClass(cls):
        cls.schema = json.loads(config.SCHEMA_FILE.read_text(encoding="utf-8"))

    def test_is_a_valid_draft_2020_12_schema(self):
        self.assertEqual(self.schema["$schema"], "https://json-schema.org/draft/2020-12/schema")
        jsonschema.Draft202012Validator.check_schema(self.schema)

    def test_every_committed_experiment_config_validates_and_loads(self):
        validator = jsonschema.Draft202012Validator(self.schema)
        files = paths.all_experiment_configs()
        self.assertTrue(files)
        for file in files:
            with self.subTest(config=paths.relative(file)):
                validator.validate(json.loads(file.read_text(encoding="utf-8")))
                config.load(file)

    def test_a_variant_is_a_document_of_the_schema(self):
        validator = jsonschema.Draft202012Validator(self.schema)
        variant = {"variant_of": "configs/experiments/core/path_vs_mis.json",
                   "description": "a variant", "techniques": ["path"]}
        validator.validate(variant)
        self.assertFalse(validator.is_valid({**variant, "paper": {}}))
        self.assertFalse(validator.is_valid({**valid(), "variant_of": variant["variant_of"]}))

    def test_names_agree_with_the_code(self):
        defs = self.schema["$defs"]
        self.assertEqual(defs["metric"]["enum"], list(config.METRICS))
        self.assertEqual(defs["thresholds"]["properties"]["profile"]["enum"],
                         list(config.PROFILES))
        self.assertEqual(defs["experiment"]["properties"]["profiles"]["required"],
                         list(config.PROFILES))
        variant = set(defs["variant"]["properties"])
        self.assertLessEqual(set(config.VARIANT_REPLACES), variant)
        self.assertLessEqual(variant - {"variant_of", "extra_techniques"},
                             set(defs["experiment"]["properties"]))


class SchemaErrorTest(unittest.TestCase):
    """Errors the schema finds: one line, the best match, naming the pointer."""
    assertRejects = BadConfigTest.assertRejects
    mutated = BadConfigTest.mutated

    def test_structural_errors(self):
        cases = [
            (lambda d: d["thresholds"]["checks"][0].update(max_error=None),
             "/thresholds/checks/0/max_error", "positive finite number, got null"),
            (lambda d: [d["thresholds"]["checks"][0].pop(k) for k in ("max_error", "min_gain")],
             "/thresholds/checks/0", "give max_error, min_gain or both"),
            (lambda d: d["thresholds"].update(profile="fast"), "/thresholds/profile",
             "unknown profile (known: quick, full), got \"fast\""),
            (lambda d: d["profiles"]["quick"].update(spp=[4, 16.0]), "/profiles/quick/spp/1",
             "integer"),
            (lambda d: d["profiles"]["quick"].update(crop=[0, 0, 0, 8]), "/profiles/quick/crop/2",
             "integer >= 1"),
            (lambda d: d["profiles"]["quick"].update(crop=[0, 0, 8]), "/profiles/quick/crop",
             "[x, y, width, height]"),
            (lambda d: d["profiles"]["quick"]["table"].update(seconds=-1),
             "/profiles/quick/table/seconds", "seconds budgets or \"matched\", got -1"),
            (lambda d: d.update(paper=[d["paper"], {"source": "x"}]), "/paper/1/metric",
             "missing"),
            (lambda d: d.update(paper=5), "/paper", "an object, or a non-empty list"),
            (lambda d: d.update(metrics=["rmse", "rmse"]), "/metrics", "each once"),
            (lambda d: d.update(techniques={}), "/techniques", "at least one technique"),
            (lambda d: d["techniques"]["base"].update(label=""), "/techniques/base/label",
             "non-empty string, got \"\""),
        ]
        for change, pointer, fragment in cases:
            with self.subTest(pointer=pointer, fragment=fragment):
                self.assertRejects(self.mutated(change), pointer, fragment)

    def test_the_shallowest_of_several_errors_is_reported(self):
        doc = self.mutated(lambda d: d["profiles"]["quick"].update(seeds=4, sppp=1))
        doc["extra"] = 1
        for _ in range(3):
            self.assertRejects(doc, "/extra", "unknown key")

    def test_a_number_too_large_for_a_double_is_not_json(self):
        text = json.dumps(valid()).replace('"max_error": 0.3', '"max_error": 1e999')
        self.assertRejects(text, "", "malformed JSON")


if __name__ == "__main__":
    unittest.main()
