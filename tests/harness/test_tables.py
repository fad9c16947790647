"""Tables: a synthetic results document renders rows with intervals, gains and verdicts."""
import csv
import dataclasses
import io
import unittest

from fixtures import results_document, summary_entry
from harness import results, stats, tables
from harness.config import PaperNumbers
from harness.results import LineFit, TechniqueSlopes

BASE = [1.0, 1.1, 0.9, 1.05, 0.95]
BETTER = [0.2, 0.22, 0.18, 0.21, 0.19]


def document(**fields):
    """Results of a config whose hash has changed (the placeholder's), with a paper number."""
    g = stats.gain(BASE, BETTER, False)
    fit = LineFit(intercept=0.0, n=10, r2=0.99, slope=-0.5, slope_stderr=0.01)
    return results_document(**{
        "paper": [PaperNumbers("x", "sigma_over_mu", 16, {"base": 1.045, "better": 0.207})],
        "summary": [summary_entry("base", "spp", 16, BASE),
                    summary_entry("better", "spp", 16, BETTER, g)],
        "slopes": {"base": TechniqueSlopes(fit, fit)}, **fields})


class TablesTest(unittest.TestCase):
    def test_markdown_row_has_interval_gain_paper_gain_and_verdict(self):
        text = tables.markdown("paper", [document()])
        row = [line for line in text.splitlines() if line.startswith("| fig5 | better |")][0]
        # gain 1.0 / 0.2 = 5; the paper's 1.045 / 0.207 = 5.05 -> reproduced
        self.assertIn("×5 [", row)
        self.assertIn("×5.05", row)
        self.assertIn("reproduced", row)
        self.assertIn("0.207 (16 spp)", row)
        self.assertIn("| fig5 | base | σ/µ | -0.500 ± 0.010 | 0.990 | -0.500 ± 0.010 | 0.990 | "
                      "10 |", text)

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
        default = [0.5, 0.55, 0.45, 0.52, 0.48]
        entries = [summary_entry("base", "spp", 16, BASE),
                   summary_entry("better", "spp", 16, BETTER, stats.gain(BASE, BETTER, False)),
                   summary_entry("default", "spp", 16, default, stats.gain(BASE, default, False))]
        also = {"base": stats.gain(default, BASE, False), "better": stats.gain(default, BETTER,
                                                                                False)}
        techniques = {**document().techniques,
                      "default": results.TechniqueEntry("default", {"type": "path_mis"})}
        doc = document(techniques=techniques, also_baseline="default", summary=[
            dataclasses.replace(e, also_gain=({"sigma_over_mu": also[e.technique], "p_eff": None}
                                              if e.technique in also else {}))
            for e in entries])
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
        doc = document(experiment="paper/fig_5")
        self.assertIn(r"fig\_5", tables.latex("paper", [doc]))


if __name__ == "__main__":
    unittest.main()
