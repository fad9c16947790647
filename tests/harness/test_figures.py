"""The RIS fig. 1 script's exact densities of resampling: each integrates to 1, M = 2 and M = 8
lie between p (M = 1) and ĝ normalised (M = ∞) where those differ most, and the streamed
reservoir's histogram for M = 2 follows the M = 2 density. TAIS's gain against image size,
measured from the spread over seeds, finds a known ratio of noise levels."""
import unittest

import numpy as np

import fixtures  # noqa: F401  (puts the harness on the path)
from figures import ris_fig01_resampling as fig1
from figures import tais_gain_vs_size


class ResamplingDensityTest(unittest.TestCase):
    def setUp(self):
        self.rng = np.random.default_rng(7)
        self.y = (np.arange(2000) + 0.5) / 2000 * fig1.HALF_PI

    def test_densities_integrate_to_one(self):
        for m in (2, 8):
            total = fig1.exact_density(m, self.y, self.rng).sum() * fig1.HALF_PI / len(self.y)
            self.assertAlmostEqual(total, 1.0, delta=2e-3, msg=f"M = {m}")

    def test_finite_m_interpolates_between_p_and_g(self):
        peak = np.array([0.26])  # the first sin⁴ peak: ĝ normalised ≈ 1.24 > p ≈ 0.64
        g = fig1.target(peak) / (1 + 3 * np.pi / 16)
        d2 = fig1.exact_density(2, peak, self.rng)
        d8 = fig1.exact_density(8, peak, self.rng)
        self.assertTrue(fig1.P < d2[0] < d8[0] < g[0], (fig1.P, d2, d8, g))

    def test_reservoir_follows_the_exact_m2_density(self):
        samples = fig1.resample(2, self.rng)
        counts, edges = np.histogram(samples, bins=30, range=(0, fig1.HALF_PI))
        width = edges[1] - edges[0]
        points = (edges[:-1, None] + (np.arange(8) + 0.5) / 8 * width).ravel()
        density = fig1.exact_density(2, points, self.rng).reshape(-1, 8).mean(axis=1)
        expected = density * width * len(samples)
        # Per-bin z of Poisson counts; 30 bins, Šidák-corrected 1 %: |z| < 3.8.
        z = (counts - expected) / np.sqrt(expected)
        self.assertLess(np.abs(z).max(), 3.8)


class SpreadOverSeedsTest(unittest.TestCase):
    def test_the_gain_of_half_the_noise_is_two(self):
        rng = np.random.default_rng(3)
        mean = rng.uniform(0.5, 2.0, size=(32, 48, 3))
        baseline = mean + rng.normal(0, 0.2, size=(5, 32, 48, 3))
        tais = mean + rng.normal(0, 0.1, size=(5, 32, 48, 3))
        gain, low, high = tais_gain_vs_size.gain_with_interval(baseline, tais)
        self.assertLess(low, 2.0)
        self.assertGreater(high, 2.0)
        self.assertAlmostEqual(gain, 2.0, delta=0.05)
        # the same noise: no gain
        gain, low, high = tais_gain_vs_size.gain_with_interval(baseline, baseline)
        self.assertEqual((gain, low, high), (1.0, 1.0, 1.0))


if __name__ == "__main__":
    unittest.main()
