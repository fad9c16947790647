"""Errors the harness reports to the user: bad input exits with status 2 and one message."""


class ConfigError(Exception):
    """Bad experiment input. `pointer` is the JSON pointer of the offending value."""

    def __init__(self, file, pointer, message):
        self.file, self.pointer, self.message = str(file), pointer, message
        where = f"{self.file}: {pointer}" if pointer else self.file
        super().__init__(f"{where}: {message}")


class HarnessFailure(Exception):
    """A step that should have worked did not (a render or a metrics call failed, a
    reference is missing or too noisy). Exit status 1."""
