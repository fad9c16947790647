"""Where things live: the repository root, the binaries, results, references."""
import os
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CONFIGS = ROOT / "configs" / "experiments"
SCHEMAS = ROOT / "configs" / "schema"  # JSON Schemas of the configs, one per kind
RESULTS = ROOT / "results"
RENDERS = RESULTS / "renders"  # per-run EXRs, git-ignored
TABLES = RESULTS / "tables"
PLOTS = RESULTS / "plots"
REFERENCE = ROOT / "reference"
MANIFEST = REFERENCE / "manifest.json"


def build_dir():
    return Path(os.environ.get("BUILD", ROOT / "build"))


def renderer_binary():
    return Path(os.environ.get("RENDERER_BINARY", build_dir() / "bin" / "renderer"))


def metrics_binary():
    return Path(os.environ.get("METRICS_BINARY", build_dir() / "bin" / "metrics"))


def experiment_id(config_path):
    """configs/experiments/<paper>/<figure>.json -> "<paper>/<figure>"."""
    p = Path(config_path).resolve()
    return f"{p.parent.name}/{p.stem}"


def suffix(profile_name):
    """File-name suffix of a profile's outputs: none for quick (the committed set), ".full"
    for full, so running the full profile never overwrites the quick one."""
    return "" if profile_name == "quick" else f".{profile_name}"


def results_file(exp, profile_name):
    return RESULTS / exp.paper_name / f"{exp.figure}{suffix(profile_name)}.json"


def all_experiment_configs():
    return sorted(CONFIGS.glob("*/*.json"))


def relative(path):
    try:
        return str(Path(path).resolve().relative_to(ROOT))
    except ValueError:
        return str(path)
