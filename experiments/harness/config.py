"""Experiment configs (configs/experiments/<paper>/<figure>.json): strict loading.

The structure (keys, types, ranges) is configs/schema/experiment.schema.json, checked with
jsonschema. This module checks what a schema cannot say: values that must agree with other
fields (a baseline among the techniques, budgets among a profile's, a crop inside the image),
budgets in strictly increasing order, and a scene file that exists. Every error is one
ConfigError naming the JSON pointer of the bad value. The format is documented in
configs/README.md ("Experiments").

A variant ("variant_of": another experiment's file) is merged onto its parent first (_merged)
and the result checked as any experiment: many figures are also rendered through another film
with a few of their techniques, and full copies would drift from their parents."""
from __future__ import annotations

import copy
import functools
import hashlib
import json
import math
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import jsonschema
from jsonschema.exceptions import ValidationError, best_match
from jsonschema.protocols import Validator

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
    "relative_bias": False,
}
# Signed diagnostics: reported with their interval over seeds, never as a gain or a threshold
# (image mean / reference mean − 1: a biased technique's bias, e.g. TAIS's contribution filter).
SIGNED_METRICS = {"relative_bias"}
# Efficiencies are 1/(T·error): the error metric each one is built on.
EFFICIENCY_OF = {"p_eff": "tvi_err", "mse_eff": "mse"}
PROFILES = ("quick", "full")
# A fixed-spp technique's `"equal_time": "baseline"`: its render times set equal-time budgets
# at which only the baseline (and also_baseline) is rendered, not every technique.
BASELINE_ONLY = "baseline"
# `"table": {"seconds": "matched"}`: the equal-time rows at each fixed-spp technique's
# measured render time for the table's spp.
MATCHED = "matched"
SCHEMA_FILE = paths.SCHEMAS / "experiment.schema.json"
# The keys a variant inherits from its parent unless it gives them, then replaced whole.
VARIANT_REPLACES = ("scene", "metrics", "reference", "profiles", "relmse_reject",
                    "slope_time_range")

# An integrator object as the scene has it; the renderer checks its keys.
Integrator = dict[str, Any]


@dataclass
class Profile:
    name: str
    resolution: tuple[int, int]
    spp: list[int]
    seconds: list[float]
    seeds: int
    reference_spp: int
    table_spp: int
    table_seconds: float | str | None  # a seconds budget, MATCHED or None
    threads_per_job: int
    crop: tuple[int, int, int, int] | None
    # spp budgets at which each fixed-spp technique's render time becomes an equal-time budget
    matched_spp: list[int] = field(default_factory=list)


@dataclass
class Technique:
    name: str
    label: str
    integrator: Integrator
    fixed_spp: bool = False  # renders a fixed spp and cannot honour --time-limit
    # JSON pointers into the integrator where each spp budget goes (one pixel sample per render)
    samples_at: list[str] = field(default_factory=list)
    # JSON pointer -> value for this technique's renders, after the experiment's (`set`)
    overrides: dict[str, Any] = field(default_factory=dict)
    # A fixed-spp technique's render times set equal-time budgets (matched_spp) unless false;
    # BASELINE_ONLY: budgets at which only the baselines are rendered
    equal_time: bool | str = True
    # A time-capable technique whose render times at matched_spp set equal-time budgets (the
    # cross-paper matrix's default technique at the figure's spp), as a fixed-spp one's do
    sets_time: bool = False

    @property
    def sets_budgets(self) -> bool:
        """Its render times at the profile's matched_spp become equal-time budgets."""
        return self.sets_time or (self.fixed_spp and self.equal_time is not False)

    def integrator_for(self, spp: int) -> tuple[Integrator, int]:
        """The integrator a render of `spp` budget uses, and the pixel samples it takes."""
        if not self.samples_at:
            return self.integrator, spp
        integrator = copy.deepcopy(self.integrator)
        for pointer in self.samples_at:
            *parents, last = pointer.split("/")[1:]
            node = integrator
            for key in parents:
                node = node[key]
            node[last] = spp
        return integrator, 1


@dataclass
class PaperNumbers:
    source: str
    metric: str
    spp: int
    values: dict[str, float]  # technique -> the paper's number


@dataclass
class ThresholdCheck:
    technique: str
    spp: int
    max_error: float | None = None
    min_gain: float | None = None


@dataclass
class Thresholds:
    profile: str
    method: str
    checks: list[ThresholdCheck]


@dataclass(frozen=True)
class MatrixRow:
    """What a cross-paper matrix experiment (harness/matrix_configs.py) is a row of."""
    figure: str  # the experiment whose setup it takes
    transport: str  # "direct" or "paths": what its default technique estimates
    refused: dict[str, str]  # technique -> the renderer's reason; reported, never rendered


@dataclass
class Experiment:
    id: str  # "<paper>/<figure>"
    file: Path
    profile_sha256: dict[str, str]  # profile -> what results record as their config's hash
    description: str
    scene: Path
    overrides: dict[str, Any]  # JSON pointer -> value
    techniques: dict[str, Technique]  # in config order
    baseline: str
    also_baseline: str | None  # a second technique gains are measured against
    metrics: list[str]  # the first is the primary metric
    reference_integrator: Integrator
    profiles: dict[str, Profile]
    relmse_reject: float
    paper: list[PaperNumbers] = field(default_factory=list)
    thresholds: Thresholds | None = None
    # "common": slopes are fitted over the runs in the time range every technique covers
    slope_time_range: str = "all"
    variant_of: Path | None = None  # a variant's parent config, which it is merged onto
    matrix: MatrixRow | None = None  # only the cross-paper matrix's experiments

    @property
    def files(self) -> list[Path]:
        """The config files the experiment is read from: its own and a variant's parent's.
        Editing either changes the experiment, so a job that depends on one depends on both."""
        return [self.file, *([self.variant_of] if self.variant_of else [])]

    @property
    def paper_name(self) -> str:
        return self.id.split("/")[0]

    @property
    def figure(self) -> str:
        return self.id.split("/")[1]

    @property
    def primary_metric(self) -> str:
        return self.metrics[0]

    def results_file(self, profile_name: str) -> Path:
        """results/<paper>/<figure>[.<profile>].json (see paths.suffix)."""
        return paths.RESULTS / self.paper_name / f"{self.figure}{paths.suffix(profile_name)}.json"


def load(file: str | Path) -> Experiment:
    """Loads and validates one experiment config, or a variant merged onto its parent. Raises
    ConfigError."""
    file = Path(file)
    doc = _parse(file)
    _check_structure(file, doc)
    if "variant_of" not in doc:
        _check_agreement(file, doc)
        return _experiment(file, doc)
    parent_file, parent = _parent(file, doc)
    merged = _merged(file, doc, parent)
    try:
        _check_structure(file, merged)
        _check_agreement(file, merged)
    except ConfigError as e:
        raise _variant_error(e, doc) from None
    return _experiment(file, merged, parent_file)


def json_pointer(*keys: str | int) -> str:
    """RFC 6901: "/" before each key, and "~" and "/" inside keys escaped."""
    return "".join("/" + str(k).replace("~", "~0").replace("/", "~1") for k in keys)


def _check_structure(file: Path, doc: Any) -> None:
    """The schema: an experiment's structure, or a variant's own (before merging)."""
    error = best_match(_validator().iter_errors(doc))
    if error is not None:
        raise _schema_error(file, error)


def _check_agreement(file: Path, doc: dict[str, Any]) -> None:
    """What the schema cannot check (_disagreements) of a structurally valid experiment."""
    disagreement = next(_disagreements(doc), None)
    if disagreement is not None:
        raise ConfigError(file, *disagreement)


def _parent(file: Path, variant: dict[str, Any]) -> tuple[Path, dict[str, Any]]:
    """The file and document of the experiment a variant varies, checked as an experiment of
    its own first, so that an error in it names its file and its pointer. No chains: the
    merged result of a variant's variant would hang on two files the reader must combine."""
    name = variant["variant_of"]
    parent_file = (paths.ROOT / name).resolve()
    if not parent_file.is_file():
        raise ConfigError(file, "/variant_of", f"experiment config not found: {name} (paths "
                                               "are relative to the repository root)")
    parent = _parse(parent_file)
    if isinstance(parent, dict) and "variant_of" in parent:
        raise ConfigError(file, "/variant_of",
                          f"{name} is itself a variant (of {_abbreviated(parent['variant_of'])}"
                          "): name a whole experiment")
    _check_structure(parent_file, parent)
    _check_agreement(parent_file, parent)
    return parent_file, parent


def _merged(file: Path, variant: dict[str, Any], parent: dict[str, Any]) -> dict[str, Any]:
    """The experiment document a variant stands for: the parent's techniques it keeps (in its
    order) and its extra ones; the parent's `set` and then its own (a pointer both set takes
    its value, at its place, as if applied after the parent's); its baselines, or the
    parent's if kept; the parent's paper numbers of the kept techniques; its thresholds only
    (the parent's are limits of other renders); of VARIANT_REPLACES, its value or else the
    parent's. Raises ConfigError for a name the parent lacks or that clashes, or no baseline."""
    kept = variant["techniques"]
    for i, name in enumerate(kept):
        if name not in parent["techniques"]:
            raise ConfigError(file, json_pointer("techniques", i),
                              f"not one of {variant['variant_of']}'s techniques (known: "
                              f"{', '.join(parent['techniques'])})")
    extra = variant.get("extra_techniques", {})
    for name in extra:
        if name in kept:
            raise ConfigError(file, json_pointer("extra_techniques", name),
                              "the name of a kept technique")
    baseline = variant.get("baseline", parent["baseline"] if parent["baseline"] in kept else None)
    if baseline is None:
        raise ConfigError(file, "/baseline", f"required: the parent's baseline, "
                                             f"{parent['baseline']}, is not kept")
    merged = {key: variant.get(key, parent.get(key)) for key in VARIANT_REPLACES
              if key in variant or key in parent}
    merged.update(description=variant["description"], baseline=baseline,
                  techniques={**{name: parent["techniques"][name] for name in kept}, **extra})
    if "set" in parent or "set" in variant:
        ours = variant.get("set", {})
        merged["set"] = {**{pointer: value for pointer, value in parent.get("set", {}).items()
                            if pointer not in ours}, **ours}
    if "also_baseline" in variant:
        merged["also_baseline"] = variant["also_baseline"]
    elif parent.get("also_baseline") in kept and parent["also_baseline"] != baseline:
        merged["also_baseline"] = parent["also_baseline"]
    paper = [{**entry, "values": {t: v for t, v in entry["values"].items() if t in kept}}
             for _, entry in _paper_entries(parent)]
    paper = [entry for entry in paper if entry["values"]]
    if paper:
        merged["paper"] = paper if isinstance(parent["paper"], list) else paper[0]
    if "thresholds" in variant:
        merged["thresholds"] = variant["thresholds"]
    return merged


def _variant_error(error: ConfigError, variant: dict[str, Any]) -> ConfigError:
    """An error of a variant's merged document, said where the variant's author can act on
    it: an extra technique's at its pointer under extra_techniques, and one in a key the
    variant inherits (the paper's numbers against its own metrics or budgets, the parent's
    matched_spp without a fixed-spp technique kept) naming the parent."""
    key, _, rest = error.pointer[1:].partition("/")
    if key == "techniques" and rest.split("/")[0] in variant.get("extra_techniques", {}):
        return ConfigError(error.file, "/extra_techniques/" + rest, error.message)
    if key and key not in variant:
        return ConfigError(error.file, error.pointer,
                           f"{error.message} (/{key} is inherited from {variant['variant_of']})")
    return error


def _parse(file: Path) -> Any:
    try:
        text = file.read_text(encoding="utf-8")
    except OSError as e:
        raise ConfigError(file, "", f"cannot read: {e.strerror}") from None
    except UnicodeDecodeError as e:
        raise ConfigError(file, "", f"not UTF-8 text: {e.reason} at byte {e.start}") from None
    try:
        return json.loads(text, object_pairs_hook=_reject_duplicate_keys,
                          parse_constant=_reject_constant, parse_float=_finite_float)
    except ValueError as e:
        raise ConfigError(file, "", f"malformed JSON: {e}") from None


def _reject_duplicate_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    keys = [k for k, _ in pairs]
    duplicates = sorted({k for k in keys if keys.count(k) > 1})
    if duplicates:
        raise ValueError(f"duplicate key \"{duplicates[0]}\"")
    return dict(pairs)


def _reject_constant(name: str) -> None:
    raise ValueError(f"{name} is not JSON")


def _finite_float(text: str) -> float:
    """Python reads 1e999 as infinity, which no JSON number is."""
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(f"{text} is too large for a double")
    return value


def _is_integer(checker: Any, instance: Any) -> bool:
    """JSON Schema's "integer" also admits 16.0; budgets and seeds become command-line
    arguments and file names, where 16.0 would read "16.0", so here an integer is a number
    written without a fraction."""
    return isinstance(instance, int) and not isinstance(instance, bool)


@functools.cache
def _validator() -> Validator:
    draft = jsonschema.Draft202012Validator
    strict = jsonschema.validators.extend(
        draft, type_checker=draft.TYPE_CHECKER.redefine("integer", _is_integer))
    return strict(json.loads(SCHEMA_FILE.read_text(encoding="utf-8")))


def _schema_error(file: Path, error: ValidationError) -> ConfigError:
    """One line naming the pointer of the bad value, or of the bad, unknown or missing key."""
    path = list(error.absolute_path)
    if error.validator == "additionalProperties":
        known = sorted(error.schema["properties"])
        unknown = min(set(error.instance) - set(known))
        return ConfigError(file, json_pointer(*path, unknown),
                           f"unknown key (expected one of: {', '.join(known)})")
    if error.validator == "required":
        missing = next(k for k in error.validator_value if k not in error.instance)
        return ConfigError(file, json_pointer(*path, missing), "required key is missing")
    if "propertyNames" in error.absolute_schema_path:  # the instance is the key itself
        return ConfigError(file, json_pointer(*path, error.instance), _message(error))
    return ConfigError(file, json_pointer(*path),
                       f"{_message(error)}, got {_abbreviated(error.instance)}")


def _message(error: ValidationError) -> str:
    """The schema's "errorMessage" (an extension VS Code shows too) of the subschema that
    failed or, for a branch of an anyOf, of the anyOf's; jsonschema's wording where there is
    none. An enum's message lists its values."""
    holder: Any = error  # a ValidationError, or None past the root
    while holder is not None and "errorMessage" not in holder.schema:
        holder = holder.parent
    text = error.message if holder is None else holder.schema["errorMessage"]
    if error.validator == "enum":
        text += f" (known: {', '.join(map(str, error.validator_value))})"
    return text


def _abbreviated(value: Any) -> str:
    text = json.dumps(value, ensure_ascii=False)
    return text if len(text) <= 40 else text[:37] + "..."


def _disagreements(doc: dict[str, Any]) -> Iterator[tuple[str, str]]:
    """(pointer, message) of each value that a structurally valid document cannot have
    because of another field, or because the scene file is absent."""
    if not _scene(doc).is_file():
        yield "/scene", (f"scene file not found: {doc['scene']} (paths are relative to the "
                         "repository root)")
    for name in PROFILES:
        yield from _profile_disagreements(name, doc["profiles"][name])
    if doc["baseline"] not in doc["techniques"]:
        yield "/baseline", "must name one of the techniques"
    if doc["metrics"][0] in SIGNED_METRICS:
        yield "/metrics/0", (f"{doc['metrics'][0]} is signed: the primary metric must be an error "
                             "or an efficiency (list it after one)")
    if "also_baseline" in doc and doc["also_baseline"] not in doc["techniques"]:
        yield "/also_baseline", "must name one of the techniques"
    if doc.get("also_baseline") == doc["baseline"]:
        yield "/also_baseline", "must differ from the baseline"
    for name, t in doc["techniques"].items():
        for i, pointer in enumerate(t.get("samples_at", [])):
            if not isinstance(_resolve(t["integrator"], pointer), int):
                yield (json_pointer("techniques", name, "samples_at", i),
                       f"{pointer} must name an integer the integrator already has")
        fixed = t.get("fixed_spp", False) or "samples_at" in t
        if "equal_time" in t and not fixed:
            yield (json_pointer("techniques", name, "equal_time"),
                   "applies only to a fixed-spp technique (whose times set equal-time budgets)")
        if t.get("sets_time", False) and fixed:
            yield (json_pointer("techniques", name, "sets_time"),
                   "applies only to a technique that honours a time limit (a fixed-spp one's "
                   "times set budgets through equal_time)")
    if not any(((t.get("fixed_spp", False) or "samples_at" in t) and
                t.get("equal_time", True) is not False) or t.get("sets_time", False)
               for t in doc["techniques"].values()):
        for name in PROFILES:
            if "matched_spp" in doc["profiles"][name]:
                yield (json_pointer("profiles", name, "matched_spp"),
                       "needs a technique with \"fixed_spp\": true and equal time, or with "
                       "\"sets_time\": true (the budgets are the render times of such "
                       "techniques)")
    for pointer, entry in _paper_entries(doc):
        yield from _paper_disagreements(doc, pointer, entry)
    if "thresholds" in doc:
        yield from _threshold_disagreements(doc)


def _resolve(document: Any, pointer: str) -> Any:
    """The value at a JSON pointer (no ~ escapes), or None."""
    node = document
    for key in pointer.split("/")[1:]:
        if not isinstance(node, dict) or key not in node:
            return None
        node = node[key]
    return node


def _scene(doc: dict[str, Any]) -> Path:
    return (paths.ROOT / doc["scene"]).resolve()


def _strictly_increasing(values: list[float]) -> bool:
    return all(a < b for a, b in zip(values, values[1:]))


def _profile_disagreements(name: str, p: dict[str, Any]) -> Iterator[tuple[str, str]]:
    at = functools.partial(json_pointer, "profiles", name)
    for key in ("spp", "seconds", "matched_spp"):
        if not _strictly_increasing(p.get(key, [])):
            yield at(key), "must be strictly increasing"
    for i, spp in enumerate(p.get("matched_spp", [])):
        if spp not in p["spp"]:
            yield at("matched_spp", i), "must be one of the profile's spp budgets"
    table = p["table"]
    if table["spp"] not in p["spp"]:
        yield at("table", "spp"), "must be one of the profile's spp budgets"
    seconds = table.get("seconds")
    if seconds == MATCHED and table["spp"] not in p.get("matched_spp", []):
        yield at("table", "seconds"), (f"\"{MATCHED}\" needs the table's spp ({table['spp']}) "
                                       "in the profile's matched_spp")
    if seconds not in (None, MATCHED, *p.get("seconds", [])):
        yield at("table", "seconds"), (f"must be one of the profile's seconds budgets or "
                                       f"\"{MATCHED}\"")
    crop, (width, height) = p.get("crop"), p["resolution"]
    if crop and (crop[0] + crop[2] > width or crop[1] + crop[3] > height):
        yield at("crop"), f"expected [x, y, width, height] inside the image ({width}x{height})"


def _paper_entries(doc: dict[str, Any]) -> list[tuple[str, dict[str, Any]]]:
    """(pointer, entry) of the paper's numbers: one object, or a list of them."""
    paper = doc.get("paper", [])
    if isinstance(paper, dict):
        return [("/paper", paper)]
    return [(json_pointer("paper", i), entry) for i, entry in enumerate(paper)]


def _paper_disagreements(doc: dict[str, Any], pointer: str,
                         entry: dict[str, Any]) -> Iterator[tuple[str, str]]:
    if entry["metric"] not in doc["metrics"]:
        yield f"{pointer}/metric", f"\"{entry['metric']}\" is not one of the experiment's metrics"
    for name in PROFILES:
        if entry["spp"] not in doc["profiles"][name]["spp"]:
            yield f"{pointer}/spp", f"the {name} profile's spp budgets must include the paper's"
    for technique in entry["values"]:
        if technique not in doc["techniques"]:
            yield pointer + json_pointer("values", technique), "not one of the techniques"


def _threshold_disagreements(doc: dict[str, Any]) -> Iterator[tuple[str, str]]:
    thresholds, primary = doc["thresholds"], doc["metrics"][0]
    if METRICS[primary] or primary in EFFICIENCY_OF:
        yield "/thresholds", (f"thresholds need an error as the primary metric, not {primary}: "
                              "an efficiency depends on the machine's speed, so a check on it "
                              "could flake")
    profile = thresholds["profile"]
    for i, check in enumerate(thresholds["checks"]):
        at = functools.partial(json_pointer, "thresholds", "checks", i)
        if check["technique"] not in doc["techniques"]:
            yield at("technique"), "not one of the techniques"
        if check["spp"] not in doc["profiles"][profile]["spp"]:
            yield at("spp"), f"not one of the {profile} profile's spp budgets"
        if "min_gain" in check and check["technique"] == doc["baseline"]:
            yield at("min_gain"), "the baseline has no gain over itself"


def _experiment(file: Path, doc: dict[str, Any], variant_of: Path | None = None) -> Experiment:
    """The Experiment of a document that passed every check. For a variant, `doc` is the
    merged document, so that its hash changes with what it inherits, and `variant_of` the
    parent's file."""
    return Experiment(
        id=paths.experiment_id(file),
        file=file,
        profile_sha256={name: profile_sha256(doc, name) for name in PROFILES},
        description=doc["description"],
        scene=_scene(doc),
        overrides=doc.get("set", {}),
        techniques={name: Technique(name, t.get("label", name), t["integrator"],
                                    t.get("fixed_spp", False) or "samples_at" in t,
                                    t.get("samples_at", []), t.get("set", {}),
                                    t.get("equal_time", True), t.get("sets_time", False))
                    for name, t in doc["techniques"].items()},
        baseline=doc["baseline"],
        also_baseline=doc.get("also_baseline"),
        metrics=doc["metrics"],
        reference_integrator=doc["reference"]["integrator"],
        profiles={name: _profile(name, doc["profiles"][name]) for name in PROFILES},
        relmse_reject=float(doc.get("relmse_reject", 0.0)),
        paper=[PaperNumbers(**entry) for _, entry in _paper_entries(doc)],
        thresholds=_thresholds(doc["thresholds"]) if "thresholds" in doc else None,
        slope_time_range=doc.get("slope_time_range", "all"),
        variant_of=variant_of,
        matrix=MatrixRow(**doc["matrix"]) if "matrix" in doc else None,
    )


def profile_sha256(doc: dict[str, Any], profile: str) -> str:
    """The hash of a config as one profile's runs see it: without the thresholds (calibrating
    keeps results) and without the other profiles (editing the full profile leaves the quick
    results current)."""
    seen = {k: v for k, v in doc.items() if k != "thresholds"}
    seen["profiles"] = {profile: doc["profiles"][profile]}
    return hashlib.sha256(json.dumps(seen, sort_keys=True).encode()).hexdigest()


def _profile(name: str, p: dict[str, Any]) -> Profile:
    table_seconds = p["table"].get("seconds")
    if table_seconds not in (None, MATCHED):
        table_seconds = float(table_seconds)
    crop = p.get("crop")
    width, height = p["resolution"]
    return Profile(name, (width, height), p["spp"],
                   [float(s) for s in p.get("seconds", [])], p["seeds"], p["reference_spp"],
                   p["table"]["spp"], table_seconds, p.get("threads_per_job", 1),
                   (crop[0], crop[1], crop[2], crop[3]) if crop else None,
                   p.get("matched_spp", []))


def _thresholds(t: dict[str, Any]) -> Thresholds:
    def limit(check: dict[str, Any], key: str) -> float | None:
        return float(check[key]) if key in check else None

    return Thresholds(t["profile"], t["method"],
                      [ThresholdCheck(c["technique"], c["spp"], limit(c, "max_error"),
                                      limit(c, "min_gain")) for c in t["checks"]])
