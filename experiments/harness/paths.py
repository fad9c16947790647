"""Where things live: the repository root, the binaries, results, references."""
from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # config imports this module
    from .config import Experiment

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs" / "experiments"
SCENES = ROOT / "configs" / "scenes"
SCHEMAS = ROOT / "configs" / "schema"  # JSON Schemas of the configs, one per kind
RESULTS = ROOT / "results"
RENDERS = RESULTS / "renders"  # per-run EXRs, git-ignored
TABLES = RESULTS / "tables"
PLOTS = RESULTS / "plots"
REFERENCE = ROOT / "reference"
MANIFEST = REFERENCE / "manifest.json"


def build_dir() -> Path:
    return Path(os.environ.get("BUILD", ROOT / "build"))


def renderer_binary() -> Path:
    return Path(os.environ.get("RENDERER_BINARY", build_dir() / "bin" / "renderer"))


def metrics_binary() -> Path:
    return Path(os.environ.get("METRICS_BINARY", build_dir() / "bin" / "metrics"))


def experiment_id(config_path: str | Path) -> str:
    """configs/experiments/<paper>/<figure>.json -> "<paper>/<figure>"."""
    p = Path(config_path).resolve()
    return f"{p.parent.name}/{p.stem}"


def suffix(profile_name: str) -> str:
    """File-name suffix of a profile's outputs: none for quick (the committed set), ".full"
    for full, so running the full profile never overwrites the quick one."""
    return "" if profile_name == "quick" else f".{profile_name}"


def results_file(exp: Experiment, profile_name: str) -> Path:
    return RESULTS / exp.paper_name / f"{exp.figure}{suffix(profile_name)}.json"


def all_experiment_configs() -> list[Path]:
    return sorted(CONFIGS.glob("*/*.json"))


def relative(path: str | Path) -> str:
    try:
        return str(Path(path).resolve().relative_to(ROOT))
    except ValueError:
        return str(path)
