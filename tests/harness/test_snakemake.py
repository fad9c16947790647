"""The workflow engine (experiments/Snakefile on Debian's Snakemake) against the harness's own:
a tiny experiment with a fixed-spp technique matched at equal time, run by each engine into a
scratch tree of its own ($HARNESS_OUTPUT_ROOT), reference included. Everything that does not
depend on how long a render took must come out equal: the equal-sample records and summaries,
the slopes of the technique that has no equal-time runs, the matched budgets' techniques and
spp, and the reference's pixels. A second Snakemake run finds nothing to do, until a config
changes: a variant's renders depend on its parent's file too.

With $SNAKEMAKE_TEST_PROFILE (a profile directory, e.g. experiments/profiles/slurm), Snakemake
runs the jobs through that profile instead of on 2 local cores: tests/cluster/slurm_test.sh
runs this test so on a single-node Slurm."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

from fixtures import from_root, load_config, tiny_matched
from harness import config, paths

RUN_PY = paths.ROOT / "experiments" / "run.py"
SNAKEFILE = paths.ROOT / "experiments" / "Snakefile"
TIME_DERIVED_METRICS = set(config.EFFICIENCY_OF)  # efficiencies divide by render time

def without_time(entry):
    """A run or summary entry without its time and what is derived from it."""
    out = {k: v for k, v in entry.items() if k != "time"}
    for field in ("metrics", "gain", "also_gain"):
        if isinstance(out.get(field), dict):
            out[field] = {m: v for m, v in out[field].items() if m not in TIME_DERIVED_METRICS}
    return out


def comparable(document):
    """The parts of a results document that do not depend on render times."""
    fixed = {t for t, d in document["techniques"].items() if d["fixed_spp"]}
    out = {k: v for k, v in document.items()
           if k not in ("provenance", "matched", "summary", "slopes", "runs", "reference")}
    # The reference's hash covers its EXR's metadata (render times); its pixels are compared
    # apart. Its noise ratio divides by the smallest error of any run, equal-time ones too.
    out["reference"] = {k: v for k, v in document["reference"].items()
                        if k not in ("sha256", "noise_ratio_to_smallest_error")}
    out["matched"] = [(m["technique"], m["spp"]) for m in document["matched"]]
    out["runs"] = [without_time(r) for r in document["runs"] if r["kind"] == "spp"]
    out["summary"] = [without_time(s) for s in document["summary"] if s["kind"] == "spp"]
    out["slopes"] = {t: s["vs_spp"] for t, s in document["slopes"].items() if t in fixed}
    return out


def run(args, root, cwd=None):
    env = {**os.environ, "HARNESS_OUTPUT_ROOT": str(root)}
    proc = subprocess.run([str(a) for a in args], env=env, cwd=cwd, capture_output=True,
                          text=True)
    if proc.returncode != 0:
        raise AssertionError(f"{' '.join(map(str, args[:3]))} failed: {proc.stdout[-2000:]}"
                             f"{proc.stderr[-2000:]}")
    return proc.stdout


@unittest.skipUnless(paths.renderer_binary().exists() and paths.metrics_binary().exists(),
                     "needs the renderer and metrics binaries (make build)")
class SnakemakeEngineTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        if shutil.which("snakemake") is None:
            raise AssertionError("snakemake is not installed: `make deps` installs it")
        scratch = tempfile.TemporaryDirectory()
        cls.addClassCleanup(scratch.cleanup)
        cls.root = Path(scratch.name)
        cls.exp = load_config(tiny_matched(), figure="tiny")
        # The same experiment again, as a variant of it: its reference has the same key, so
        # the workflow renders the halves once for both.
        cls.twin = load_config({"variant_of": from_root(cls.exp.file),
                                "description": "Matched equal time, end to end, again.",
                                "techniques": ["path", "path_mis"]}, figure="twin")
        cls.harness_root, cls.snakemake_root = cls.root / "harness", cls.root / "snakemake"
        for subcommand in ("references", "run"):
            run([sys.executable, RUN_PY, subcommand, cls.exp.file], cls.harness_root)
        profile = os.environ.get("SNAKEMAKE_TEST_PROFILE")
        engine = ["--profile", Path(profile).resolve()] if profile else ["--cores", "2"]
        cls.snakemake = [shutil.which("snakemake"), "results", "-s", SNAKEFILE, "--directory",
                         cls.snakemake_root, *engine, "--config", "profile=quick",
                         f"configs={cls.exp.file} {cls.twin.file}"]
        cls.snakemake_root.mkdir()
        run(cls.snakemake, cls.snakemake_root)
        cls.documents = [json.loads((root / "results" / cls.exp.paper_name / "tiny.json")
                                    .read_text())
                         for root in (cls.harness_root, cls.snakemake_root)]

    def test_results_equal_the_harness_engines_but_for_times(self):
        harness, snakemake = map(comparable, self.documents)
        self.assertEqual(len(harness["runs"]), 20)  # 2 techniques × 2 spp × 5 seeds
        self.assertEqual(harness["matched"], [("path_mis", 8)])
        self.assertIn("path_mis", harness["slopes"])
        for part in harness:
            self.assertEqual(harness[part], snakemake[part], part)

    def test_the_matched_budget_was_rendered_by_the_second_phase(self):
        document = self.documents[1]
        seconds = document["matched"][0]["seconds"]
        renders = [r for r in document["runs"] if r["technique"] == "path"
                   and r["kind"] == "time" and r["budget"] == seconds]
        copies = [r for r in document["runs"] if r.get("duplicate_of")]
        self.assertEqual((len(renders), len(copies)), (5, 5))
        self.assertEqual(document["provenance"]["engine"], "snakemake")

    def test_the_references_have_the_same_pixels(self):
        self.assertSamePixels(self.harness_root / "reference" / self.exp.paper_name / "tiny.quick.exr",
                              self.snakemake_root / "reference" / self.exp.paper_name / "tiny.quick.exr")

    def test_an_experiment_of_the_same_key_shares_the_halves_and_renders_the_same(self):
        references = self.snakemake_root / "reference"
        manifest = json.loads((references / "manifest.json").read_text())
        tiny, twin = (manifest[f"{e.id}/quick"] for e in (self.exp, self.twin))
        self.assertEqual(tiny["key"], twin["key"])
        self.assertSamePixels(references / tiny["file"], references / twin["file"])
        document = json.loads((self.snakemake_root / "results" / self.twin.paper_name /
                               "twin.json").read_text())
        records = [[{k: v for k, v in r.items() if k != "file"} for r in comparable(d)["runs"]]
                   for d in (self.documents[1], document)]
        self.assertEqual(records[0], records[1])

    def assertSamePixels(self, a, b):
        answer = json.loads(subprocess.run(
            [str(paths.metrics_binary()), "compare", str(a), str(b), "--json"],
            capture_output=True, text=True, check=True).stdout)
        self.assertEqual(answer["rmse"], 0.0)

    def test_each_reference_half_ran_on_the_cpus_it_asked_for(self):
        # On Slurm, the CPUs of the job's allocation that its srun step could use.
        manifest = json.loads((self.snakemake_root / "reference" / "manifest.json").read_text())
        halves = manifest[f"{self.exp.id}/quick"]["halves"]
        self.assertEqual(len(halves), 2)
        for half in halves:
            self.assertGreaterEqual(half["cpus"], half["threads"])

    def test_a_second_run_has_nothing_to_do_until_the_reference_changes(self):
        dry_run = [*self.snakemake, "--dry-run", "--quiet", "rules"]
        out = run(dry_run, self.snakemake_root)
        self.assertNotIn("render", out)
        self.assertNotIn("assemble", out)
        # As if the harness's engine had rendered the reference again since (same key, new
        # hash): the stamp no longer matches, so the reference and every render are redone.
        stamps = list((self.snakemake_root / "reference" / ".stamps").rglob("tiny.*"))
        self.assertEqual(len(stamps), 1)
        stamps[0].write_text("0" * 64 + "\n")
        out = run(dry_run, self.snakemake_root)
        self.assertRegex(out, r"reference\s+1\b")
        self.assertRegex(out, r"render\s+20\b")  # the first phase; the checkpoint adds 5

    def test_editing_a_variants_parent_makes_the_variant_out_of_date(self):
        dry_run = [*self.snakemake, "--dry-run", "--quiet", "rules"]
        # Snakemake reruns for an input of new content, not for a new time alone.
        text = self.exp.file.read_text()
        self.addCleanup(self.exp.file.write_text, text)
        self.exp.file.write_text(text + "\n")
        out = run(dry_run, self.snakemake_root)
        # The first phases of both: the parent's and the variant's (the twin).
        self.assertRegex(out, r"render\s+40\b")
        self.assertRegex(out, r"assemble\s+2\b")


if __name__ == "__main__":
    unittest.main()
