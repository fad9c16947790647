"""Errors the harness reports to the user: bad input exits with status 2 and one message."""
import os
from pathlib import Path

# `renderer check --json`'s error kind for a third-party file (mesh, environment map) that is
# not on this machine, as opposed to "invalid".
MISSING_ASSET = "missing_asset"


class ConfigError(Exception):
    """Bad experiment input. `pointer` is the JSON pointer of the offending value."""

    def __init__(self, file: str | Path, pointer: str, message: str):
        self.file, self.pointer, self.message = str(file), pointer, message
        where = f"{self.file}: {pointer}" if pointer else self.file
        super().__init__(f"{where}: {message}")


class SceneRejected(ConfigError):
    """A scene document the renderer refused (`renderer check --json`). `kind` is "invalid"
    or MISSING_ASSET."""

    def __init__(self, scene: str | Path, kind: str, pointer: str, message: str):
        super().__init__(scene, "", message)  # the renderer's message starts with the pointer
        self.kind, self.pointer = kind, pointer

    @property
    def skippable(self) -> bool:
        """An absent asset on a machine that may lack them: every one but CI, which has
        ../shared beside the checkout and sets REQUIRE_ASSETS=1."""
        return self.kind == MISSING_ASSET and os.environ.get("REQUIRE_ASSETS") != "1"


class HarnessFailure(Exception):
    """A step that should have worked did not (a render or a metrics call failed, a
    reference is missing or too noisy). Exit status 1."""
