"""A whole closed-loop experiment through run_experiment, on a udpm port of its own.

Parameters: `experiment` (path), `duration_s` (optional, overrides the file's), and
`plan.<path>` to change the plan given to a controller with `--plan`: `plan.delta_lambda_mm.GGp.1`
is the second target of GGp. With changes, the experiment and its plan are written anew into the
run's logs folder with absolute paths, the original files left as they are.
"""
import os
import shutil
import subprocess

import numpy as np
import yaml

from .landmarks import LandmarkTracker


def find_run_experiment(given=None):
    """The runner: given, $RUN_EXPERIMENT, next to the tongue module's build, or on the PATH."""
    if given:
        return given
    if os.environ.get("RUN_EXPERIMENT"):
        return os.environ["RUN_EXPERIMENT"]
    try:
        import tongue
        build = os.path.dirname(os.path.dirname(os.path.abspath(tongue.__file__)))
        candidate = os.path.join(build, "experiments", "run_experiment")
        if os.access(candidate, os.X_OK):
            return candidate
    except ImportError:
        pass
    found = shutil.which("run_experiment")
    if not found:
        raise RuntimeError("run_experiment not found: give --run-experiment or $RUN_EXPERIMENT")
    return found


def set_path(doc, dotted, value):
    """doc at a dotted path (list items by index) set to value; the path must exist but its last
    part, which may be a new key."""
    parts = dotted.split(".")
    node = doc
    try:
        for part in parts[:-1]:
            node = node[int(part)] if isinstance(node, list) else node[part]
        if isinstance(node, list):
            node[int(parts[-1])] = value
        else:
            node[parts[-1]] = value
    except (KeyError, IndexError, ValueError, TypeError):
        raise ValueError(f"the plan has no '{dotted}'") from None


def rewrite_experiment(experiment, params, folder):
    """The experiment with the run's changes, written into folder; returns its path."""
    source = os.path.dirname(experiment)
    with open(experiment) as f:
        doc = yaml.safe_load(f)

    def absolute(p):
        return os.path.normpath(os.path.join(source, p))

    doc["scene"] = absolute(doc["scene"])
    if "duration_s" in params:
        doc["duration"] = float(params["duration_s"])
        if "plots" in doc and "times" in (doc["plots"] or {}):
            # The runner refuses snapshot times past the end (no plots are drawn anyway).
            doc["plots"]["times"] = [t for t in doc["plots"]["times"] if t <= doc["duration"]]
    changes = {k[len("plan."):]: v for k, v in params.items() if k.startswith("plan.")}
    planned = False
    for c in doc["controllers"]:
        if "/" in c["program"]:
            c["program"] = absolute(c["program"])
        args = [str(a) for a in c.get("args", [])]
        for i, arg in enumerate(args):
            if i > 0 and args[i - 1] == "--plan" and changes:
                with open(absolute(arg)) as f:
                    plan = yaml.safe_load(f)
                for path, value in changes.items():
                    set_path(plan, path, value)
                arg = os.path.join(folder, f"plan_{c['name']}.yaml")
                with open(arg, "w") as f:
                    yaml.safe_dump(plan, f)
                planned = True
            elif not arg.startswith("-") and os.path.exists(absolute(arg)):
                arg = absolute(arg)  # a file the controller reads, relative to the experiment
            args[i] = arg
        c["args"] = args
    if changes and not planned:
        raise ValueError("plan.* given but no controller of the experiment has --plan")
    path = os.path.join(folder, "experiment.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(doc, f, sort_keys=False)
    return path


def summary_line(text, start):
    return next((line for line in text.splitlines() if line.startswith(start)), "")


def run_experiment(params, port, logs_dir, runner=None):
    if port is None:
        raise ValueError("an experiment run needs a udpm port")
    import tongue
    shutil.rmtree(logs_dir, ignore_errors=True)  # what an earlier, failed attempt left
    inputs = os.path.join(logs_dir, "inputs")
    os.makedirs(inputs)
    experiment = params["experiment"]
    if "duration_s" in params or any(k.startswith("plan.") for k in params):
        experiment = rewrite_experiment(experiment, params, inputs)
    command = [find_run_experiment(runner), experiment, "--logs", logs_dir,
               "--port", str(int(port)), "--no-plots", "--quiet"]
    done = subprocess.run(command, capture_output=True, text=True)
    runs = [d for d in sorted(os.listdir(logs_dir)) if d not in ("inputs",)
            and not d.endswith("-latest") and os.path.isdir(os.path.join(logs_dir, d))]
    folder = os.path.join(logs_dir, runs[-1]) if runs else ""
    summary = ""
    if folder and os.path.exists(os.path.join(folder, "summary.txt")):
        with open(os.path.join(folder, "summary.txt")) as f:
            summary = f.read()
    if done.returncode != 0:
        why = summary_line(summary, "result:") or done.stderr.strip()[-500:]
        raise RuntimeError(f"run_experiment exited with {done.returncode}: {why}")

    run = tongue.RunFile(os.path.join(folder, "run.h5"))
    positions = run.positions
    node_sets = {n: run.dataset(f"/mesh/node_sets/{n}") for n in
                 ("tip", "blade", "palatal_dorsum", "velar_dorsum", "root")
                 if run.has(f"/mesh/node_sets/{n}")}
    tracker = LandmarkTracker(node_sets, positions[0])
    for frame in positions[1:]:
        tracker.add(frame)
    return {"steps": len(run.time) - 1, "simulated_s": float(run.time[-1] - run.time[0]),
            "newton_iterations": int(np.sum(run.dataset("/solver/iterations"))),
            "step_cuts": int(np.sum(run.dataset("/solver/cuts"))),
            "physics_wall_s": float(np.sum(run.dataset("/solver/wall_time"))),
            "run_status": run.status, "port": int(port), "run_folder": folder,
            **tracker.figures()}
