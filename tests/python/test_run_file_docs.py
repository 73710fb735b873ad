"""docs/run_file.md against the files: every root attribute and dataset a run file holds is in
the documentation's tables, and every one the tables list turns up in one of these runs (or is
named below with the condition it needs): sim_batch's dynamic runs with muscles and with
obstacles, a static run, and sim_server's lock-step run."""
import os
import re
import subprocess

import h5py
import pytest

import tongue
from server_process import PROCESS_TIMEOUT_S, Server, path, url

DOCS = path("docs", "run_file.md")
# Documented, written only under conditions these runs do not meet.
CONDITIONAL = {
    "resets": "a reset command to sim_server",
    "reduced_model_warning": "a reduced model's indicator above its threshold",
    "/mesh/node_ids": "an imported mesh",
    "/mesh/element_ids": "an imported mesh",
}


def documented(section_start, section_end):
    """The backquoted names in the first column of the tables between two headings, as regular
    expressions (<name> and <part> stand for any name)."""
    text = open(DOCS, encoding="utf-8").read()
    text = text[text.index(section_start):text.index(section_end)]
    names = {}
    for line in text.splitlines():
        if not line.startswith("| `"):
            continue
        for name in re.findall(r"`([^`]+)`", line.split("|")[1]):
            names[name] = re.compile(re.sub(r"<[a-z]+>", "[A-Za-z0-9_]+", name) + "$")
    return names


def contents(run_file):
    attributes, datasets = set(), set()
    with h5py.File(run_file, "r") as f:
        attributes.update(f.attrs.keys())
        f.visititems(lambda name, item: datasets.add("/" + name)
                     if isinstance(item, h5py.Dataset) else None)
    return attributes, datasets


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("runs")
    files = []
    for scene in ("tongue_sg_3n.yaml", "tongue_i.yaml"):
        files.append(tmp / scene.replace(".yaml", ".h5"))
        subprocess.run([os.environ["SIM_BATCH"], path("scenes", scene), "--quiet", "--output",
                        str(files[-1])], check=True, capture_output=True, timeout=PROCESS_TIMEOUT_S)
    static = tmp / "static.yaml"
    text = open(path("scenes", "tongue_sg_3n.yaml"), encoding="utf-8").read()
    static.write_text(re.sub(r"analysis:\n(  .*\n)+", "analysis: {type: static, load_steps: 2}\n",
                             text))
    files.append(tmp / "static.h5")
    subprocess.run([os.environ["SIM_BATCH"], str(static), "--quiet", "--output", str(files[-1])],
                   check=True, capture_output=True, timeout=PROCESS_TIMEOUT_S)
    files.append(tmp / "server.h5")
    client = tongue.BusClient(tongue.ControllerOptions(lcm_url=url(7867), max_steps=3))
    server = Server(7867, "tongue_sg_3n.yaml", files[-1], "--max-steps", "3")
    try:
        client.connect()
        for _ in client.lockstep():
            client.send({"SG": 0.1})
        assert server.wait()[0] == 0
    finally:
        server.kill()
    return [contents(f) for f in files]


def check(found, names):
    undocumented = sorted(n for n in found if not any(p.match(n) for p in names.values()))
    assert not undocumented, f"in the files, not in {DOCS}: {undocumented}"
    unseen = sorted(d for d, p in names.items()
                    if d not in CONDITIONAL and not any(p.match(n) for n in found))
    assert not unseen, f"in {DOCS}, in none of the files: {unseen}"


def test_root_attributes_are_documented_one_by_one(runs):
    check(set().union(*(a for a, _ in runs)), documented("**Root attributes**", "**Frames.**"))


def test_datasets_are_documented_one_by_one(runs):
    check(set().union(*(d for _, d in runs)), documented("## Layout", "**Root attributes**"))
