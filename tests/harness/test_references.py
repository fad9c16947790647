"""References with the same key (scene document, integrator, resolution, spp; fixed seeds) are
the same image: the harness copies a current one instead of rendering it again, but not when
forced, and never from a file whose hash no longer matches its manifest entry. A render killed
after its first half resumes from it."""
import contextlib
import hashlib
import io
import json
import multiprocessing
import tempfile
import unittest
from pathlib import Path
from unittest import mock

from fixtures import load_config, valid
from harness import paths, references


def use_scratch_reference_directory(test: unittest.TestCase) -> None:
    """Points paths.REFERENCE and paths.MANIFEST into a temporary directory for one test."""
    scratch = tempfile.TemporaryDirectory()
    test.addCleanup(scratch.cleanup)
    root = Path(scratch.name)
    for name, value in (("REFERENCE", root / "reference"),
                        ("MANIFEST", root / "reference" / "manifest.json")):
        test.addCleanup(setattr, paths, name, getattr(paths, name))
        setattr(paths, name, value)


class SameKeyReferences(unittest.TestCase):
    def setUp(self):
        use_scratch_reference_directory(self)
        self.first = load_config(valid(), figure="first")
        self.second = load_config(valid(), figure="second")
        self.profile = self.second.profiles["quick"]
        image = b"an exr's bytes"
        file = references.file_name(self.first, self.first.profiles["quick"])
        (paths.REFERENCE / file).parent.mkdir(parents=True)
        (paths.REFERENCE / file).write_bytes(image)
        self.source = references.entry_name(self.first, self.first.profiles["quick"])
        paths.MANIFEST.write_text(json.dumps({self.source: {
            "file": str(file), "key": "K", "sha256": hashlib.sha256(image).hexdigest(),
            "spp": 64, "noise_sigma_over_mu": 0.01}}))
        for target, value in ((references, "key"), (references.renders, "render")):
            patcher = mock.patch.object(target, value, side_effect=self.fake(value))
            patcher.start()
            self.addCleanup(patcher.stop)

    @staticmethod
    def fake(what):
        if what == "key":
            return lambda exp, profile: "K"

        def render(*args, **kwargs):
            raise RuntimeError("rendered")
        return render

    def ensure(self, **kwargs):
        with contextlib.redirect_stdout(io.StringIO()):
            references.ensure([self.second], "quick", **kwargs)

    def test_a_current_reference_with_the_same_key_is_copied(self):
        self.ensure()
        manifest = json.loads(paths.MANIFEST.read_text())
        entry = manifest[references.entry_name(self.second, self.profile)]
        self.assertEqual(entry["copied_from"], self.source)
        self.assertEqual(entry["file"], str(references.file_name(self.second, self.profile)))
        self.assertEqual((paths.REFERENCE / entry["file"]).read_bytes(), b"an exr's bytes")
        self.assertEqual(references.status(self.second, self.profile), "ok")

    def test_forced_references_are_rendered(self):
        with self.assertRaisesRegex(RuntimeError, "rendered"):
            self.ensure(force=True)

    def test_a_file_that_no_longer_matches_its_entry_is_not_copied(self):
        entry = json.loads(paths.MANIFEST.read_text())[self.source]
        (paths.REFERENCE / entry["file"]).write_bytes(b"changed since")
        with self.assertRaisesRegex(RuntimeError, "rendered"):
            self.ensure()


class ResumedHalves(unittest.TestCase):
    """The halves live in a directory named by the key: a second attempt renders only the half
    the first did not finish, and the directory is removed once the halves are merged."""

    def setUp(self):
        use_scratch_reference_directory(self)
        paths.REFERENCE.mkdir()
        self.exp = load_config(valid())
        self.profile = self.exp.profiles["quick"]
        self.rendered_seeds = []
        self.kill_at_seed = None
        for target, value, fake in ((references, "key", lambda exp, profile: "K" * 64),
                                    (references.renders, "render", self.render),
                                    (references.jobs, "run_command", self.merge)):
            patcher = mock.patch.object(target, value, side_effect=fake)
            patcher.start()
            self.addCleanup(patcher.stop)

    def render(self, exp, profile, integrator, out, seed, **kwargs):
        if seed == self.kill_at_seed:
            raise KeyboardInterrupt("killed")
        self.rendered_seeds.append(seed)
        Path(out).write_bytes(f"half {seed}".encode())

    @staticmethod
    def merge(args):
        Path(args[args.index("--out") + 1]).write_bytes(b"merged")
        return json.dumps({"noise_rmse": 0.1, "noise_sigma_over_mu": 0.01})

    def render_reference(self):
        with contextlib.redirect_stdout(io.StringIO()):
            references.render_reference(self.exp, self.profile)

    def test_a_killed_render_resumes_from_its_finished_half(self):
        first, second = (references.renders.REFERENCE_SEED_BASE + i for i in range(2))
        self.kill_at_seed = second
        with self.assertRaises(KeyboardInterrupt):
            self.render_reference()
        self.assertEqual(self.rendered_seeds, [first])
        self.kill_at_seed = None
        self.render_reference()
        self.assertEqual(self.rendered_seeds, [first, second])
        entry = json.loads(paths.MANIFEST.read_text())[references.entry_name(self.exp,
                                                                            self.profile)]
        self.assertEqual([h["resumed"] for h in entry["halves"]], [True, False])
        self.assertEqual([h["seed"] for h in entry["halves"]], [first, second])
        self.assertEqual(list(paths.REFERENCE.glob(".halves-*")), [])

    def test_a_forced_render_does_not_resume(self):
        first, second = (references.renders.REFERENCE_SEED_BASE + i for i in range(2))
        self.kill_at_seed = second
        with self.assertRaises(KeyboardInterrupt):
            self.render_reference()
        self.kill_at_seed = None
        with contextlib.redirect_stdout(io.StringIO()):
            references.render_reference(self.exp, self.profile, reuse=False)
        self.assertEqual(self.rendered_seeds, [first, first, second])


def _write_entries(writer: int, count: int) -> None:
    """A forked process's part of the concurrent-writers test: `count` entries of its own."""
    for i in range(count):
        references.update_manifest_entry(f"writer{writer}/entry{i}", lambda _: {"i": i})


class ConcurrentManifestWriters(unittest.TestCase):
    """Parallel jobs (a workflow engine's) write entries of different experiments at once;
    each read-modify-write holds the manifest's lock, so none loses another's entry."""

    def test_no_entry_is_lost(self):
        use_scratch_reference_directory(self)
        paths.REFERENCE.mkdir(parents=True)
        writers, count = 4, 40
        context = multiprocessing.get_context("fork")  # the children keep the scratch paths
        processes = [context.Process(target=_write_entries, args=(w, count))
                     for w in range(writers)]
        for process in processes:
            process.start()
        for process in processes:
            process.join()
        self.assertEqual([p.exitcode for p in processes], [0] * writers)
        manifest = json.loads(paths.MANIFEST.read_text())
        self.assertEqual(len(manifest), writers * count)


if __name__ == "__main__":
    unittest.main()
