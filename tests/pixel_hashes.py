#!/usr/bin/python3
"""Pixel hashes of every scene in configs/scenes under every integrator, at a small size: the
proof that a refactoring left every render bit-identical.

  tests/pixel_hashes.py record HASHES.json   # before the change
  tests/pixel_hashes.py compare HASHES.json  # after it: lists every render that differs

Each render is 32x24 at 4 spp (path, path_mis, the three direct strategies with one and with
several samples, tais with 8-row bands so that bands and their warm-up rows are exercised,
path_mis with each structured sampler, every technique's estimator under direct and path_mis,
the techniques' integrators in their deterministic modes, and the scene's own integrator). A hash covers every channel of the EXR (radiance,
variance, sample count); a render the renderer refuses is recorded by its exit status and
message, so a changed error shows up too. RENDERER_BINARY names the binary (default
build/bin/renderer).
"""
import hashlib
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "experiments"))
from harness.exr import read_exr  # noqa: E402
RENDERER = os.environ.get("RENDERER_BINARY", str(ROOT / "build" / "bin" / "renderer"))

CONFIGURATIONS = {
    "path": ["--set", '/integrator={"type":"path"}'],
    "path_mis": ["--set", '/integrator={"type":"path_mis"}'],
    "direct_light": ["--set", '/integrator={"type":"direct","strategy":"light"}'],
    "direct_bsdf": ["--set", '/integrator={"type":"direct","strategy":"bsdf"}'],
    "direct_mis": ["--set", '/integrator={"type":"direct","strategy":"mis"}'],
    "direct_mis_3x2": ["--set", '/integrator={"type":"direct","strategy":"mis",'
                                '"light_samples":3,"bsdf_samples":2}'],
    "direct_light_4": ["--set", '/integrator={"type":"direct","strategy":"light",'
                                '"light_samples":4}'],
    "tais": ["--set", '/integrator={"type":"tais","maps":"auto","band_rows":8}'],
    "path_mis_stratified": ["--set", '/integrator={"type":"path_mis"}',
                            "--set", "/render/sampler=stratified"],
    "path_mis_hammersley": ["--set", '/integrator={"type":"path_mis"}',
                            "--set", "/render/sampler=hammersley"],
    # The techniques' estimators and integrators (their deterministic modes), and each
    # scene's own integrator as its file configures it.
    "as_configured": [],
    "direct_ris": ["--set", '/integrator={"type":"direct","estimator":'
                            '{"type":"ris","candidates":4,"samples":2}}'],
    "direct_ris_proxy": ["--set", '/integrator={"type":"direct","estimator":'
                                  '{"type":"ris","candidates":4,"source":"light_proxy"}}'],
    "direct_two_stage": ["--set", '/integrator={"type":"direct","estimator":'
                                  '{"type":"two_stage","samples":4}}'],
    "direct_pmc_hi": ["--set", '/integrator={"type":"direct","estimator":{"type":"pmc_hi"}}'],
    "path_mis_ris": ["--set", '/integrator={"type":"path_mis","estimator":'
                              '{"type":"ris","candidates":3}}'],
    "path_mis_pmc_hi": ["--set", '/integrator={"type":"path_mis","estimator":'
                                 '{"type":"pmc_hi","samples":6}}'],
    "ris_fixed": ["--set", '/integrator={"type":"ris","mode":"fixed","candidates":4,'
                           '"samples":2}'],
    "two_stage_variable": ["--set", '/integrator={"type":"two_stage","samples":4,'
                                    '"allocation":"variable","pilot_pixels":16,"band_rows":8}'],
    "pmc_ip": ["--set", '/integrator={"type":"pmc_ip","initial_spp":2,"iteration_spp":1,'
                        '"integrator":{"type":"path_mis"}}'],
}


def pixel_hash(exr):
    spec, pixels = read_exr(exr)
    digest = hashlib.sha256()
    digest.update(",".join(spec.channelnames).encode())
    digest.update(pixels.tobytes())
    return digest.hexdigest()


def render(scene, arguments, out):
    command = [RENDERER, "render", str(scene), "--resolution", "32x24", "--spp", "4",
               "--threads", "2", "--no-preview", "--out", str(out), *arguments]
    proc = subprocess.run(command, capture_output=True, text=True)
    if proc.returncode != 0:
        return f"exit {proc.returncode}: {proc.stderr.strip()}"
    return pixel_hash(out)


def all_hashes():
    hashes = {}
    scenes = sorted((ROOT / "configs" / "scenes").glob("*.json"))
    with tempfile.TemporaryDirectory() as scratch:
        out = pathlib.Path(scratch) / "render.exr"
        for scene in scenes:
            for name, arguments in CONFIGURATIONS.items():
                key = f"{scene.stem} {name}"
                hashes[key] = render(scene, arguments, out)
                print(f"{key}: {hashes[key][:16]}", flush=True)
    return hashes


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("record", "compare"):
        print(__doc__, file=sys.stderr)
        return 2
    command, file = sys.argv[1], pathlib.Path(sys.argv[2])
    hashes = all_hashes()
    if command == "record":
        file.write_text(json.dumps(hashes, indent=1, sort_keys=True) + "\n")
        print(f"recorded {len(hashes)} renders in {file}")
        return 0
    before = json.loads(file.read_text())
    changed = [k for k in sorted(set(before) | set(hashes)) if before.get(k) != hashes.get(k)]
    for key in changed:
        print(f"DIFFERS {key}:\n  before {before.get(key)}\n  after  {hashes.get(key)}")
    print(f"{len(hashes) - len(changed)} of {len(hashes)} renders identical, "
          f"{len(changed)} differ")
    return 1 if changed else 0


if __name__ == "__main__":
    sys.exit(main())
