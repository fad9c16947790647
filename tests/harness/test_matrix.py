"""The cross-paper matrix: its columns come from the renderer's registry, so a technique
registered later (here a fixture estimator and two fixture integrators, in a stand-in for
`renderer keys`) appears in the experiments, the table, the CSV and the heat map with no edit
to the matrix code; refusals and the other transport's techniques are placed as documented."""
import copy
import csv
import io
import json
import tempfile
import unittest
from pathlib import Path

import fixtures  # noqa: F401  (puts experiments/ on the path)
from harness import config, matrix_configs, matrix_plot, matrix_tables, paths, stats
from harness.matrix_configs import DEFAULT, ColumnCheck

FIXTURE_ESTIMATOR, FIXTURE_INTEGRATOR, FIXTURE_WRAPPER = "fixture_est", "fixture_int", "fixture_wrap"


def catalogue(extra: bool) -> dict:
    """A stand-in for `renderer keys`: the built-in types, and with `extra` the fixture ones."""
    estimators = ["bsdf", "light", "mis", *([FIXTURE_ESTIMATOR] if extra else [])]
    integrators = {"direct": ["strategy", "estimator"], "path": [], "path_mis": ["estimator"],
                   "pmc_ip": ["integrator", "initial_spp"], "tais": ["maps"]}
    if extra:
        integrators[FIXTURE_INTEGRATOR] = ["knob"]
        integrators[FIXTURE_WRAPPER] = ["integrator"]
    return {
        "categories": {
            "estimator": {"types": [[e, f"estimator/{e}"] for e in estimators]},
            "integrator": {"types": [[i, f"integrator/{i}"] for i in integrators]}},
        "tables": {f"integrator/{i}": {"keys": [{"name": k} for k in keys]}
                   for i, keys in integrators.items()}}


SPEC = {"seeds": 5, "figures": {}, "required": {FIXTURE_INTEGRATOR: {"knob": 3}},
        "wrapped": {"direct": {"type": "direct"}, "paths": {"type": "path_mis"}}}


class ColumnsTest(unittest.TestCase):
    def test_the_registry_gives_the_columns(self):
        names = [c.name for c in matrix_configs.columns(catalogue(False), SPEC)]
        self.assertEqual(names, ["direct-bsdf", "direct-light", "direct-mis", "path",
                                 "path_mis-bsdf", "path_mis-light", "path_mis-mis", "pmc_ip",
                                 "tais"])

    def test_a_technique_registered_later_gets_columns(self):
        columns = {c.name: c for c in matrix_configs.columns(catalogue(True), SPEC)}
        before = {c.name for c in matrix_configs.columns(catalogue(False), SPEC)}
        self.assertEqual(set(columns) - before,
                         {"direct-fixture_est", "path_mis-fixture_est", FIXTURE_INTEGRATOR,
                          FIXTURE_WRAPPER})
        self.assertEqual(columns["path_mis-fixture_est"].integrator["paths"],
                         {"type": "path_mis", "estimator": {"type": FIXTURE_ESTIMATOR}})
        self.assertEqual(columns[FIXTURE_INTEGRATOR].integrator["direct"],
                         {"type": FIXTURE_INTEGRATOR, "knob": 3})  # its required key
        self.assertEqual(columns[FIXTURE_WRAPPER].integrator["paths"],
                         {"type": FIXTURE_WRAPPER, "integrator": {"type": "path_mis"}})


def figure():
    return config.load(paths.CONFIGS / "ris" / "fig05_diffuse_sphere.json")


def fixture_row():
    """The fixture techniques as `renderer check` would answer on a direct-lighting scene: one
    accepted, one that cannot stop at a time limit, one refused, one of the other transport."""
    return [ColumnCheck("direct-mis", {"type": "direct", "estimator": {"type": "mis"}}, None, "direct",
                 True),
            ColumnCheck("direct-fixture_est", {"type": "direct", "estimator": {"type": "fixture_est"}},
                 None, "direct", True),
            ColumnCheck(FIXTURE_INTEGRATOR, {"type": FIXTURE_INTEGRATOR, "knob": 3}, None, "direct",
                 False),
            ColumnCheck(FIXTURE_WRAPPER, {"type": FIXTURE_WRAPPER}, "/integrator: no, not here", None,
                 False),
            ColumnCheck("path_mis-fixture_est", {"type": "path_mis"}, "/integrator/estimator: no",
                 None, False),
            ColumnCheck("tais", {"type": "tais"}, None, "paths", False)]


TRANSPORTS = {"direct-mis": {"direct"}, "direct-fixture_est": {"direct"},
              FIXTURE_INTEGRATOR: {"direct"}, FIXTURE_WRAPPER: set(),
              "path_mis-fixture_est": {"paths"}, "tais": {"paths"}}


class ExperimentDocumentTest(unittest.TestCase):
    def setUp(self):
        self.doc = matrix_configs.experiment_document(
            "ris_fig5_diffuse_sphere.json", figure(), "direct", fixture_row(), TRANSPORTS, SPEC)

    def test_accepted_techniques_of_the_scenes_transport_are_rendered(self):
        self.assertEqual(list(self.doc["techniques"]),
                         [DEFAULT, "direct-mis", "direct-fixture_est", FIXTURE_INTEGRATOR])
        self.assertTrue(self.doc["techniques"][DEFAULT]["sets_time"])
        self.assertEqual(self.doc["techniques"][FIXTURE_INTEGRATOR]["equal_time"], "baseline")
        self.assertTrue(self.doc["techniques"][FIXTURE_INTEGRATOR]["fixed_spp"])

    def test_refusals_are_kept_where_the_technique_could_apply(self):
        # the wrapper is refused everywhere, so its transport is unknown: listed; the paths
        # estimator is another transport's: left out
        self.assertEqual(self.doc["matrix"]["refused"],
                         {FIXTURE_WRAPPER: "/integrator: no, not here"})

    def test_the_document_is_a_valid_experiment_with_the_figures_setup(self):
        with tempfile.TemporaryDirectory() as tmp:
            file = Path(tmp) / "matrix" / "ris_fig5_diffuse_sphere.json"
            file.parent.mkdir()
            file.write_text(json.dumps(self.doc))
            exp = config.load(file)
        fig = figure()
        quick = exp.profiles["quick"]
        self.assertEqual(quick.resolution, fig.profiles["quick"].resolution)
        self.assertEqual(quick.spp, [fig.profiles["quick"].table_spp])
        self.assertEqual(quick.table_seconds, config.MATCHED)
        self.assertEqual(exp.reference_integrator, fig.reference_integrator)
        self.assertEqual(exp.matrix.refused, {FIXTURE_WRAPPER: "/integrator: no, not here"})


def gain(value):
    return stats.Gain(value, 0.1 * value, (0.8 * value, 1.2 * value))


def fixture_rows():
    """A direct row with the fixture technique at equal time, one refused, and one that took
    1.5 times the default's time; a path row with tais."""
    cell = matrix_tables.Cell
    cells = {DEFAULT: cell(DEFAULT, None, 0.5, 16, time_ratio=1.0),
             "direct-mis": cell("direct-mis", gain(1.0), 0.5, 15, time_ratio=0.98),
             "direct-fixture_est": cell("direct-fixture_est", gain(3.0), 0.5, 9, time_ratio=1.02),
             "direct-slow": cell("direct-slow", gain(1.4), 0.5, 1, time_ratio=1.5),
             FIXTURE_WRAPPER: cell(FIXTURE_WRAPPER, refusal="/integrator: no")}
    direct = matrix_tables.Row("a.json", "matrix/a", "direct", 0.5, 16, cells, False)
    paths_row = matrix_tables.Row("b.json", "matrix/b", "paths", 1.0, 8, {
        DEFAULT: cell(DEFAULT, None, 1.0, 8, time_ratio=1.0),
        "tais": cell("tais", gain(0.5), 1.3, 8, time_ratio=1.0)}, True)
    return [direct, paths_row]


class GenerateTest(unittest.TestCase):
    """generate() with the real renderer on one scene, the registry extended by a fixture
    estimator that the renderer does not know."""

    SCENE = "ris_fig5_diffuse_sphere.json"

    def test_a_technique_registered_later_is_checked_on_each_scene(self):
        real = matrix_configs.registry()
        stand_in = copy.deepcopy(real)
        stand_in["categories"]["estimator"]["types"].append(
            [FIXTURE_ESTIMATOR, f"estimator/{FIXTURE_ESTIMATOR}"])
        file = matrix_configs.config_file(self.SCENE)
        doc = json.loads(matrix_configs.generate(2, stand_in, {self.SCENE})[file])
        # the renderer refuses it here, in its own words, which the row keeps
        self.assertIn(FIXTURE_ESTIMATOR, doc["matrix"]["refused"][f"direct-{FIXTURE_ESTIMATOR}"])
        committed = json.loads(file.read_text())
        self.assertEqual(doc["techniques"], committed["techniques"])


class TablesTest(unittest.TestCase):
    def test_the_fixture_technique_is_a_column_with_its_interval(self):
        text = matrix_tables.markdown(fixture_rows())
        self.assertIn("`direct-fixture_est`", text)
        self.assertIn("**×3** [2.4, 3.6]", text)  # the interval excludes 1: bold
        self.assertIn("×1 [0.8, 1.2]", text)
        self.assertIn("| refused (1) |", text)  # the reason's note
        self.assertIn(f"1. `{FIXTURE_WRAPPER}`: /integrator: no (a)", text)

    def test_a_cell_not_at_equal_time_is_marked_and_charged_for_its_time(self):
        text = matrix_tables.markdown(fixture_rows())
        self.assertIn("**×1.4** [1.12, 1.68] † (×1.5 the time)", text)
        self.assertIn("| b ‡ |", text)  # its config changed since
        summary = "\n".join(matrix_tables.measured_summary(fixture_rows()))
        self.assertIn("| `direct-slow` | 0 | 0 | 0 | 1 | 0 | — | — | — |", summary)
        self.assertIn("| a | `direct-fixture_est` | ×3 [2.4, 3.6] |", summary)
        # charged for 1.5 times the time, ×1.4 [1.12, 1.68] could be a tie; ×3 could not
        faster = matrix_tables.Cell("x", gain(3.0), 0.5, 1, time_ratio=1.5)
        self.assertEqual(matrix_tables.verdict(faster), "better")
        slower = matrix_tables.Cell("x", gain(0.5), 0.5, 1, time_ratio=0.6)  # [0.4, 0.6] / 0.6
        self.assertEqual(matrix_tables.verdict(slower), "unequal time")

    def test_each_transport_has_its_own_columns(self):
        text = matrix_tables.markdown(fixture_rows())
        direct, paths_part = text.split("## Path-traced scenes")
        self.assertNotIn("`tais`", direct)
        self.assertIn("`tais`", paths_part.split("## Refusals")[0])
        self.assertNotIn("fixture_est", paths_part.split("## Refusals")[0])

    def test_the_csv_has_every_cell_with_its_status(self):
        rows = list(csv.DictReader(io.StringIO(matrix_tables.csv_text(fixture_rows()))))
        status = {(r["scene"], r["technique"]): r["status"] for r in rows}
        self.assertEqual(status[("a.json", "direct-fixture_est")], "measured")
        verdicts = {r["technique"]: r["verdict"] for r in rows if r["scene"] == "a.json"}
        self.assertEqual((verdicts["direct-fixture_est"], verdicts["direct-slow"]),
                         ("better", "unequal time"))
        self.assertEqual(status[("a.json", FIXTURE_WRAPPER)], "refused")
        self.assertEqual(status[("a.json", DEFAULT)], "baseline")
        fixture = next(r for r in rows if r["technique"] == "direct-fixture_est")
        self.assertEqual((fixture["gain"], fixture["gain_ci95_lo"]), ("3", "2.4"))

    def test_the_analysis_keeps_its_reading_and_replaces_its_measured_part(self):
        with tempfile.TemporaryDirectory() as tmp:
            file = Path(tmp) / "analysis.md"
            file.write_text(f"# Reading\n\nhand-written\n\n{matrix_tables.BEGIN}\nold\n"
                            f"{matrix_tables.END}\n\nmore reading\n")
            original = matrix_tables.ANALYSIS_FILE
            matrix_tables.ANALYSIS_FILE = file
            try:
                matrix_tables.write_analysis(fixture_rows())
            finally:
                matrix_tables.ANALYSIS_FILE = original
            text = file.read_text()
        self.assertIn("hand-written", text)
        self.assertIn("more reading", text)
        self.assertNotIn("\nold\n", text)
        self.assertIn("| `direct-fixture_est` | 1 | 0 | 0 | 0 | 0 | ×3 |", text)

    def test_the_heat_map_draws_the_fixture_column(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "heatmap.png"
            matrix_plot.heatmap(copy.deepcopy(fixture_rows()), out)
            self.assertGreater(out.stat().st_size, 1000)


if __name__ == "__main__":
    unittest.main()
