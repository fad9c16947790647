"""Experiment configs (configs/experiments/<paper>/<figure>.json): strict loading.

Every unknown key, wrong type or impossible value is a ConfigError naming its JSON pointer.
The schema is documented in configs/README.md ("Experiments")."""
import hashlib
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from . import paths
from .errors import ConfigError

# Metrics the `metrics compare` tool reports; True when larger is better.
METRICS = {
    "sigma_over_mu": False,
    "rmse": False,
    "mse": False,
    "relmse": False,
    "tvi_err": False,
    "p_eff": True,
    "mse_eff": True,
}
# Efficiencies are 1/(T·error): the error metric each one is built on.
EFFICIENCY_OF = {"p_eff": "tvi_err", "mse_eff": "mse"}
PROFILES = ("quick", "full")
MIN_SEEDS = 5
# Technique names become directory names and JSON-pointer segments.
NAME_PATTERN = re.compile(r"[A-Za-z0-9_-]+")
# The harness sets these per render; `set` may not.
HARNESS_OWNED = ("/integrator", "/render/spp", "/render/seed", "/render/resolution")
ABSENT = object()  # a missing key, as opposed to a JSON null
# `"table": {"seconds": "matched"}`: the equal-time rows at each fixed-spp technique's
# measured render time for the table's spp.
MATCHED = "matched"


@dataclass
class Profile:
    name: str
    resolution: tuple
    spp: list
    seconds: list
    seeds: int
    reference_spp: int
    table_spp: int
    table_seconds: float | str | None  # a seconds budget, MATCHED or None
    threads_per_job: int
    crop: tuple | None
    # spp budgets at which each fixed-spp technique's render time becomes an equal-time budget
    matched_spp: list = field(default_factory=list)


@dataclass
class Technique:
    name: str
    label: str
    integrator: dict
    fixed_spp: bool = False  # renders a fixed spp and cannot honour --time-limit


@dataclass
class PaperNumbers:
    source: str
    metric: str
    spp: int
    values: dict  # technique -> the paper's number


@dataclass
class ThresholdCheck:
    technique: str
    spp: int
    max_error: float | None
    min_gain: float | None


@dataclass
class Thresholds:
    profile: str
    method: str
    checks: list


@dataclass
class Experiment:
    id: str  # "<paper>/<figure>"
    file: Path
    config_sha256: str  # of the document without its thresholds (calibrating keeps results)
    description: str
    scene: Path
    overrides: dict
    techniques: dict  # name -> Technique, in config order
    baseline: str
    metrics: list  # the first is the primary metric
    reference_integrator: dict
    profiles: dict
    relmse_reject: float
    paper: list = field(default_factory=list)
    thresholds: Thresholds | None = None

    @property
    def paper_name(self):
        return self.id.split("/")[0]

    @property
    def figure(self):
        return self.id.split("/")[1]

    @property
    def primary_metric(self):
        return self.metrics[0]


class _Reader:
    """Typed access to one JSON object that remembers its pointer and rejects unknown keys."""

    def __init__(self, file, value, pointer=""):
        self.file, self.value, self.pointer = file, value, pointer
        if not isinstance(value, dict):
            self.fail("expected an object")
        self.used = set()

    def fail(self, message, key=None):
        pointer = self.pointer if key is None else f"{self.pointer}/{key}"
        raise ConfigError(self.file, pointer, message)

    def has(self, key):
        return key in self.value

    def raw(self, key, required=True, default=None):
        """The value at key; `default` when it is absent and optional. A JSON null is a
        value, which every typed accessor rejects."""
        self.used.add(key)
        if key not in self.value:
            if required:
                self.fail("required key is missing", key)
            return default
        return self.value[key]

    def child(self, key):
        return _Reader(self.file, self.raw(key), f"{self.pointer}/{key}")

    def string(self, key, required=True, default=None):
        v = self.raw(key, required, ABSENT)
        if v is ABSENT:
            return default
        if not (isinstance(v, str) and v):
            self.fail("expected a non-empty string", key)
        return v

    def integer(self, key, minimum, required=True, default=None):
        v = self.raw(key, required, ABSENT)
        if v is ABSENT:
            return default
        if not (isinstance(v, int) and not isinstance(v, bool)) or v < minimum:
            self.fail(f"expected an integer >= {minimum}", key)
        return v

    def positive(self, key, required=True, default=None):
        v = self.raw(key, required, ABSENT)
        if v is ABSENT:
            return default
        if not _is_positive_number(v):
            self.fail("expected a positive finite number", key)
        return float(v)

    def boolean(self, key, default):
        v = self.raw(key, False, ABSENT)
        if v is ABSENT:
            return default
        if not isinstance(v, bool):
            self.fail("expected true or false", key)
        return v

    def fraction(self, key, upper, default):
        v = self.raw(key, False, ABSENT)
        if v is ABSENT:
            return default
        if not (isinstance(v, (int, float)) and not isinstance(v, bool) and 0 <= v < upper):
            self.fail(f"expected a number in [0, {upper})", key)
        return float(v)

    def finish(self):
        unknown = sorted(set(self.value) - self.used)
        if unknown:
            self.fail(f"unknown key (expected one of: {', '.join(sorted(self.used))})",
                      unknown[0])


def _is_positive_number(v):
    return (isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
            and v > 0)


def _strictly_increasing(values):
    return all(a < b for a, b in zip(values, values[1:]))


def _reject_duplicate_keys(pairs):
    keys = [k for k, _ in pairs]
    duplicates = sorted({k for k in keys if keys.count(k) > 1})
    if duplicates:
        raise ValueError(f"duplicate key \"{duplicates[0]}\"")
    return dict(pairs)


def _reject_constant(name):
    raise ValueError(f"{name} is not JSON")


def load(file):
    """Loads and validates one experiment config. Raises ConfigError."""
    file = Path(file)
    try:
        text = file.read_text(encoding="utf-8")
    except OSError as e:
        raise ConfigError(file, "", f"cannot read: {e.strerror}") from None
    except UnicodeDecodeError as e:
        raise ConfigError(file, "", f"not UTF-8 text: {e.reason} at byte {e.start}") from None
    try:
        doc = json.loads(text, object_pairs_hook=_reject_duplicate_keys,
                         parse_constant=_reject_constant)
    except ValueError as e:
        raise ConfigError(file, "", f"malformed JSON: {e}") from None
    r = _Reader(file, doc)
    without_thresholds = {k: v for k, v in doc.items() if k != "thresholds"}
    exp = Experiment(
        id=paths.experiment_id(file),
        file=file,
        config_sha256=hashlib.sha256(
            json.dumps(without_thresholds, sort_keys=True).encode()).hexdigest(),
        description=r.string("description"),
        scene=_scene(r),
        overrides=_overrides(r),
        techniques=_techniques(r),
        baseline=r.string("baseline"),
        metrics=_metrics(r),
        reference_integrator=_reference(r),
        profiles=_profiles(r),
        relmse_reject=r.fraction("relmse_reject", 0.5, 0.0),
    )
    if exp.baseline not in exp.techniques:
        r.fail("must name one of the techniques", "baseline")
    if not any(t.fixed_spp for t in exp.techniques.values()):
        for profile in exp.profiles.values():
            if profile.matched_spp:
                raise ConfigError(file, f"/profiles/{profile.name}/matched_spp",
                                  "needs a technique with \"fixed_spp\": true (the budgets "
                                  "are the render times of such techniques)")
    if r.has("paper"):
        exp.paper = _paper(r, exp)
    if r.has("thresholds"):
        exp.thresholds = _thresholds(r, exp)
    r.finish()
    return exp


def _scene(r):
    scene = r.string("scene")
    path = (paths.ROOT / scene).resolve()
    if not path.is_file():
        r.fail(f"scene file not found: {scene} (paths are relative to the repository root)",
               "scene")
    return path


def _overrides(r):
    value = r.raw("set", required=False, default={})
    if not isinstance(value, dict):
        r.fail("expected an object of JSON pointer -> value", "set")
    for pointer in value:
        if not pointer.startswith("/"):
            r.fail(f"keys are JSON pointers starting with '/', got \"{pointer}\"", "set")
        owned = [p for p in HARNESS_OWNED if pointer == p or pointer.startswith(p + "/")]
        if owned:
            r.fail(f"{pointer} is set by the harness for each render (techniques, budgets, "
                   "seeds, profiles' resolution)", "set")
    return value


def _integrator(reader, key):
    value = reader.raw(key)
    if not isinstance(value, dict) or not isinstance(value.get("type"), str):
        reader.fail("expected an integrator object with a \"type\"", key)
    return value


def _techniques(r):
    t = r.child("techniques")
    if not t.value:
        t.fail("at least one technique is required")
    out = {}
    for name in t.value:
        if not NAME_PATTERN.fullmatch(name):
            t.fail("technique names use only letters, digits, '_' and '-'", name)
        tr = t.child(name)
        out[name] = Technique(name, tr.string("label", required=False, default=name),
                              _integrator(tr, "integrator"), tr.boolean("fixed_spp", False))
        tr.finish()
    t.finish()
    return out


def _metrics(r):
    value = r.raw("metrics")
    if not isinstance(value, list) or not value:
        r.fail("expected a non-empty list of metric names", "metrics")
    for i, m in enumerate(value):
        if m not in METRICS:
            r.fail(f"unknown metric \"{m}\" (known: {', '.join(METRICS)})", f"metrics/{i}")
    if len(set(value)) != len(value):
        r.fail("metrics are listed twice", "metrics")
    return value


def _reference(r):
    ref = r.child("reference")
    integrator = _integrator(ref, "integrator")
    ref.finish()
    return integrator


def _profiles(r):
    p = r.child("profiles")
    out = {name: _profile(p.child(name), name) for name in PROFILES}
    p.finish()
    return out


def _profile(p, name):
    res = p.raw("resolution")
    if not (isinstance(res, list) and len(res) == 2
            and all(isinstance(v, int) and not isinstance(v, bool) and v >= 1 for v in res)):
        p.fail("expected [width, height] with positive integers", "resolution")
    spp = p.raw("spp")
    if not (isinstance(spp, list) and spp
            and all(isinstance(v, int) and not isinstance(v, bool) and v >= 1 for v in spp)
            and _strictly_increasing(spp)):
        p.fail("expected a strictly increasing, non-empty list of positive integers", "spp")
    seconds = p.raw("seconds", required=False, default=[])
    if not (isinstance(seconds, list) and all(_is_positive_number(v) for v in seconds)
            and _strictly_increasing(seconds)):
        p.fail("expected a strictly increasing list of positive numbers", "seconds")
    seeds = p.integer("seeds", MIN_SEEDS)
    reference_spp = p.integer("reference_spp", 2)
    if reference_spp % 2:
        p.fail("must be even (the reference is two independent halves)", "reference_spp")
    matched_spp = p.raw("matched_spp", required=False, default=ABSENT)
    if matched_spp is ABSENT:
        matched_spp = []
    elif not (isinstance(matched_spp, list) and matched_spp
              and all(isinstance(v, int) and not isinstance(v, bool) for v in matched_spp)
              and _strictly_increasing(matched_spp)):
        p.fail("expected a strictly increasing, non-empty list of the profile's spp budgets",
               "matched_spp")
    for i, v in enumerate(matched_spp):
        if v not in spp:
            p.fail("must be one of the profile's spp budgets", f"matched_spp/{i}")
    table = p.child("table")
    table_spp = table.integer("spp", 1)
    if table_spp not in spp:
        table.fail("must be one of the profile's spp budgets", "spp")
    table_seconds = table.raw("seconds", required=False, default=ABSENT)
    if table_seconds is ABSENT:
        table_seconds = None
    elif table_seconds == MATCHED:
        if table_spp not in matched_spp:
            table.fail(f"\"{MATCHED}\" needs the table's spp ({table_spp}) in the profile's "
                       "matched_spp", "seconds")
    elif not (_is_positive_number(table_seconds) and table_seconds in seconds):
        table.fail(f"must be one of the profile's seconds budgets or \"{MATCHED}\"", "seconds")
    else:
        table_seconds = float(table_seconds)
    table.finish()
    crop = p.raw("crop", required=False)
    if crop is not None:
        ok = (isinstance(crop, list) and len(crop) == 4
              and all(isinstance(v, int) and not isinstance(v, bool) and v >= 0 for v in crop)
              and crop[2] > 0 and crop[3] > 0 and crop[0] + crop[2] <= res[0]
              and crop[1] + crop[3] <= res[1])
        if not ok:
            p.fail("expected [x, y, width, height] inside the image", "crop")
        crop = tuple(crop)
    profile = Profile(name, tuple(res), spp, [float(s) for s in seconds], seeds, reference_spp,
                      table_spp, table_seconds, p.integer("threads_per_job", 1, False, 1), crop,
                      matched_spp)
    p.finish()
    return profile


def _paper(r, exp):
    value = r.raw("paper")
    entries = value if isinstance(value, list) else [value]
    out = []
    for i, entry in enumerate(entries):
        pointer = "/paper" + (f"/{i}" if isinstance(value, list) else "")
        e = _Reader(r.file, entry, pointer)
        metric = e.string("metric")
        if metric not in exp.metrics:
            e.fail(f"\"{metric}\" is not one of the experiment's metrics", "metric")
        spp = e.integer("spp", 1)
        for profile in exp.profiles.values():
            if spp not in profile.spp:
                e.fail(f"the {profile.name} profile's spp budgets must include the paper's",
                       "spp")
        values = e.child("values")
        for name in values.value:
            if name not in exp.techniques:
                values.fail("not one of the techniques", name)
            values.positive(name)
        values.finish()
        out.append(PaperNumbers(e.string("source"), metric, spp, dict(values.value)))
        e.finish()
    return out


def _thresholds(r, exp):
    t = r.child("thresholds")
    if METRICS[exp.primary_metric] or exp.primary_metric in EFFICIENCY_OF:
        t.fail(f"thresholds need an error as the primary metric, not {exp.primary_metric}: an "
               "efficiency depends on the machine's speed, so a check on it could flake")
    profile = t.string("profile")
    if profile not in PROFILES:
        t.fail(f"expected one of {', '.join(PROFILES)}", "profile")
    method = t.string("method")
    checks_value = t.raw("checks")
    if not isinstance(checks_value, list) or not checks_value:
        t.fail("expected a non-empty list", "checks")
    checks = []
    for i in range(len(checks_value)):
        c = _Reader(r.file, checks_value[i], f"/thresholds/checks/{i}")
        technique = c.string("technique")
        if technique not in exp.techniques:
            c.fail("not one of the techniques", "technique")
        spp = c.integer("spp", 1)
        if spp not in exp.profiles[profile].spp:
            c.fail(f"not one of the {profile} profile's spp budgets", "spp")
        max_error = c.positive("max_error", required=False)
        min_gain = c.positive("min_gain", required=False)
        if max_error is None and min_gain is None:
            c.fail("give max_error, min_gain or both")
        if min_gain is not None and technique == exp.baseline:
            c.fail("the baseline has no gain over itself", "min_gain")
        checks.append(ThresholdCheck(technique, spp, max_error, min_gain))
        c.finish()
    t.finish()
    return Thresholds(profile, method, checks)
