"""The harness's modules import one another without a cycle, typing-only imports included:
a cycle makes the import order matter and hides which module is the lower layer."""
import ast
import tempfile
import unittest
from pathlib import Path

from harness import paths

HARNESS = paths.ROOT / "experiments" / "harness"


def module_imports(file: Path) -> set[str]:
    """The harness modules `file` imports outside function bodies (`from . import x`,
    `from .x import y`, also under `if TYPE_CHECKING:`); imports inside a function are lazy
    by intent and left out."""
    found: set[str] = set()

    def visit(nodes: list[ast.stmt]) -> None:
        for node in nodes:
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                if node.module:
                    found.add(node.module.split(".")[0])
                else:
                    found.update(alias.name for alias in node.names)
            elif isinstance(node, (ast.If, ast.Try)):
                visit(node.body)
                visit(node.orelse)
                for handler in getattr(node, "handlers", []):
                    visit(handler.body)

    visit(ast.parse(file.read_text()).body)
    return found


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle of `graph` as [a, b, ..., a], or None."""
    done: set[str] = set()

    def walk(module: str, path: list[str]) -> list[str] | None:
        for dep in sorted(graph.get(module, ())):
            if dep in path:
                return path[path.index(dep):] + [dep]
            if dep not in done:
                cycle = walk(dep, path + [dep])
                if cycle:
                    return cycle
        done.add(module)
        return None

    for module in sorted(graph):
        cycle = walk(module, [module])
        if cycle:
            return cycle
    return None


class HarnessImportsTest(unittest.TestCase):
    def test_no_import_cycle(self):
        graph = {f.stem: module_imports(f) for f in HARNESS.glob("*.py")}
        self.assertIn("paths", graph["config"])  # the graph is read at all
        self.assertIsNone(find_cycle(graph))

    def test_a_typing_only_cycle_is_found(self):
        # Negative control: the cycle this test was written for (config <-> paths, the second
        # under `if TYPE_CHECKING:`) is read and detected.
        typing_only = ("from typing import TYPE_CHECKING\n"
                       "if TYPE_CHECKING:\n    from .config import X\n")
        with tempfile.TemporaryDirectory() as scratch:
            file = Path(scratch) / "paths.py"
            file.write_text(typing_only)
            self.assertEqual(module_imports(file), {"config"})
        self.assertEqual(find_cycle({"config": {"paths"}, "paths": {"config"}}),
                         ["config", "paths", "config"])


if __name__ == "__main__":
    unittest.main()
