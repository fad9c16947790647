"""Experiment configs: a valid one loads; every kind of bad input names its JSON pointer;
the schema is a valid schema that every committed config satisfies."""
import json
import unittest

import jsonschema

from fixtures import load_config, valid
from harness import config, paths, renders
from harness.errors import ConfigError


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

    def test_names_agree_with_the_code(self):
        self.assertEqual(self.schema["$defs"]["metric"]["enum"], list(config.METRICS))
        self.assertEqual(self.schema["$defs"]["thresholds"]["properties"]["profile"]["enum"],
                         list(config.PROFILES))
        self.assertEqual(self.schema["properties"]["profiles"]["required"], list(config.PROFILES))


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
