"""Where things live: the repository root, the binaries, results, references."""
from __future__ import annotations

import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs" / "experiments"
SCENES = ROOT / "configs" / "scenes"
SCHEMAS = ROOT / "configs" / "schema"  # JSON Schemas of the configs, one per kind
# What the harness writes lives under the repository, or under $HARNESS_OUTPUT_ROOT (its
# results/ and reference/) when that is set: a scratch tree for tests that run the harness in
# subprocesses, such as the workflow engine's (experiments/Snakefile).
OUTPUT_ROOT = Path(os.environ.get("HARNESS_OUTPUT_ROOT") or ROOT).resolve()
RESULTS = OUTPUT_ROOT / "results"
RENDERS = RESULTS / "renders"  # per-run EXRs, git-ignored
TABLES = RESULTS / "tables"
PLOTS = RESULTS / "plots"
REFERENCE = OUTPUT_ROOT / "reference"
MANIFEST = REFERENCE / "manifest.json"


def build_dir() -> Path:
    return Path(os.environ.get("BUILD", ROOT / "build"))


def renderer_binary() -> Path:
    return Path(os.environ.get("RENDERER_BINARY", build_dir() / "bin" / "renderer"))


def metrics_binary() -> Path:
    return Path(os.environ.get("METRICS_BINARY", build_dir() / "bin" / "metrics"))


def asset_environment() -> dict[str, str]:
    """The environment with this checkout's asset folders first on RENDERER_ASSETS: a binary
    built from another checkout (an older or a patched one) searches beside that one."""
    ours = [ROOT / "assets", ROOT.parent / "shared" / "assets"]
    given = os.environ.get("RENDERER_ASSETS")
    return {**os.environ,
            "RENDERER_ASSETS": ":".join([*map(str, ours), *([given] if given else [])])}


def experiment_id(config_path: str | Path) -> str:
    """configs/experiments/<paper>/<figure>.json -> "<paper>/<figure>"."""
    p = Path(config_path).resolve()
    return f"{p.parent.name}/{p.stem}"


def suffix(profile_name: str) -> str:
    """File-name suffix of a profile's outputs: none for quick (the committed set), ".full"
    for full, so running the full profile never overwrites the quick one."""
    return "" if profile_name == "quick" else f".{profile_name}"


def all_experiment_configs() -> list[Path]:
    return sorted(CONFIGS.glob("*/*.json"))


def relative(path: str | Path) -> str:
    """A path as results and manifests record it: relative to the repository root, or, for an
    output in a scratch tree (OUTPUT_ROOT), relative to that, so that the records read the same
    wherever they were written. Read them back with output()."""
    resolved = Path(path).resolve()
    # The deeper root first: either may lie inside the other.
    for root in sorted((OUTPUT_ROOT, ROOT), key=lambda r: len(r.parts), reverse=True):
        if resolved.is_relative_to(root):
            return str(resolved.relative_to(root))
    return str(path)


def output(recorded: str | Path) -> Path:
    """An output's path as relative() recorded it."""
    return OUTPUT_ROOT / recorded
