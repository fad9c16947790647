"""configs/schema/results.schema.json: a valid Draft 2020-12 schema that every committed
results file (results/<paper>/<figure>.json and .full.json) satisfies, strict enough to refuse
an unknown key, a bad value or a missing key (negative controls), naming the metrics of
config.METRICS and giving every property a description. A results file in the current format
(with fingerprints) reads into harness.results.Results and writes back unchanged."""
import copy
import functools
import json
import unittest
from typing import Any

import jsonschema
from jsonschema.exceptions import ValidationError, relevance

import fixtures  # noqa: F401  (puts experiments/ on sys.path)
from harness import config, paths, results

SCHEMA_FILE = paths.SCHEMAS / "results.schema.json"
DRAFT = "https://json-schema.org/draft/2020-12/schema"


@functools.cache
def schema() -> dict[str, Any]:
    return json.loads(SCHEMA_FILE.read_text(encoding="utf-8"))


@functools.cache
def committed_results() -> dict[str, dict[str, Any]]:
    """Every committed results file, by its path relative to the repository root. Other JSON
    files beside them (results/tables/*.json) have no top-level "experiment"."""
    documents = {}
    for file in sorted((paths.ROOT / "results").glob("*/*.json")):
        doc = json.loads(file.read_text(encoding="utf-8"))
        if isinstance(doc, dict) and "experiment" in doc:
            documents[file.relative_to(paths.ROOT).as_posix()] = doc
    return documents


def _is_integer(checker: Any, instance: Any) -> bool:
    """As the harness's config checks: an integer is written without a fraction (Draft
    2020-12's "integer" also admits 16.0)."""
    return isinstance(instance, int) and not isinstance(instance, bool)


def strict_integer_validator() -> jsonschema.protocols.Validator:
    draft = jsonschema.Draft202012Validator
    strict = jsonschema.validators.extend(
        draft, type_checker=draft.TYPE_CHECKER.redefine("integer", _is_integer))
    return strict(schema())


def pointer(error: ValidationError) -> str:
    """The JSON pointer of the bad value: "" for the document itself."""
    return config.json_pointer(*error.absolute_path)


def describe(name: str, errors: list[ValidationError], shown: int = 5) -> str:
    """The file and, for the most relevant errors, the pointer of the bad value and why."""
    errors = sorted(errors, key=relevance, reverse=True)
    lines = [f"{name}: {len(errors)} schema error(s)"]
    lines += [f"  {pointer(e) or '(document)'}: {e.message[:300]}" for e in errors[:shown]]
    return "\n".join(lines)


def schema_properties(node: Any, at: str = "#"):
    """(pointer, subschema) of every property the schema declares, at any depth; not those
    an if/then/else clause only constrains further."""
    if isinstance(node, dict):
        for name, sub in node.get("properties", {}).items():
            yield f"{at}/properties/{name}", sub
        for key, value in node.items():
            if key not in ("if", "then", "else"):
                yield from schema_properties(value, f"{at}/{key}")
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from schema_properties(value, f"{at}/{i}")


class SchemaTest(unittest.TestCase):
    def test_is_a_valid_draft_2020_12_schema(self):
        self.assertEqual(schema()["$schema"], DRAFT)
        jsonschema.Draft202012Validator.check_schema(schema())

    def test_metric_names_are_those_of_config(self):
        defs = schema()["$defs"]
        self.assertEqual(defs["metric"]["enum"], list(config.METRICS))
        self.assertEqual(defs["gainMetric"]["enum"],
                         [m for m in config.METRICS if m not in config.SIGNED_METRICS])

    def test_every_property_has_a_description(self):
        declared = list(schema_properties(schema()))
        self.assertGreater(len(declared), 50)
        missing = [at for at, sub in declared
                   if not isinstance(sub, dict) or not sub.get("description")]
        self.assertEqual(missing, [], "properties without a description")


class CommittedResultsTest(unittest.TestCase):
    def test_every_committed_results_file_validates(self):
        validator = jsonschema.Draft202012Validator(schema())
        documents = committed_results()
        self.assertTrue(documents, "no results files found")
        for name, doc in documents.items():
            with self.subTest(file=name):
                errors = list(validator.iter_errors(doc))
                self.assertFalse(errors, describe(name, errors) if errors else "")

    def test_integers_are_written_without_a_fraction(self):
        """Draft 2020-12 takes 16.0 for an integer; spp, seeds and counts are written as 16."""
        validator = strict_integer_validator()
        for name, doc in committed_results().items():
            with self.subTest(file=name):
                errors = list(validator.iter_errors(doc))
                self.assertFalse(errors, describe(name, errors) if errors else "")

    def test_file_names_follow_experiment_and_profile(self):
        for name, doc in committed_results().items():
            with self.subTest(file=name):
                self.assertEqual(name, f"results/{doc['experiment']}"
                                       f"{paths.suffix(doc['profile'])}.json")

    def test_current_format_round_trips_through_results(self):
        current = {name: doc for name, doc in committed_results().items()
                   if "fingerprints" in doc}
        self.assertTrue(current, "no results file in the current format (with fingerprints)")
        for name, doc in current.items():
            with self.subTest(file=name):
                written = results.Results.from_json(copy.deepcopy(doc)).to_json()
                self.assertTrue(written == doc, f"{name} changes when read and written")
                # The dataclasses' field order is the files' key order.
                self.assertEqual(json.dumps(written), json.dumps(doc),
                                 f"{name}: keys come back in another order")


class NegativeControlsTest(unittest.TestCase):
    """Each change to a valid committed file makes it invalid, with an error at the change."""
    validator: jsonschema.Draft202012Validator
    name: str
    valid: dict[str, Any]

    @classmethod
    def setUpClass(cls):
        cls.validator = jsonschema.Draft202012Validator(schema())
        documents = committed_results()
        # The smallest file, so that copying it is cheap.
        name = min(documents, key=lambda n: (paths.ROOT / n).stat().st_size)
        cls.name, cls.valid = name, documents[name]

    def document(self) -> dict[str, Any]:
        doc = copy.deepcopy(self.valid)
        self.assertTrue(self.validator.is_valid(doc), f"{self.name} should be valid")
        return doc

    def assert_rejected(self, doc: dict[str, Any], at: str, keyword: str):
        errors = list(self.validator.iter_errors(doc))
        self.assertTrue(errors, f"a changed {self.name} was accepted")
        found = {(pointer(e), e.validator) for e in errors}
        self.assertIn((at, keyword), found, describe(self.name, errors))

    def test_unknown_top_level_key(self):
        doc = self.document()
        doc["unexpected"] = 1
        self.assert_rejected(doc, "", "additionalProperties")

    def test_unknown_kind_of_budget(self):
        doc = self.document()
        doc["runs"][0]["kind"] = "bogus"
        self.assert_rejected(doc, "/runs/0/kind", "enum")

    def test_missing_required_key(self):
        doc = self.document()
        del doc["reference"]
        self.assert_rejected(doc, "", "required")

    def test_config_hash_not_hex(self):
        doc = self.document()
        doc["config"]["sha256"] = "z" * 64
        self.assert_rejected(doc, "/config/sha256", "pattern")

    def test_unknown_metric_in_a_run(self):
        doc = self.document()
        doc["runs"][0]["metrics"]["psnr"] = 30.0
        # propertyNames' enum fails, at the object whose key it is
        self.assert_rejected(doc, "/runs/0/metrics", "enum")

    def test_fractional_equal_sample_budget(self):
        doc = self.document()
        run = next(r for r in doc["runs"] if r["kind"] == "spp")
        run["budget"] += 0.5
        self.assert_rejected(doc, f"/runs/{doc['runs'].index(run)}/budget", "type")

    def test_interval_of_three_numbers(self):
        doc = self.document()
        doc["summary"][0]["spp"]["ci95"].append(1.0)
        self.assert_rejected(doc, "/summary/0/spp/ci95", "maxItems")


class AllowedValuesTest(unittest.TestCase):
    """What no committed file happens to hold but the harness may write is accepted."""

    def test_undefined_values_and_optional_forms(self):
        validator = jsonschema.Draft202012Validator(schema())
        name, doc = next(iter(committed_results().items()))
        doc = copy.deepcopy(doc)
        run, entry = doc["runs"][0], doc["summary"][0]
        run["metrics"] = {m: None for m in config.METRICS}
        entry["metrics"] = {m: None for m in entry["metrics"]}
        entry["gain"] = {"sigma_over_mu": None}
        entry["also_gain"] = {}
        doc["crop"] = [0, 0, 8, 8]
        doc["table"] = {"spp": None, "seconds": "matched"}
        doc["provenance"].update(engine="snakemake", hosts=["node1"], git_commit=None)
        for technique in doc["slopes"].values():
            technique["time_range"] = None
        errors = list(validator.iter_errors(doc))
        self.assertFalse(errors, describe(name, errors) if errors else "")


if __name__ == "__main__":
    unittest.main()
