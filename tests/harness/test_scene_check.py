"""`renderer check --json` as the harness reads it: a valid scene's answer, a rejected scene's
error kind and pointer, and scenes with an absent asset skipped unless REQUIRE_ASSETS=1."""
import contextlib
import io
import json
import os
import tempfile
import unittest
from pathlib import Path
from unittest import mock

import fixtures  # noqa: F401  (puts the harness on the path)
import previews
import run
from harness import paths, renders
from harness.errors import MISSING_ASSET, HarnessFailure, SceneRejected

SCENE = {
    "camera": {"type": "pinhole", "position": [0, 0, 3], "look_at": [0, 0, 0]},
    "materials": {"white": {"type": "lambert"}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "white"}],
    "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 5}],
}
ABSENT_MESH = {"type": "mesh", "file": "meshes/absent_for_test.ply", "material": "white"}


def with_environment(**values):
    """os.environ with REQUIRE_ASSETS as given (absent when not)."""
    environment = {k: v for k, v in os.environ.items() if k != "REQUIRE_ASSETS"}
    return mock.patch.dict(os.environ, {**environment, **values}, clear=True)


@unittest.skipUnless(paths.renderer_binary().exists(), "needs the renderer (make build)")
class SceneCheckTest(unittest.TestCase):
    def setUp(self):
        scratch = tempfile.TemporaryDirectory()
        self.addCleanup(scratch.cleanup)
        self.dir = Path(scratch.name)
        self.valid = self.write("valid.json", SCENE)
        self.absent = self.write("absent.json", {**SCENE, "shapes": [ABSENT_MESH]})

    def write(self, name, scene):
        file = self.dir / name
        file.write_text(json.dumps(scene))
        return file

    def rejection(self, *args):
        with self.assertRaises(SceneRejected) as caught:
            renders.check(args)
        return caught.exception

    def test_a_valid_scene_answers_its_settings_and_hash(self):
        check = renders.check([self.valid, "--resolution", "8x4"])
        self.assertEqual((check.integrator, check.resolution), ("path_mis", (8, 4)))
        self.assertRegex(check.scene_sha256, r"^[0-9a-f]{64}$")
        self.assertNotEqual(renders.check([self.valid]).scene_sha256, check.scene_sha256)

    def test_the_estimand_hash_ignores_only_how_the_image_is_estimated(self):
        scene = self.write("with_render.json", {**SCENE, "render": {"max_depth": 4}})
        base = renders.check([scene])
        for estimator_only in (
                ["--set", "/render/rr_depth=4", "--set", "/render/rr_threshold=1",
                 "--set", "/render/light_selection=uniform", "--set", "/render/sampler=stratified",
                 "--set", "/render/spp=7", "--set", "/render/seed=3",
                 "--set", '/description="another"'],
                ["--set", "/render/rr_survival=0.5"]):
            with self.subTest(estimator_only):
                check = renders.check([scene, *estimator_only])
                self.assertNotEqual(check.scene_sha256, base.scene_sha256)
                self.assertEqual(check.estimand_sha256, base.estimand_sha256)
        for image_changing in (["--set", "/render/max_depth=2"],
                               ["--set", "/shapes/0/radius=0.4"],
                               ["--resolution", "8x4"],
                               ["--set", '/integrator={"type": "direct"}']):
            with self.subTest(image_changing):
                self.assertNotEqual(renders.check([scene, *image_changing]).estimand_sha256,
                                    base.estimand_sha256)

    def test_an_absent_asset_is_told_apart_by_its_kind(self):
        e = self.rejection(self.absent)
        self.assertEqual((e.kind, e.pointer), (MISSING_ASSET, "/shapes/0/file"))
        with with_environment():
            self.assertTrue(e.skippable)
        with with_environment(REQUIRE_ASSETS="1"):
            self.assertFalse(e.skippable)

    def test_an_invalid_scene_is_never_skipped(self):
        e = self.rejection(self.valid, "--set", "/shapes/0/radius=-1")
        self.assertEqual((e.kind, e.pointer), ("invalid", "/shapes/0/radius"))
        self.assertIn("/shapes/0/radius", str(e))
        with with_environment():
            self.assertFalse(e.skippable)

    def test_no_answer_is_a_failure(self):
        with self.assertRaises(HarnessFailure):
            renders.check([self.valid, "--no-such-option"])

    def test_validate_skips_a_scene_with_an_absent_asset_unless_assets_are_required(self):
        with mock.patch.object(paths, "SCENES", self.dir), with_environment():
            out = io.StringIO()
            with contextlib.redirect_stdout(out):
                run.validate_scenes()
            self.assertIn("absent.json: skipped, an asset is absent (/shapes/0/file: ",
                          out.getvalue())
            self.assertIn("valid.json: valid", out.getvalue())
        with mock.patch.object(paths, "SCENES", self.dir), with_environment(REQUIRE_ASSETS="1"):
            with contextlib.redirect_stdout(io.StringIO()), self.assertRaises(SceneRejected):
                run.validate_scenes()

    def test_previews_give_an_absent_asset_a_blank_tile_unless_assets_are_required(self):
        with with_environment():
            self.assertEqual(previews.preview(self.absent, 8, 1),
                             (None, "absent\n(asset absent)", None))
        with with_environment(REQUIRE_ASSETS="1"):
            image, label, failure = previews.preview(self.absent, 8, 1)
            self.assertEqual((image, label), (None, "absent\n(does not load)"))
            self.assertIn("/shapes/0/file", failure)


if __name__ == "__main__":
    unittest.main()
