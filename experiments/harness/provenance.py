"""Provenance of results (git commit, machine) and atomic text and JSON output."""
import hashlib
import json
import os
import platform
import subprocess
import tempfile
from pathlib import Path
from typing import Any

from . import paths


def _git(*args: str) -> str | None:
    proc = subprocess.run(["git", "-C", str(paths.ROOT), *args], capture_output=True, text=True)
    return proc.stdout.strip() if proc.returncode == 0 else None


def git_commit() -> str | None:
    return _git("rev-parse", "HEAD")


def git_dirty() -> bool:
    """True when tracked sources differ from the commit (results/ and reference/ excluded,
    since runs write there)."""
    status = _git("status", "--porcelain", "--untracked-files=no", "--", ".",
                  ":(exclude)results", ":(exclude)reference")
    return bool(status)


def machine() -> dict[str, str | int]:
    cpu = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"hostname": platform.node(), "cpu": cpu, "cores": len(os.sched_getaffinity(0)),
            "os": platform.platform(), "python": platform.python_version()}


def sha256_file(path: str | Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def write_text_atomically(path: str | Path, text: str) -> None:
    """Writes through a temporary sibling renamed into place: no half-written outputs."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.NamedTemporaryFile("w", dir=path.parent, prefix=f".{path.name}.",
                                     suffix=".tmp", delete=False, encoding="utf-8") as f:
        f.write(text)
    os.chmod(f.name, 0o644)  # NamedTemporaryFile creates 0600
    os.replace(f.name, path)


def write_json_atomically(path: str | Path, value: Any) -> None:
    write_text_atomically(path, json.dumps(value, indent=1, ensure_ascii=False) + "\n")
