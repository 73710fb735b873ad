"""The sweep file: the runs to do, each a flat dict of parameters with a key.

YAML (`defaults`, then every combination of `grid`, then the explicit `runs`):

    defaults: {kind: simulation, scene: ../scenes/tongue_sg_3n.yaml, duration_s: 0.1}
    grid: {levels.SG: [0.05, 0.1], levels.GGp: [0.0, 0.2]}
    runs: [{levels.SG: 0.2, release_s: 0.05}]

or CSV: a header naming the parameters, one run a row, empty cells left out. Nested mappings
become dotted names (`levels: {SG: 0.1}` is `levels.SG`). `scene` and `experiment` are resolved
against the sweep file's folder, so that a rerun from elsewhere gives the same keys.
"""
import csv
import hashlib
import itertools
import json
import os
from dataclasses import dataclass

import yaml

KINDS = ("simulation", "experiment")
PATH_PARAMETERS = ("scene", "experiment")


@dataclass(frozen=True)
class Run:
    key: str
    params: dict  # flat: name -> str, float, int or bool

    @property
    def kind(self):
        return self.params["kind"]


def flatten(mapping, prefix=""):
    flat = {}
    for name, value in mapping.items():
        full = f"{prefix}{name}"
        if isinstance(value, dict):
            flat.update(flatten(value, full + "."))
        else:
            flat[full] = value
    return flat


def run_key(params):
    """The same parameters give the same key, whatever their order or 1 vs 1.0."""
    def canonical(v):
        return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v
    text = json.dumps({k: canonical(v) for k, v in params.items()}, sort_keys=True)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


def make_runs(param_dicts, folder="."):
    """Runs from parameter dicts: kind inferred, paths made absolute, keys made, duplicates
    refused (they would be one row)."""
    runs, seen = [], {}
    for i, given in enumerate(param_dicts):
        params = flatten(given)
        for name in PATH_PARAMETERS:
            if name in params:
                params[name] = os.path.normpath(os.path.join(folder, str(params[name])))
        if "kind" not in params:
            params["kind"] = "experiment" if "experiment" in params else "simulation"
        if params["kind"] not in KINDS:
            raise ValueError(f"run {i}: kind '{params['kind']}' is not one of {', '.join(KINDS)}")
        needed = "scene" if params["kind"] == "simulation" else "experiment"
        if needed not in params:
            raise ValueError(f"run {i}: a {params['kind']} run needs '{needed}'")
        key = run_key(params)
        if key in seen:
            raise ValueError(f"runs {seen[key]} and {i} have the same parameters")
        seen[key] = i
        runs.append(Run(key, params))
    return runs


def _number(text):
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def read_csv(path):
    with open(path, newline="") as f:
        lines = [line for line in f if line.strip() and not line.lstrip().startswith("#")]
    return [{k.strip(): _number(v.strip()) for k, v in row.items() if v is not None and v.strip()}
            for row in csv.DictReader(lines)]


def read_yaml(path):
    with open(path) as f:
        doc = yaml.safe_load(f) or {}
    unknown = set(doc) - {"defaults", "grid", "runs"}
    if unknown:
        raise ValueError(f"{path}: unknown keys {sorted(unknown)} (defaults, grid, runs)")
    defaults = flatten(doc.get("defaults") or {})
    grid = flatten(doc.get("grid") or {})
    for name, values in grid.items():
        if not isinstance(values, list) or not values:
            raise ValueError(f"{path}: grid.{name} must be a non-empty list")
    dicts = []
    if grid:
        names = list(grid)
        for combination in itertools.product(*(grid[n] for n in names)):
            dicts.append({**defaults, **dict(zip(names, combination))})
    for run in doc.get("runs") or []:
        dicts.append({**defaults, **flatten(run)})
    if not dicts:
        raise ValueError(f"{path}: no runs (give a grid, runs or both)")
    return dicts


def read_sweep(path):
    """The runs of a sweep file (.csv, else YAML), in the file's order."""
    dicts = read_csv(path) if path.endswith(".csv") else read_yaml(path)
    return make_runs(dicts, os.path.dirname(os.path.abspath(path)))
