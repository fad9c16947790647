#!/usr/bin/python3
"""`renderer serve` against `renderer render`: the same arguments give the same pixels and
metadata (all but the timings and the process's peak memory), whatever was served before, with
the scene built once or rebuilt after eviction, after a change to what the scene is built from
(resolution, camera, a material) and after an asset file changed on disk; bad requests get
status 2, one message naming the problem and no output, and the server goes on serving.
RENDERER_BINARY names the binary."""
import json
import os
import pathlib
import subprocess
import tempfile
import unittest

from pixel_hashes import read_exr

ROOT = pathlib.Path(__file__).resolve().parent.parent
RENDERER = os.environ.get("RENDERER_BINARY", str(ROOT / "build" / "bin" / "renderer"))
SCENES = ROOT / "configs" / "scenes"
CORNELL = str(SCENES / "cornell_spheres.json")
PENUMBRAE = str(SCENES / "twostage_fig10_penumbrae.json")
# What may differ between two renders of the same arguments.
UNDETERMINED = {"renderer.renderTime", "renderer.prepareTime", "renderer.peakMemoryMiB"}

# Name → arguments (before --out). Several integrators on one scene, so that a served render
# follows renders whose integrators kept state; a second scene; changes to what the scene is
# built from (resolution, camera, a material), which must not reuse the cached scene; and
# settings that reach only the integrator or the schedule (max_depth, seed, spp), which may.
JOBS = {
    "path_mis": [CORNELL, "--seed", "3", "--spp", "4"],
    "tais": [CORNELL, "--seed", "4", "--spp", "4", "--set",
             '/integrator={"type":"tais","maps":"auto","band_rows":8}'],
    "direct": [CORNELL, "--seed", "5", "--spp", "3", "--set",
               '/integrator={"type":"direct","strategy":"mis","light_samples":3,'
               '"bsdf_samples":2}'],
    "pmc_ip": [CORNELL, "--seed", "6", "--spp", "6", "--set",
               '/integrator={"type":"pmc_ip","initial_spp":2,"iteration_spp":4,'
               '"integrator":{"type":"direct","strategy":"mis"}}'],
    "two_stage": [PENUMBRAE, "--seed", "7", "--spp", "2", "--set",
                  '/integrator={"type":"two_stage","samples":4}'],
    "path_mis_depth3": [CORNELL, "--seed", "3", "--spp", "4", "--set", "/render/max_depth=3"],
    "path_mis_seed8": [CORNELL, "--seed", "8", "--spp", "5"],
    "path_mis_20x12": [CORNELL, "--seed", "3", "--spp", "4", "--resolution", "20x12"],
    "path_mis_fov50": [CORNELL, "--seed", "3", "--spp", "4", "--set", "/camera/fov=50"],
    "path_mis_red_walls": [CORNELL, "--seed", "3", "--spp", "4", "--set",
                           "/materials/white/albedo=[0.6,0.2,0.2]"],
}
COMMON = ["--threads", "2", "--no-preview"]


def arguments(args):
    """A job's arguments with the common options (24x16 unless it sets its resolution)."""
    resolution = [] if "--resolution" in args else ["--resolution", "24x16"]
    return [*args, *resolution, *COMMON]


def read(exr):
    spec, pixels = read_exr(exr)
    attributes = {a.name: a.value for a in spec.extra_attribs if a.name not in UNDETERMINED}
    # An integrator's own timings (pmc_ip's adapt_seconds) are not determined either.
    parameters = json.loads(attributes.pop("renderer.integratorParameters"))
    attributes["parameters"] = {k: v for k, v in parameters.items() if not k.endswith("seconds")}
    return list(spec.channelnames), pixels.tobytes(), attributes


class Server:
    def __init__(self, *options):
        # stderr goes to a file: a pipe nobody reads could fill and stall the server.
        self.errors = tempfile.TemporaryFile("w+")
        self.proc = subprocess.Popen([RENDERER, "serve", *options], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, stderr=self.errors, text=True)

    def send(self, line):
        self.proc.stdin.write(line + "\n")
        self.proc.stdin.flush()
        reply = self.proc.stdout.readline()
        if not reply:
            raise AssertionError(f"the server exited (status {self.proc.wait(timeout=60)}) "
                                 f"without answering {line!r}")
        return json.loads(reply)

    def render(self, args):
        return self.send(json.dumps(args))

    def close(self):
        self.proc.stdin.close()
        status = self.proc.wait(timeout=60)
        self.proc.stdout.close()
        self.errors.seek(0)
        errors = self.errors.read()
        self.errors.close()
        return status, errors


class ServeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.scratch = tempfile.TemporaryDirectory()
        cls.dir = pathlib.Path(cls.scratch.name)
        cls.expected = {}
        for name, args in JOBS.items():
            out = cls.dir / f"{name}.separate.exr"
            proc = subprocess.run([RENDERER, "render", *arguments(args), "--out", str(out)],
                                  capture_output=True, text=True)
            if proc.returncode != 0:
                raise RuntimeError(f"{name}: {proc.stderr}")
            cls.expected[name] = read(out)

    @classmethod
    def tearDownClass(cls):
        cls.scratch.cleanup()

    def serve_and_compare(self, server, order, tag):
        for name in order:
            out = self.dir / f"{name}.{tag}.exr"
            reply = server.render([*arguments(JOBS[name]), "--out", str(out)])
            self.assertEqual(reply["status"], 0, reply)
            self.assertEqual(len(reply["messages"]), 1, reply)  # the summary line
            self.assertIn(str(out), reply["messages"][0])
            channels, pixels, attributes = read(out)
            want_channels, want_pixels, want_attributes = self.expected[name]
            self.assertEqual(channels, want_channels, name)
            self.assertTrue(pixels == want_pixels, f"{name} ({tag}): pixels differ")
            self.assertEqual(attributes, want_attributes, name)

    def test_served_renders_equal_separate_ones_in_any_order(self):
        order = ["tais", "path_mis", "pmc_ip", "two_stage", "direct", "path_mis_seed8",
                 "path_mis_depth3", "path_mis_20x12", "path_mis", "path_mis_fov50",
                 "path_mis_red_walls", "path_mis", "tais"]
        for tag, options in (("cached", []), ("evicted", ["--cached-scenes", "1"]),
                             ("uncached", ["--cached-scenes", "0"])):
            server = Server(*options)
            try:
                self.serve_and_compare(server, order, tag)
            finally:
                status, errors = server.close()
            self.assertEqual(status, 0, errors)
            self.assertEqual(errors, "", tag)

    def test_a_changed_asset_file_rebuilds_the_scene(self):
        scene = {
            "render": {"resolution": [16, 12], "spp": 2},
            "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 50},
            "materials": {"grey": {"type": "lambert", "albedo": 0.5}},
            "shapes": [
                {"type": "mesh", "file": "triangle.obj", "material": "grey"},
                {"type": "quad", "corner": [-1, 1.5, -1], "edge_u": [2, 0, 0],
                 "edge_v": [0, 0, 2], "emission": {"radiance": 4}},
            ],
        }
        folder = self.dir / "asset_change"
        folder.mkdir()
        scene_file = folder / "scene.json"
        scene_file.write_text(json.dumps(scene))
        mesh = folder / "triangle.obj"
        args = [str(scene_file), *COMMON]
        server = Server()
        try:
            for corner in ("1 0 0", "1.6 0.4 0.2"):  # the second triangle is larger, and longer
                mesh.write_text(f"v -1 -1 0\nv {corner}\nv 0 1 0\nf 1 2 3\n")
                separate, served = folder / "separate.exr", folder / "served.exr"
                subprocess.run([RENDERER, "render", *args, "--out", str(separate)], check=True,
                               capture_output=True)
                reply = server.render([*args, "--out", str(served)])
                self.assertEqual(reply["status"], 0, reply)
                self.assertTrue(read(served)[1] == read(separate)[1], corner)
        finally:
            status, errors = server.close()
        self.assertEqual(status, 0, errors)

    def test_bad_requests_get_status_two_one_message_and_write_nothing(self):
        out = self.dir / "bad.exr"
        bad = {
            "not JSON": ("[unclosed", "one line of JSON"),
            "empty line": ("", "one line of JSON"),
            "not an array": ('{"scene": "x"}', "JSON array"),
            "not strings": ("[1, 2]", "string"),
            "unknown option": (json.dumps([CORNELL, "--bogus", "--out", str(out)]), "--bogus"),
            "missing scene": (json.dumps([str(self.dir / "absent.json"), "--out", str(out)]),
                              "absent.json"),
            "unknown key": (json.dumps([CORNELL, *COMMON, "--set", "/render/bogus=1",
                                        "--out", str(out)]), "/render/bogus"),
            "help": (json.dumps([CORNELL, "--help"]), "--help"),
        }
        server = Server()
        try:
            for what, (line, mentions) in bad.items():
                reply = server.send(line)
                self.assertEqual(reply["status"], 2, what)
                self.assertEqual(len(reply["messages"]), 1, (what, reply))
                self.assertIn(mentions, reply["messages"][0], what)
                self.assertFalse(out.exists(), what)
            self.serve_and_compare(server, ["path_mis"], "after_bad")
        finally:
            status, _ = server.close()
        self.assertEqual(status, 0)


if __name__ == "__main__":
    unittest.main()
