"""Tables: a synthetic results document renders rows with intervals, gains and verdicts."""
import csv
import io
import unittest

from fixtures import summary_entry
from harness import stats, tables
from harness.records import to_json

BASE = [1.0, 1.1, 0.9, 1.05, 0.95]
BETTER = [0.2, 0.22, 0.18, 0.21, 0.19]


def document():
    g = stats.gain(BASE, BETTER, False)
    return {
        "experiment": "paper/fig5", "profile": "quick", "description": "synthetic",
        "config": {"file": "configs/experiments/core/path_vs_mis.json", "sha256": "stale"},
        "techniques": {"base": {}, "better": {}}, "baseline": "base",
        "metrics": ["sigma_over_mu", "p_eff"], "resolution": [8, 8], "seeds": [0, 1, 2, 3, 4],
        "table": {"spp": 16, "seconds": None},
        "paper": [{"source": "x", "metric": "sigma_over_mu", "spp": 16,
                   "values": {"base": 1.045, "better": 0.207}}],
        "summary": [to_json(summary_entry("base", "spp", 16, BASE)),
                    to_json(summary_entry("better", "spp", 16, BETTER, g))],
        "slopes": {"base": {"vs_spp": {"slope": -0.5, "slope_stderr": 0.01, "r2": 0.99,
                                       "n": 10}}},
        "reference": {"integrator": {"type": "path_mis"}, "spp": 1024,
                      "noise_sigma_over_mu": 0.01, "noise_ratio_to_smallest_error": 0.05},
        "provenance": {"parallel_jobs": 2, "threads_per_job": 1, "git_commit": "abc",
                       "git_dirty": False},
    }


class TablesTest(unittest.TestCase):
    def test_markdown_row_has_interval_gain_paper_gain_and_verdict(self):
        text = tables.markdown("paper", [document()])
        row = [line for line in text.splitlines() if line.startswith("| fig5 | better |")][0]
        # gain 1.0 / 0.2 = 5; the paper's 1.045 / 0.207 = 5.05 -> reproduced
        self.assertIn("×5 [", row)
        self.assertIn("×5.05", row)
        self.assertIn("reproduced", row)
        self.assertIn("0.207 (16 spp)", row)
        self.assertIn("| fig5 | base | σ/µ | -0.500 ± 0.010 | 0.990 | — | — | 10 |", text)

    def test_the_legend_explains_every_verdict(self):
        legend = tables.markdown("paper", [document()]).split("\n\n")[1]
        for verdict in ("reproduced", "weaker", "stronger", "inconclusive"):
            self.assertIn(f"*{verdict}*", legend)
        self.assertIn("*inconclusive* when our gain is outside the band but its interval "
                      "reaches into it", legend)

    def test_results_of_a_changed_config_are_flagged(self):
        self.assertIn("its config has changed since this run", tables.markdown("paper",
                                                                               [document()]))

    def test_csv_has_every_metric_of_every_budget(self):
        rows = list(csv.DictReader(io.StringIO(tables.csv_text([document()]))))
        self.assertEqual(len(rows), 4)  # 2 techniques x 2 metrics
        better = [r for r in rows if r["technique"] == "better" and r["metric"] == "sigma_over_mu"]
        self.assertAlmostEqual(float(better[0]["mean"]), 0.2)
        self.assertEqual(better[0]["verdict"], "reproduced")

    def test_a_second_baseline_gets_its_own_gain_column(self):
        doc = document()
        doc["techniques"]["default"] = {}
        doc["also_baseline"] = "default"
        default = [0.5, 0.55, 0.45, 0.52, 0.48]
        entries = [summary_entry("base", "spp", 16, BASE),
                   summary_entry("better", "spp", 16, BETTER, stats.gain(BASE, BETTER, False)),
                   summary_entry("default", "spp", 16, default, stats.gain(BASE, default, False))]
        also = {"base": stats.gain(default, BASE, False), "better": stats.gain(default, BETTER,
                                                                                False)}
        doc["summary"] = [{**to_json(e), "also_gain": ({"sigma_over_mu": to_json(also[e.technique]),
                                                        "p_eff": None}
                                                       if e.technique in also else {})}
                          for e in entries]
        text = tables.markdown("paper", [doc])
        self.assertIn("| gain over baseline (95 %) | gain over 2nd baseline (95 %) |", text)
        row = [line for line in text.splitlines() if line.startswith("| fig5 | better |")][0]
        # over base ×5, over default 0.5 / 0.2 = ×2.5; the verdict stays against base
        self.assertIn("| ×5 [", row)
        self.assertIn("| ×2.5 [", row)
        self.assertIn("reproduced", row)
        self.assertIn("fig5: default (baseline base)", text)
        rows = list(csv.DictReader(io.StringIO(tables.csv_text([doc]))))
        better = [r for r in rows if r["technique"] == "better" and r["metric"] == "sigma_over_mu"]
        self.assertAlmostEqual(float(better[0]["also_gain"]), 2.5)

    def test_latex_escapes_names(self):
        doc = document()
        doc["experiment"] = "paper/fig_5"
        self.assertIn(r"fig\_5", tables.latex("paper", [doc]))


if __name__ == "__main__":
    unittest.main()
