"""The include rule of renderer/README.md: a file includes its own directory and lower layers
only; directories of one layer are independent, and so is every technique folder. The layers
are read from the README's numbered list, so the rule and its documentation are one text."""
import pathlib
import re
import tempfile
import unittest

ROOT = pathlib.Path(__file__).resolve().parent.parent
LAYER_LINE = re.compile(r"^(\d+)\. ((?:`[a-z_]+/`(?:, )?)+):")
INCLUDE = re.compile(r'^\s*#include "([a-z_0-9]+)/([^"]+)"', re.MULTILINE)


def read_layers(readme: pathlib.Path) -> dict[str, int]:
    """Directory -> layer number, from lines such as "2. `sampling/`, `config/`: ..."."""
    layers = {}
    for line in readme.read_text().splitlines():
        match = LAYER_LINE.match(line)
        if match:
            for directory in re.findall(r"`([a-z_]+)/`", match.group(2)):
                layers[directory] = int(match.group(1))
    return layers


def unit_of(path: pathlib.PurePosixPath) -> str:
    """A file's directory as the rule sees it: techniques/<name> for a technique's files."""
    parts = path.parts
    return "/".join(parts[:2]) if parts[0] == "techniques" and len(parts) > 2 else parts[0]


def violations(source_root: pathlib.Path, layers: dict[str, int]) -> list[str]:
    """Every include in `source_root` that breaks the rule, as "file: includes target"."""
    found = []
    for file in sorted(source_root.rglob("*")):
        if file.suffix not in (".h", ".cpp", ".in"):
            continue
        relative = pathlib.PurePosixPath(file.relative_to(source_root).as_posix())
        here = unit_of(relative)
        if relative.parts[0] not in layers:
            found.append(f"{relative}: directory not in the layer list")
            continue
        for top, rest in INCLUDE.findall(file.read_text()):
            target = unit_of(pathlib.PurePosixPath(top, rest))
            if target == here:
                continue
            if top not in layers:
                found.append(f"{relative}: includes {top}/{rest}, which is in no layer")
            elif layers[top] >= layers[relative.parts[0]]:
                found.append(f"{relative}: includes {top}/{rest} (layer {layers[top]} from "
                             f"layer {layers[relative.parts[0]]})")
    return found


class Layering(unittest.TestCase):
    def test_the_readme_lists_every_source_directory(self):
        layers = read_layers(ROOT / "renderer" / "README.md")
        directories = {p.name for p in (ROOT / "renderer").iterdir() if p.is_dir()}
        self.assertEqual(set(layers), directories)

    def test_no_include_points_up_or_sideways(self):
        layers = read_layers(ROOT / "renderer" / "README.md")
        self.assertEqual(violations(ROOT / "renderer", layers), [])

    def test_the_check_finds_upward_sideways_and_cross_technique_includes(self):
        layers = {"math": 1, "io": 2, "config": 2, "scene": 3, "techniques": 6}
        files = {
            "math/vector.h": '#include "scene/shape.h"\n',             # upwards
            "io/exr_io.h": '#include "config/json_reader.h"\n',        # sideways
            "techniques/a/a.cpp": '#include "techniques/b/b.h"\n',      # another technique
            "techniques/b/b.h": '#include "techniques/b/c.h"\n#include "math/vector.h"\n',
            "scene/shape.h": '#include "scene/ray.h"\n#include "io/exr_io.h"\n',
        }
        with tempfile.TemporaryDirectory() as scratch:
            for name, text in files.items():
                path = pathlib.Path(scratch, name)
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(text)
            found = violations(pathlib.Path(scratch), layers)
        self.assertEqual(len(found), 3, found)
        self.assertTrue(found[0].startswith("io/exr_io.h: includes config/json_reader.h"))
        self.assertTrue(found[1].startswith("math/vector.h: includes scene/shape.h"))
        self.assertTrue(found[2].startswith("techniques/a/a.cpp: includes techniques/b/b.h"))


if __name__ == "__main__":
    unittest.main()
