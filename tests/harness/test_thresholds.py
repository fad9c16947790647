"""CI thresholds: the check passes at the stored limits and fails once a limit is tightened
below the measurement (so the CI check can fail); calibration is mean + 4 sd, gain - 4 s.e."""
import json
import math
import unittest

from fixtures import load_config, results_document, summary_entry, valid
from harness import stats, thresholds
from harness.errors import HarnessFailure
from harness.results import ConfigFile

# Seeds' σ/µ: baseline mean 0.6, technique mean 0.25 -> gain 2.4.
BASE = [0.58, 0.60, 0.62, 0.59, 0.61]
BETTER = [0.24, 0.25, 0.26, 0.245, 0.255]


def summary():
    g = stats.gain(BASE, BETTER, False)
    return [summary_entry("base", "spp", 16, BASE), summary_entry("better", "spp", 16, BETTER, g)]


class EvaluateTest(unittest.TestCase):
    def verdicts(self, max_error, min_gain):
        doc = valid()
        doc["thresholds"]["checks"][0].update(max_error=max_error, min_gain=min_gain)
        return thresholds.evaluate(load_config(doc), summary())

    def test_passes_above_the_measurement(self):
        v = self.verdicts(0.3, 2.0)
        self.assertEqual([x.passed for x in v], [True, True])
        self.assertAlmostEqual(v[0].measured, 0.25)
        self.assertAlmostEqual(v[1].measured, 2.4)

    def test_fails_when_tightened_below_the_measurement(self):
        v = self.verdicts(0.249, 2.41)
        self.assertEqual([x.passed for x in v], [False, False])
        text = thresholds.format_verdicts(load_config(valid()), v)
        self.assertIn("FAIL better at 16 spp: sigma_over_mu 0.25 (must be <= 0.249)", text)


class CalibrateTest(unittest.TestCase):
    def test_keeps_a_minimum_margin_from_a_noiseless_measurement(self):
        exp = load_config(valid())
        same = [0.25] * 5
        rows = [summary_entry("base", "spp", 16, [0.5] * 5),
                summary_entry("better", "spp", 16, same, stats.gain([0.5] * 5, same, False))]
        results = results_document(
            summary=rows, config=ConfigFile(str(exp.file), exp.profile_sha256["quick"]))
        better = thresholds.calibrate(exp, results, [16]).checks[1]
        self.assertEqual(better.max_error, 0.255)  # 0.25 · 1.02
        self.assertEqual(better.min_gain, 1.96)  # 2 / 1.02 = 1.9608, rounded down

    def test_refuses_results_of_another_config(self):
        results = results_document()  # another config's hash
        with self.assertRaises(HarnessFailure):
            thresholds.calibrate(load_config(valid()), results, [16])

    def test_mean_plus_four_sd_and_gain_minus_four_stderr(self):
        exp = load_config(valid())
        results = results_document(
            summary=summary(), config=ConfigFile(str(exp.file), exp.profile_sha256["quick"]))
        block = thresholds.calibrate(exp, results, [16])
        better = [c for c in block.checks if c.technique == "better"][0]
        e = stats.estimate(BETTER)
        self.assertGreaterEqual(better.max_error, e.mean + 4 * e.sd)
        self.assertLess(better.max_error, e.mean + 4 * e.sd + 0.001)  # rounded up, 3 digits
        g = stats.gain(BASE, BETTER, False)
        floor = min(g.value * math.exp(-4 * g.stderr / g.value), g.value / 1.02)
        self.assertLessEqual(better.min_gain, floor)
        self.assertGreater(better.min_gain, floor - 0.01)
        self.assertIn("mean + 4 sd", block.method)
        self.assertIsNone([c for c in block.checks if c.technique == "base"][0].min_gain)
        printed = json.loads(thresholds.format_block(block))["thresholds"]
        self.assertEqual(printed["checks"][0], {"technique": "base", "spp": 16,
                                                "max_error": block.checks[0].max_error})


if __name__ == "__main__":
    unittest.main()
