#!/usr/bin/env python3
"""Checks an XDMF sidecar against its run file, as ParaView's Xdmf2 reader would resolve it.

Usage: check_xdmf.py RUN.xmf
Exits 0 when: the sidecar is a temporal collection of one uniform grid per frame of /time, with
the same times; its hexahedron topology and hyperslab geometry name datasets that exist in the
HDF5 file with the dimensions stated; each hyperslab selects its own frame; and the elements in
XDMF (= VTK) hexahedron order have positive volume at rest. Prints what is wrong otherwise.
"""
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def check(condition, what):
    if not condition:
        print("FAILED:", what)
        sys.exit(1)


def dims(item):
    return [int(d) for d in item.get("Dimensions").split()]


def hdf_item(item, xmf_dir, files):
    """The dataset an HDF DataItem names, after checking its file, path and dimensions."""
    check(item.get("Format") == "HDF", "DataItem format %s" % item.get("Format"))
    name, _, path = item.text.strip().partition(":")
    check(not os.path.isabs(name), "file name %s is relative to the sidecar" % name)
    h5_path = os.path.join(xmf_dir, name)
    check(os.path.exists(h5_path), "file %s exists" % h5_path)
    f = files.setdefault(h5_path, h5py.File(h5_path, "r"))
    check(path in f, "dataset %s in %s" % (path, h5_path))
    ds = f[path]
    check(list(ds.shape) == dims(item), "%s: shape %s == Dimensions %s" % (path, ds.shape, dims(item)))
    number_type = item.get("NumberType")
    if ds.dtype.kind == "f":
        check(number_type == "Float" and int(item.get("Precision")) == ds.dtype.itemsize,
              "%s: float type" % path)
    else:
        check(number_type == "Int" and int(item.get("Precision")) == ds.dtype.itemsize,
              "%s: int type" % path)
    return ds


def main():
    xmf = sys.argv[1]
    xmf_dir = os.path.dirname(os.path.abspath(xmf))
    root = ET.parse(xmf).getroot()
    check(root.tag == "Xdmf" and root.get("Version") == "2.0", "Xdmf Version 2.0 root")
    domain = root.find("Domain")
    check(domain is not None, "a Domain")
    collections = domain.findall("Grid")
    check(len(collections) == 1, "one top grid")
    coll = collections[0]
    check(coll.get("GridType") == "Collection" and coll.get("CollectionType") == "Temporal",
          "a temporal collection")
    files = {}
    grids = coll.findall("Grid")
    check(grids, "frames")
    time = None
    for k, grid in enumerate(grids):
        check(grid.get("GridType") == "Uniform", "frame %d is uniform" % k)
        topo = grid.find("Topology")
        check(topo.get("TopologyType") == "Hexahedron", "hexahedron topology")
        elements = hdf_item(topo.find("DataItem"), xmf_dir, files)
        check(int(topo.get("NumberOfElements")) == elements.shape[0] and elements.shape[1] == 8,
              "NumberOfElements = E, 8 nodes each")
        geom = grid.find("Geometry")
        check(geom.get("GeometryType") == "XYZ", "XYZ geometry")
        slab = geom.find("DataItem")
        check(slab.get("ItemType") == "HyperSlab", "hyperslab geometry")
        selection, source = slab.findall("DataItem")
        positions = hdf_item(source, xmf_dir, files)
        check(positions.name == "/positions", "geometry from /positions")
        f = positions.file
        if time is None:
            time = f["time"][...]
            check(len(grids) == len(time), "%d frames == %d times" % (len(grids), len(time)))
            check(positions.shape[0] == len(time), "positions has T frames")
            check(positions.shape[1:] == f["rest_positions"].shape, "positions frame = N x 3")
            check(elements.shape == f["elements"].shape, "elements")
            # XDMF Hexahedron = VTK_HEXAHEDRON: bottom face counter-clockwise (seen from the top
            # face), then the top face; every element then has a positive volume at rest.
            rest = f["rest_positions"][...]
            conn = f["elements"][...]
            p = rest[conn]
            det = np.einsum("ij,ij->i", p[:, 1] - p[:, 0],
                            np.cross(p[:, 3] - p[:, 0], p[:, 4] - p[:, 0]))
            check(np.all(det > 0), "positive volumes in XDMF hexahedron order")
        check(float(grid.find("Time").get("Value")) == time[k],
              "frame %d time %s == %r" % (k, grid.find("Time").get("Value"), time[k]))
        check(dims(selection) == [3, 3], "start/stride/count are 3 x 3")
        start, stride, count = np.array(selection.text.split(), dtype=int).reshape(3, 3)
        n = positions.shape[1]
        check(list(start) == [k, 0, 0] and list(stride) == [1, 1, 1] and list(count) == [1, n, 3],
              "frame %d selects its frame: %s %s %s" % (k, start, stride, count))
        check(dims(slab) == [1, n, 3], "hyperslab Dimensions 1 N 3")
    print("OK: %d frames" % len(grids))


if __name__ == "__main__":
    main()
