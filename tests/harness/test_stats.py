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
        half_width = 2.570582 * math.sqrt(3.5) / math.sqrt(6)
        self.assertAlmostEqual(e.stderr, math.sqrt(3.5) / math.sqrt(6))
        self.assertAlmostEqual(e.ci95[0], 3.5 - half_width, places=5)
        self.assertAlmostEqual(e.ci95[1], 3.5 + half_width, places=5)

    def test_one_seed_has_no_interval(self):
        with self.assertRaises(ValueError):
            stats.estimate([1.0])


class GainTest(unittest.TestCase):
    def test_paired_ratio_of_means_and_delta_method_interval(self):
        # means 2 and 0.5 -> gain 4. Sample (co)variances: var_b = 0.02, var_t = 0.005,
        # cov = 0.01. With p = (1, -1): scaled = (1/2, -1/0.5) = (0.5, -2), so
        # var(log gain) = (0.25·0.02 + 4·0.005 - 2·0.5·2·0.01) / 2 = 0.0025, s.e. 0.05
        # (unpaired it would be sqrt(0.0125) = 0.112: the shared seeds' correlation counts).
        g = stats.gain([1.9, 2.1], [0.45, 0.55], higher_is_better=False)
        self.assertAlmostEqual(g.value, 4.0)
        self.assertAlmostEqual(g.stderr, 4.0 * 0.05)
        t = stats.t_quantile(2)  # 12.7062
        self.assertAlmostEqual(g.ci95[0], 4.0 * math.exp(-t * 0.05))
        self.assertAlmostEqual(g.ci95[1], 4.0 * math.exp(t * 0.05))

    def test_identical_techniques_have_gain_one_without_spread(self):
        g = stats.gain([0.3, 0.5, 0.4], [0.3, 0.5, 0.4], False)
        self.assertAlmostEqual(g.value, 1.0)
        self.assertAlmostEqual(g.stderr, 0.0)

    def test_efficiency_ratio_is_technique_over_baseline(self):
        g = stats.gain([0.05, 0.05], [0.15, 0.15], True)
        self.assertAlmostEqual(g.value, 3.0)

    def test_efficiency_is_a_ratio_of_means(self):
        # T = (1, 2), Err = (1, 1): 1/(mean T · mean Err) = 1/1.5, not mean(1/(T·Err)) = 0.75.
        e = stats.mean_power_product([[1.0, 2.0], [1.0, 1.0]], (-1, -1))
        self.assertAlmostEqual(e.value, 1 / 1.5)

    def test_unpaired_lengths_are_refused(self):
        with self.assertRaises(ValueError):
            stats.gain([1, 2, 3], [1, 2], False)

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

    def test_point_outside_band_with_interval_reaching_in_is_inconclusive(self):
        self.assertEqual(stats.verdict(self.gain(2.0, 1.0, 6.0), 5.0), "inconclusive")
        self.assertEqual(stats.verdict(self.gain(7.0, 6.0, 9.0), 5.0), "inconclusive")

    def test_weaker_and_stronger(self):
        self.assertEqual(stats.verdict(self.gain(3.9, 3.8, 3.95), 5.0), "weaker")
        self.assertEqual(stats.verdict(self.gain(6.3, 6.26, 6.4), 5.0), "stronger")

    def test_no_paper_number(self):
        self.assertEqual(stats.verdict(self.gain(2.0, 1.0, 3.0), None), "—")


if __name__ == "__main__":
    unittest.main()
