"""Seed statistics, gains and verdicts against hand-computed values."""
import math
import unittest

import fixtures  # noqa: F401  (puts the harness on the path)
from harness import stats


class EstimateTest(unittest.TestCase):
    def test_mean_sd_and_t_interval(self):
        # values 1..6: mean 3.5, sd = sqrt(17.5/5) = 1.870829; t(0.975, 5) = 2.570582
        e = stats.estimate([1, 2, 3, 4, 5, 6])
        self.assertAlmostEqual(e.mean, 3.5)
        self.assertAlmostEqual(e.sd, math.sqrt(3.5))
        self.assertAlmostEqual(stats.t_quantile(6), 2.570582, places=5)
        self.assertAlmostEqual(e.half_width, 2.570582 * math.sqrt(3.5) / math.sqrt(6), places=5)

    def test_one_seed_has_no_interval(self):
        with self.assertRaises(ValueError):
            stats.estimate([1.0])


class GainTest(unittest.TestCase):
    def test_error_ratio_and_delta_method_interval(self):
        base = stats.Estimate(mean=2.0, sd=0.2, n=5)  # relative sd 0.1
        tech = stats.Estimate(mean=0.5, sd=0.1, n=5)  # relative sd 0.2
        g = stats.gain(base, tech, higher_is_better=False)
        self.assertAlmostEqual(g.value, 4.0)
        log_se = math.sqrt(0.1 ** 2 / 5 + 0.2 ** 2 / 5)  # 0.1
        self.assertAlmostEqual(g.stderr, 4.0 * log_se)
        t = stats.t_quantile(5)  # 2.776445
        self.assertAlmostEqual(g.ci95[0], 4.0 * math.exp(-t * log_se))
        self.assertAlmostEqual(g.ci95[1], 4.0 * math.exp(t * log_se))

    def test_efficiency_ratio_is_technique_over_baseline(self):
        g = stats.gain(stats.Estimate(0.05, 0.0, 5), stats.Estimate(0.15, 0.0, 5), True)
        self.assertAlmostEqual(g.value, 3.0)

    def test_paper_gain_orientation(self):
        values = {"pt": 1.045, "tais": 0.207}
        self.assertAlmostEqual(stats.paper_gain(values, "pt", "tais", False), 1.045 / 0.207)
        self.assertAlmostEqual(stats.paper_gain({"a": 0.027, "b": 0.138}, "a", "b", True),
                               0.138 / 0.027)
        self.assertIsNone(stats.paper_gain(values, "pt", "other", False))


class VerdictTest(unittest.TestCase):
    def gain(self, value, lo, hi):
        return stats.Gain(value, 0.0, (lo, hi))

    def test_within_factor_is_reproduced(self):
        self.assertEqual(stats.verdict(self.gain(4.1, 4.0, 4.2), 5.0), "reproduced")  # 5/1.25=4

    def test_paper_inside_interval_is_reproduced(self):
        self.assertEqual(stats.verdict(self.gain(2.0, 1.0, 6.0), 5.0), "reproduced")

    def test_weaker_and_stronger(self):
        self.assertEqual(stats.verdict(self.gain(3.9, 3.8, 3.95), 5.0), "weaker")
        self.assertEqual(stats.verdict(self.gain(6.3, 6.26, 6.4), 5.0), "stronger")

    def test_no_paper_number(self):
        self.assertEqual(stats.verdict(self.gain(2.0, 1.0, 3.0), None), "—")


if __name__ == "__main__":
    unittest.main()
