"""Reading a run file (the HDF5 log of sim_batch and sim_server) and the geometry of its mesh, for
the scripts that draw runs: draw_midsagittal.py and plot_run.py.

Run file (HDF5, SI units; the full layout is in docs/run_file.md):
/rest_positions [N x 3] (m), /elements [E x 8] (hex8, bottom face counter-clockwise then top
face), /time [T] (s), /positions [T x N x 3] (m); optional /mesh/node_sets/*,
/mesh/element_sets/*, /muscles/names, /muscles/max_force [M] (N), /activations [T x M].

Errors are RunError, whose message names the file and the dataset and is meant to be printed as
is. Needs h5py and numpy (Debian: python3-h5py, python3-numpy; run with /usr/bin/python3).
"""
import os

import h5py
import numpy as np

# Landmark node sets of the built-in tongue; a landmark is the first node of its set.
LANDMARKS = ["tip", "blade", "palatal_dorsum", "velar_dorsum", "root", "gg_insertion"]
# Faces of a hex8 (bottom counter-clockwise, then top), each as a loop of 4 local nodes.
HEX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]


class RunError(Exception):
    """A problem with the run file or the command line; the message is printed as is."""


# ---------------------------------------------------------------------------------------------
# Reading the run file


def read_dataset(h5, path, filename, ndim=None, last=None):
    if path not in h5:
        raise RunError("%s has no dataset %s" % (filename, path))
    obj = h5[path]
    if not isinstance(obj, h5py.Dataset):
        raise RunError("%s: %s is not a dataset" % (filename, path))
    data = obj[()]
    if ndim is not None and np.ndim(data) != ndim:
        raise RunError("%s: %s has %d dimensions, expected %d"
                       % (filename, path, np.ndim(data), ndim))
    if last is not None and np.shape(data)[-1] != last:
        raise RunError("%s: %s has shape %s, expected last dimension %d"
                       % (filename, path, np.shape(data), last))
    return data


def read_group_of_sets(h5, path):
    sets = {}
    group = h5.get(path)
    if isinstance(group, h5py.Group):
        for name, obj in group.items():
            if isinstance(obj, h5py.Dataset):
                sets[name] = np.asarray(obj[()], dtype=np.int64).ravel()
    return sets


def decode(name):
    return name.decode("utf-8") if isinstance(name, bytes) else str(name)


class Run:
    """A run file's mesh, times, sets and muscles, checked for consistency; positions are read
    per frame (or per node, for trajectories) when asked for."""

    def __init__(self, filename):
        if not os.path.isfile(filename):
            raise RunError("no such run file: %s" % filename)
        try:
            h5 = h5py.File(filename, "r")
        except OSError as error:
            raise RunError("cannot open %s as HDF5: %s" % (filename, error))
        base = os.path.basename(filename)
        self.filename = filename
        with h5:
            self.rest = np.asarray(read_dataset(h5, "/rest_positions", base, 2, 3), float)
            self.elements = np.asarray(read_dataset(h5, "/elements", base, 2, 8), np.int64)
            self.time = np.asarray(read_dataset(h5, "/time", base, 1), float)
            if "/positions" not in h5:
                raise RunError("%s has no dataset /positions" % base)
            self._positions = h5["/positions"]
            shape = self._positions.shape
            n = len(self.rest)
            if len(shape) != 3 or shape[1] != n or shape[2] != 3:
                raise RunError("%s: /positions has shape %s, expected [T x %d x 3]"
                               % (base, shape, n))
            if shape[0] == 0:
                raise RunError("%s: /positions has no frames" % base)
            if len(self.time) != shape[0]:
                raise RunError("%s: /time has %d entries but /positions %d frames"
                               % (base, len(self.time), shape[0]))
            if self.elements.size and (self.elements.min() < 0 or self.elements.max() >= n):
                raise RunError("%s: /elements refers to nodes outside 0..%d" % (base, n - 1))
            self.num_frames = shape[0]
            self.frames = {}
            self.node_sets = read_group_of_sets(h5, "/mesh/node_sets")
            self.element_sets = read_group_of_sets(h5, "/mesh/element_sets")
            for name, ids in self.element_sets.items():
                if ids.size and (ids.min() < 0 or ids.max() >= len(self.elements)):
                    raise RunError("%s: /mesh/element_sets/%s refers to elements outside 0..%d"
                                   % (base, name, len(self.elements) - 1))
            self.muscle_names = []
            self.activations = None
            self.max_force = None
            if "/muscles/names" in h5:
                self.muscle_names = [decode(s) for s in np.ravel(h5["/muscles/names"][()])]
                if "/activations" in h5:
                    act = np.asarray(h5["/activations"][()], float)
                    if act.ndim != 2 or act.shape != (self.num_frames, len(self.muscle_names)):
                        raise RunError("%s: /activations has shape %s, expected [%d x %d]"
                                       % (base, act.shape, self.num_frames,
                                          len(self.muscle_names)))
                    self.activations = act
                if "/muscles/max_force" in h5:
                    mf = np.ravel(np.asarray(h5["/muscles/max_force"][()], float))
                    if len(mf) == len(self.muscle_names):
                        self.max_force = mf
            # Obstacles (scenes with contact): name -> (vertices [V x 3] m, triangles [F x 3]).
            self.obstacles = {}
            if "/obstacles/names" in h5:
                for name in (decode(s) for s in np.ravel(h5["/obstacles/names"][()])):
                    v = np.asarray(read_dataset(h5, "/obstacles/%s/vertices" % name, base, 2, 3),
                                   float)
                    t = np.asarray(read_dataset(h5, "/obstacles/%s/triangles" % name, base, 2, 3),
                                   np.int64)
                    if t.size and (t.min() < 0 or t.max() >= len(v)):
                        raise RunError("%s: /obstacles/%s/triangles refer to vertices outside "
                                       "0..%d" % (base, name, len(v) - 1))
                    self.obstacles[name] = (v, t)
            # Read the frames needed now, while the file is open.
            self._load_frame(0)
            self._load_frame(self.num_frames - 1)

    def _load_frame(self, k):
        if k not in self.frames:
            self.frames[k] = np.asarray(self._positions[k], float)
        return self.frames[k]

    def load(self, filename, k):
        """Positions of frame k [N x 3] (m)."""
        if k not in self.frames:
            with h5py.File(filename, "r") as h5:
                self.frames[k] = np.asarray(h5["/positions"][k], float)
        return self.frames[k]

    def contact_nodes(self, filename, k):
        """Nodes the obstacles push on in frame k (none without /contact)."""
        with h5py.File(filename, "r") as h5:
            if "/contact/node_force" not in h5:
                return np.zeros(0, np.int64)
            f = np.asarray(h5["/contact/node_force"][k], float)
        return np.flatnonzero(np.abs(f).sum(axis=1) > 0.0)

    def trajectories(self, nodes):
        """Positions of the given nodes at every frame [T x len(nodes) x 3] (m)."""
        nodes = [int(n) for n in nodes]
        for n in nodes:
            if not 0 <= n < len(self.rest):
                raise RunError("%s: node %d is outside 0..%d"
                               % (os.path.basename(self.filename), n, len(self.rest) - 1))
        # h5py reads a selection of nodes in increasing order, each once.
        unique = sorted(set(nodes))
        with h5py.File(self.filename, "r") as h5:
            data = np.asarray(h5["/positions"][:, unique, :], float)
        return data[:, [unique.index(n) for n in nodes], :]



# ---------------------------------------------------------------------------------------------
# Geometry


def element_faces(elements, element_ids):
    """(element, face loop of 4 global nodes) for every face of the given elements."""
    for e in element_ids:
        nodes = elements[e]
        for f in HEX_FACES:
            yield e, tuple(int(nodes[i]) for i in f)


def midsagittal_section(run, filename):
    """Faces of the section: dict key (sorted nodes) -> {"loop": nodes, "elements": set}.

    Returns (faces, how) where how describes the method used.
    """
    faces = {}
    mid = run.node_sets.get("midsagittal")
    if mid is not None and len(mid):
        in_mid = np.zeros(len(run.rest), bool)
        in_mid[mid[(mid >= 0) & (mid < len(run.rest))]] = True
        for e, loop in element_faces(run.elements, range(len(run.elements))):
            if all(in_mid[n] for n in loop):
                key = tuple(sorted(loop))
                faces.setdefault(key, {"loop": loop, "elements": set()})["elements"].add(e)
        if not faces:
            raise RunError("%s: no element face has all its nodes in the midsagittal node set"
                           % os.path.basename(filename))
        return faces, "node set midsagittal"
    # Fallback: elements crossing z = 0, by their face nearest to z = 0.
    z = run.rest[:, 2]
    extent = np.ptp(run.rest, axis=0).max() if len(run.rest) else 1.0
    tol = 1e-9 * max(extent, 1e-12)
    zmin = z[run.elements].min(axis=1)
    zmax = z[run.elements].max(axis=1)
    crossing = np.nonzero((zmin <= tol) & (zmax >= -tol))[0]
    for e in crossing:
        best = None
        for _, loop in element_faces(run.elements, [e]):
            zs = z[list(loop)]
            score = (abs(zs.mean()), np.ptp(zs))
            if best is None or score < best[0]:
                best = (score, loop)
        key = tuple(sorted(best[1]))
        faces.setdefault(key, {"loop": best[1], "elements": set()})["elements"].add(e)
    if not faces:
        raise RunError("%s has no midsagittal node set (/mesh/node_sets/midsagittal) and no "
                       "element crosses z = 0" % os.path.basename(filename))
    return faces, "elements crossing z = 0 (no midsagittal node set)"


def nearest_faces(run, element_ids):
    """For elements off the section: each one's face nearest to z = 0 (for a projection)."""
    z = np.abs(run.rest[:, 2])
    loops = []
    for e in element_ids:
        best = None
        for _, loop in element_faces(run.elements, [e]):
            score = z[list(loop)].mean()
            if best is None or score < best[0]:
                best = (score, loop)
        loops.append(best[1])
    return loops


def area_centroid(polygons):
    """Centroid of the union of non-overlapping polygons (shoelace formula)."""
    total, moment = 0.0, np.zeros(2)
    for p in polygons:
        q = np.roll(p, -1, axis=0)
        cross = p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]
        a = cross.sum() / 2
        total += a
        moment += ((p + q) * cross[:, None]).sum(axis=0) / 6
    if abs(total) < 1e-300:
        return np.mean(np.vstack(polygons), axis=0)
    return moment / total


def boundary_edges(loops):
    """Edges used by exactly one of the face loops (the outline of the section)."""
    count = {}
    for loop in loops:
        for a, b in zip(loop, loop[1:] + loop[:1]):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    return [edge for edge, c in count.items() if c == 1]


def chain_edges(edges):
    """Joins edges into polylines (closed loops where possible) for a clean outline."""
    adjacent = {}
    for a, b in edges:
        adjacent.setdefault(a, []).append(b)
        adjacent.setdefault(b, []).append(a)
    unused = set(edges)
    paths = []

    def take(a, b):
        key = (min(a, b), max(a, b))
        if key in unused:
            unused.remove(key)
            return True
        return False

    # Start from open ends first, then from anything left (closed loops).
    starts = [n for n, nb in adjacent.items() if len(nb) % 2 == 1] + list(adjacent)
    for start in starts:
        while any((min(start, b), max(start, b)) in unused for b in adjacent[start]):
            path = [start]
            current = start
            while True:
                nxt = next((b for b in adjacent[current]
                            if (min(current, b), max(current, b)) in unused), None)
                if nxt is None:
                    break
                take(current, nxt)
                path.append(nxt)
                current = nxt
            paths.append(path)
    return paths


def boundary_faces(elements):
    """Faces of the mesh used by exactly one element: (loop, element)."""
    seen = {}
    for e, loop in element_faces(elements, range(len(elements))):
        key = tuple(sorted(loop))
        if key in seen:
            seen[key] = None
        else:
            seen[key] = (loop, e)
    return [v for v in seen.values() if v is not None]


def plane_section(vertices, triangles, axis=2, value=0.0):
    """Segments where the triangles cross the plane x[axis] = value: a list of 2 x 3 arrays."""
    segments = []
    d = vertices[:, axis] - value
    for tri in triangles:
        points = []
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            if (d[a] < 0.0) != (d[b] < 0.0):
                s = d[a] / (d[a] - d[b])
                points.append(vertices[a] + s * (vertices[b] - vertices[a]))
        if len(points) == 2:
            segments.append(np.array(points))
    return segments
