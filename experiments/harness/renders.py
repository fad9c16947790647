"""Command lines for the renderer and the metrics tool, built from an experiment."""
import json

from . import jobs, paths

# Reference halves use seeds far from the experiments' (0, 1, 2, ...), so a reference is
# independent of every image compared against it.
REFERENCE_SEED_BASE = 1 << 30


def scene_args(exp, profile, integrator):
    """`SCENE --set ... --resolution WxH` rendering `integrator` at the profile's size."""
    args = [exp.scene]
    for pointer, value in exp.overrides.items():
        args += ["--set", f"{pointer}={json.dumps(value)}"]
    args += ["--set", f"/integrator={json.dumps(integrator, sort_keys=True)}"]
    args += ["--resolution", f"{profile.resolution[0]}x{profile.resolution[1]}"]
    return args


def check_scene(exp, profile, integrator):
    """Validates the scene document a render would use (exit 2 from the renderer -> error);
    returns the document's sha256 (what renders record as renderer.sceneSha256)."""
    out = jobs.run_command([paths.renderer_binary(), "check",
                            *scene_args(exp, profile, integrator)])
    return out.split("scene sha256 ")[1].split()[0]


def render(exp, profile, integrator, out, seed, spp=None, seconds=None, threads=1):
    args = [paths.renderer_binary(), "render", *scene_args(exp, profile, integrator),
            "--seed", seed, "--threads", threads, "--no-preview", "--out", out]
    args += ["--time-limit", seconds] if seconds is not None else ["--spp", spp]
    jobs.run_command(args)


def compare(image, reference, relmse_reject=0.0):
    """`metrics compare --json` -> dict. relmse_reject: the fraction of pixels with the
    largest relMSE left out of it."""
    return json.loads(jobs.run_command([paths.metrics_binary(), "compare", image, reference,
                                        "--json", "--relmse-reject", repr(relmse_reject)]))


def slope(points, scratch_file):
    """`metrics slope --json` over [{"spp", "time", "error"}] -> dict."""
    scratch_file.write_text(json.dumps({"points": points}))
    return json.loads(jobs.run_command([paths.metrics_binary(), "slope", scratch_file, "--json"]))
