#!/usr/bin/python3
"""Writes the stress scenes of `make stress` (configs/stress/*.json) and the maps and meshes
they use (configs/stress/maps, configs/stress/meshes): scenes built to break numerics, each
rendered by every technique (experiments/stress.py). Committed with its output; a stress scene
can also be written by hand: any scene document in configs/stress/ is run.

Every scene is small (a few dozen pixels across): the checks are per block of pixels against a
reference, and the point is the numerics, not the picture."""
import json
import re
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

HERE = Path(__file__).resolve().parent
RENDER = {"resolution": [24, 24], "max_depth": 8}


def lambert(albedo):
    return {"type": "lambert", "albedo": albedo}


def quad(corner, edge_u, edge_v, **more):
    return {"type": "quad", "corner": corner, "edge_u": edge_u, "edge_v": edge_v, **more}


def sphere(center, radius, **more):
    return {"type": "sphere", "center": center, "radius": radius, **more}


def write_scene(name: str, description: str, **document) -> None:
    """Indented, but each light on one line (one scene has 10^4 of them)."""
    scene = {"description": description, "render": document.pop("render", RENDER), **document}
    lights = scene.pop("lights")
    text = json.dumps(scene, indent=2)[:-2]
    # Arrays of numbers on one line.
    text = re.sub(r"\[\s+([-0-9.e+,\s]+?)\s+\]",
                  lambda m: "[" + ", ".join(m.group(1).replace(",", " ").split()) + "]", text)
    text += ',\n  "lights": [\n' + ",\n".join(
        "    " + json.dumps(light, separators=(",", ":")) for light in lights)
    (HERE / f"{name}.json").write_text(text + "\n  ]\n}\n")


# --- scale: one scene at 1 unit, 10^-4, 10^4, and 10^6 units from the origin -----------------

def base_scene(scale: float, offset: float) -> dict:
    """A floor, a diffuse and a glossy sphere, a square area light and a point light; points
    map to scale·p + offset, lengths scale, and the point light's intensity scales by scale²
    so that every variant renders the same image."""
    def p(v):
        return [scale * x + offset for x in v]

    def d(v):
        return [scale * x for x in v]
    return {
        "camera": {"position": p([0, 1.2, 3.2]), "look_at": p([0, 0.4, 0]), "fov": 45},
        "materials": {"floor": lambert(0.6), "diffuse": lambert([0.7, 0.5, 0.3]),
                      "glossy": {"type": "cook_torrance", "reflectance": 0.9, "roughness": 0.2}},
        "shapes": [
            quad(p([-2, 0, 2]), d([4, 0, 0]), d([0, 0, -4]), material="floor"),
            sphere(p([-0.5, 0.4, 0]), 0.4 * scale, material="diffuse"),
            sphere(p([0.5, 0.4, 0]), 0.4 * scale, material="glossy"),
            quad(p([-0.3, 2, -0.3]), d([0.6, 0, 0]), d([0, 0, 0.6]),
                 emission={"radiance": 15}),
        ],
        "lights": [{"type": "point", "position": p([1, 1.5, 1]), "intensity": 3 * scale ** 2}],
    }


def scale_scenes() -> None:
    what = ("a floor, a diffuse and a glossy sphere under a square area light and a point light "
            "(the point light's intensity scaled by the square of the scale, so the image is the "
            "same at every scale)")
    write_scene("scale_1", f"Scale reference: {what}, at 1 unit.", **base_scene(1, 0))
    write_scene("scale_1e-4", f"Scale: {what}, at 10^-4 units.", **base_scene(1e-4, 0))
    write_scene("scale_1e4", f"Scale: {what}, at 10^4 units.", **base_scene(1e4, 0))
    write_scene("offset_1e6", f"Far from the origin: {what}, at 1 unit, moved 10^6 units along "
                "every axis (float spacing there is 0.0625).", **base_scene(1, 1e6))


# --- grazing angles -----------------------------------------------------------------------------

def grazing_scene() -> None:
    tilt = np.tan(np.radians(0.1))  # 89.9° from the normal
    write_scene(
        "grazing",
        "Grazing: the camera looks along the floor at 89.9° to its normal; a square area light "
        "stands on the floor (its lower edge touching it) tilted to 89.9° from the floor's "
        "normal; a point light 10^-6 above the floor. Every camera ray passes through its pixel's "
        "centre: at this angle the horizon row's footprint spans the floor out to its far edge, "
        "and the strip the light reaches is a sliver of it, so sampling the footprint made those "
        "pixels heavy-tailed (at 256 spp a quarter of their mean, agreeing at 16,384): the film's "
        "integration, not the grazing numerics of the estimators this scene tests.",
        camera={"position": [0, 5 * tilt, 3], "look_at": [0, 0, -2], "fov": 30,
                "pixel_sample": "centre"},
        materials={"floor": lambert(0.6), "ball": lambert(0.5)},
        shapes=[
            quad([-4, 0, 4], [8, 0, 0], [0, 0, -8], material="floor"),
            sphere([0.6, 0.2, -0.5], 0.2, material="ball"),
            quad([-0.5, 0, -1], [0, 1, tilt], [1, 0, 0], emission={"radiance": 5}),
        ],
        lights=[{"type": "point", "position": [0.3, 1e-6, 0.5], "intensity": 0.5}],
    )


# --- materials at the bounds of their parameters ---------------------------------------------

def row_of_spheres(materials: dict) -> dict:
    names = list(materials)
    n = len(names)
    shapes = [sphere([1.1 * (i - (n - 1) / 2), 0.5, 0], 0.5, material=name)
              for i, name in enumerate(names)]
    shapes.append(quad([-6, 0, 3], [12, 0, 0], [0, 0, -6], material="floor"))
    shapes.append(quad([-1.5, 3, -1], [3, 0, 0], [0, 0, 1.5], emission={"radiance": 8}))
    return {
        "render": {"resolution": [8 * n, 12], "max_depth": 8},
        "camera": {"position": [0, 1.2, 5.5], "look_at": [0, 0.5, 0], "fov": 14 * n},
        "materials": {"floor": lambert(0.5), **materials},
        "shapes": shapes,
        "lights": [{"type": "environment", "radiance": [0.3, 0.35, 0.4]}],
    }


def material_scenes() -> None:
    write_scene(
        "materials_sharp",
        "Materials at their sharpest bounds, under a square light and a constant sky: Blinn "
        "roughness 10^-6 (exponent 10^6), Beckmann α 10^-4, Phong exponent 10^6, Ashikhmin-"
        "Shirley exponents 10^6 and 1, glass of ior 1.0001.",
        **row_of_spheres({
            "blinn": {"type": "blinn", "roughness": 1e-6},
            "beckmann": {"type": "cook_torrance", "roughness": 1e-4},
            "phong": {"type": "phong", "diffuse": 0, "specular": 1, "exponent": 1e6},
            "ashikhmin": {"type": "ashikhmin_shirley", "diffuse": 0.2, "specular": 0.8,
                          "exponent_u": 1e6, "exponent_v": 1},
            "glass": {"type": "dielectric", "ior": 1.0001},
        }))
    write_scene(
        "materials_rough",
        "Materials at their roughest bounds, under a square light and a constant sky: Blinn "
        "roughness 1, Beckmann α 2, Ashikhmin-Shirley exponents 1 and 10^6 (swapped), a "
        "Lafortune lobe whose directional albedo is 0.999 of the energy limit, glass of ior 4.",
        **row_of_spheres({
            "blinn": {"type": "blinn", "roughness": 1},
            "beckmann": {"type": "cook_torrance", "roughness": 2},
            "ashikhmin": {"type": "ashikhmin_shirley", "diffuse": 0.2, "specular": 0.8,
                          "exponent_u": 1, "exponent_v": 1e6},
            "lafortune": {"type": "lafortune",
                          "lobes": [{"c": [-1, -1, 1], "exponent": 4, "albedo": LAFORTUNE_ALBEDO}]},
            "glass": {"type": "dielectric", "ior": 4},
        }))


# Lobe albedo that puts the lobe's directional albedo at 0.999: `renderer check` with albedo 1
# reports the albedo the lobe reaches (its peak), and this is 0.999 over it.
LAFORTUNE_ALBEDO = 0.9542  # 0.999 / 1.047


# --- lights -------------------------------------------------------------------------------------

def write_map(name: str, pixels: np.ndarray) -> None:
    (HERE / "maps").mkdir(exist_ok=True)
    file = HERE / "maps" / name
    out = oiio.ImageOutput.create(str(file))
    spec = oiio.ImageSpec(pixels.shape[1], pixels.shape[0], 3, "float")
    spec.attribute("compression", "zip")
    out.open(str(file), spec)
    out.write_image(pixels.astype(np.float32))
    out.close()


def object_under(light: dict, description: str, name: str) -> None:
    write_scene(
        name, description,
        camera={"position": [0, 1, 3], "look_at": [0, 0.4, 0], "fov": 40},
        materials={"floor": lambert(0.5),
                   "glossy": {"type": "blinn", "roughness": 0.01},
                   "diffuse": lambert(0.7)},
        shapes=[quad([-3, 0, 3], [6, 0, 0], [0, 0, -6], material="floor"),
                sphere([-0.45, 0.4, 0], 0.4, material="diffuse"),
                sphere([0.45, 0.4, 0], 0.4, material="glossy")],
        lights=[light])


def light_scenes() -> None:
    sky = np.ones((16, 32, 3))
    sky[3, 9] = 1e6  # a sun texel 10^6 brighter than the rest
    write_map("sun.exr", sky)
    dark = np.zeros((16, 32, 3))
    dark[4, 20] = 100.0  # one lit texel, the rest black
    write_map("one_texel.exr", dark)
    object_under({"type": "environment", "file": "maps/sun.exr", "layout": "latlong"},
                 "An environment map (lat-long, 32 × 16) with one sun texel 10^6 brighter than "
                 "the rest.", "env_sun")
    object_under({"type": "environment", "file": "maps/one_texel.exr", "layout": "latlong"},
                 "An environment map (lat-long, 32 × 16) that is black but for one texel.",
                 "env_one_texel")

    rng = np.random.default_rng(7)
    grid = [(x, z) for x in np.linspace(-2, 2, 100) for z in np.linspace(-2, 2, 100)]
    lights = [{"type": "point", "position": [round(x, 4), round(float(rng.uniform(1, 2)), 4),
                                             round(z, 4)],
               "intensity": round(float(rng.uniform(0, 2e-3)), 7)} for x, z in grid]
    write_scene(
        "many_point_lights",
        "10^4 point lights on a 100 × 100 grid 1 to 2 units above a floor and two spheres, "
        "intensities uniform in [0, 0.002].",
        camera={"position": [0, 1, 3], "look_at": [0, 0.4, 0], "fov": 40},
        materials={"floor": lambert(0.5), "glossy": {"type": "blinn", "roughness": 0.05},
                   "diffuse": lambert(0.7)},
        shapes=[quad([-3, 0, 3], [6, 0, 0], [0, 0, -6], material="floor"),
                sphere([-0.45, 0.4, 0], 0.4, material="diffuse"),
                sphere([0.45, 0.4, 0], 0.4, material="glossy")],
        lights=lights)

    write_scene(
        "zero_power_and_tiny_lights",
        "Lights of zero power among others (a point light of intensity 0, a spot light of "
        "intensity 0), and a sphere light of radius 10^-5 "
        "(radiance 10^8, power about 0.4) beside a square light.",
        camera={"position": [0, 1, 3], "look_at": [0, 0.4, 0], "fov": 40},
        materials={"floor": lambert(0.5), "diffuse": lambert(0.7)},
        shapes=[quad([-3, 0, 3], [6, 0, 0], [0, 0, -6], material="floor"),
                sphere([0, 0.4, 0], 0.4, material="diffuse"),
                sphere([0.8, 0.9, 0.3], 1e-5, emission={"radiance": 1e8}),
                quad([-0.3, 2.5, -0.3], [0.6, 0, 0], [0, 0, 0.6], emission={"radiance": 4})],
        lights=[{"type": "point", "position": [1, 1.5, 1], "intensity": 0},
                {"type": "spot", "position": [-1, 1.5, 1], "look_at": [0, 0, 0],
                 "intensity": 0, "cone_angle": 30}])


# --- geometry -------------------------------------------------------------------------------------

def write_ply(name: str, vertices: list, faces: list) -> None:
    (HERE / "meshes").mkdir(exist_ok=True)
    lines = ["ply", "format ascii 1.0", f"element vertex {len(vertices)}", "property float x",
             "property float y", "property float z", f"element face {len(faces)}",
             "property list uchar int vertex_indices", "end_header"]
    lines += [" ".join(f"{c:g}" for c in v) for v in vertices]
    lines += [f"{len(f)} " + " ".join(map(str, f)) for f in faces]
    (HERE / "meshes" / name).write_text("\n".join(lines) + "\n")


def box(lo, hi, inward=False):
    """Vertices and outward (or inward) triangles of an axis-aligned box."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5)]
    faces = []
    for a, b, c, d in quads:
        tris = [(a, b, c), (a, c, d)]
        faces += [t[::-1] for t in tris] if inward else tris
    return v, faces


def geometry_scenes() -> None:
    v, f = box((-0.8, 0, -0.4), (-0.2, 0.6, 0.2))
    # Degenerate triangles: a repeated index, three collinear points, a sliver of area 1e-12.
    v += [(0.2, 0.1, 0), (0.5, 0.4, 0), (0.8, 0.7, 0), (0.2, 0.6, 0), (0.8, 0.6, 0),
          (0.5, 0.6 + 1e-12, 0)]
    n = len(v)
    f += [(0, 0, 1), (n - 6, n - 5, n - 4), (n - 3, n - 2, n - 1)]
    write_ply("degenerate.ply", v, f)
    # Duplicate vertices: every corner listed twice, each triangle using both copies.
    bv, bf = box((0.2, 0, -0.4), (0.8, 0.6, 0.2))
    dv = bv + bv
    df = [(a, b + len(bv), c) for a, b, c in bf]
    write_ply("duplicate_vertices.ply", dv, df)
    iv, ifaces = box((-0.3, 0, 0.4), (0.3, 0.5, 0.9), inward=True)
    write_ply("inverted_normals.ply", iv, ifaces)
    write_scene(
        "degenerate_geometry",
        "Meshes that break assumptions: a box with degenerate triangles beside it (a repeated "
        "index, collinear points, a sliver of area 10^-12); a box whose every vertex is listed "
        "twice; a box with inward (inverted) normals; two coincident quads of different "
        "materials (z-fighting) as the floor.",
        camera={"position": [0, 1.3, 3], "look_at": [0, 0.3, 0], "fov": 45},
        materials={"red": lambert([0.7, 0.2, 0.2]), "green": lambert([0.2, 0.7, 0.2]),
                   "grey": lambert(0.6), "glossy": {"type": "blinn", "roughness": 0.05}},
        shapes=[
            quad([-3, 0, 3], [6, 0, 0], [0, 0, -6], material="red"),
            quad([-3, 0, 3], [6, 0, 0], [0, 0, -6], material="green"),
            {"type": "mesh", "file": "meshes/degenerate.ply", "material": "grey"},
            {"type": "mesh", "file": "meshes/duplicate_vertices.ply", "material": "glossy",
             "normals": "smooth"},
            {"type": "mesh", "file": "meshes/inverted_normals.ply", "material": "grey"},
            quad([-0.3, 2.5, -0.3], [0.6, 0, 0], [0, 0, 0.6], emission={"radiance": 10}),
        ],
        lights=[{"type": "environment", "radiance": 0.2}])


# --- fog ------------------------------------------------------------------------------------------

def fog_scenes() -> None:
    shapes = [quad([-3, 0, 3], [6, 0, 0], [0, 0, -6], material="floor"),
              quad([-0.3, 2.5, -0.3], [0.6, 0, 0], [0, 0, 0.6], emission={"radiance": 10})]
    write_scene(
        "fog_dense",
        "Dense fog: a sphere filled with a medium of σt = 10^3 (σs 999, σa 1; an index-matched "
        "boundary) on a floor under a square light.",
        camera={"position": [0, 1, 3], "look_at": [0, 0.4, 0], "fov": 40},
        materials={"floor": lambert(0.5)},
        shapes=shapes + [sphere([0, 0.5, 0], 0.5, interior_medium={"sigma_a": 1,
                                                                   "sigma_s": 999})],
        lights=[{"type": "point", "position": [1, 1.5, 1], "intensity": 2}])
    write_scene(
        "fog_thin",
        "Nearly empty fog: the whole scene filled with a medium of σt = 10^-6, a diffuse "
        "sphere on a floor under a square light.",
        camera={"position": [0, 1, 3], "look_at": [0, 0.4, 0], "fov": 40},
        medium={"sigma_a": 5e-7, "sigma_s": 5e-7},
        materials={"floor": lambert(0.5), "diffuse": lambert(0.7)},
        shapes=shapes + [sphere([0, 0.4, 0], 0.4, material="diffuse")],
        lights=[{"type": "point", "position": [1, 1.5, 1], "intensity": 2}])


def main() -> None:
    scale_scenes()
    grazing_scene()
    material_scenes()
    light_scenes()
    geometry_scenes()
    fog_scenes()


if __name__ == "__main__":
    main()
