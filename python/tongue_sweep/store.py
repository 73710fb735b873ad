"""The output folder: one JSON file per finished run (the durable record, written atomically so
that a crash leaves whole rows or none), and the table assembled from them."""
import csv
import json
import os

FIRST_COLUMNS = ("key", "kind", "status", "error")


def _write_atomically(path, text):
    tmp = f"{path}.{os.getpid()}.tmp"
    with open(tmp, "w") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


class RowStore:
    def __init__(self, out_dir):
        self.out_dir = os.path.abspath(out_dir)
        self.rows_dir = os.path.join(self.out_dir, "runs")
        os.makedirs(self.rows_dir, exist_ok=True)

    def row_path(self, key):
        return os.path.join(self.rows_dir, f"{key}.json")

    def write(self, rows):
        """Each row's file, then the folder synced once: the renames are durable from then."""
        for row in rows:
            # One line: with `indent` the json module encodes in Python instead of C, about
            # 0.4 ms a row of this process's CPU beside the workers.
            _write_atomically(self.row_path(row["key"]), json.dumps(row))
        fd = os.open(self.rows_dir, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)

    def load(self):
        """key -> row of every run on record; unreadable files count as not done."""
        rows = {}
        for name in os.listdir(self.rows_dir):
            if not name.endswith(".json"):
                continue
            try:
                with open(os.path.join(self.rows_dir, name)) as f:
                    row = json.load(f)
                rows[row["key"]] = row
            except (OSError, ValueError, KeyError):
                continue
        return rows


def columns_of(rows, runs):
    """The fixed columns, the parameters in the runs' order, then the results."""
    columns = list(FIRST_COLUMNS)
    for source in [r.params for r in runs] + rows:
        for name in source:
            if name not in columns:
                columns.append(name)
    return columns


def table_rows(runs, rows_by_key):
    """The rows of these runs on record, in the runs' order."""
    return [rows_by_key[r.key] for r in runs if r.key in rows_by_key]


def _cell(value):
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)  # round-trips exactly
    return str(value)


def write_csv(path, runs, rows_by_key):
    rows = table_rows(runs, rows_by_key)
    columns = columns_of(rows, runs)
    tmp = f"{path}.{os.getpid()}.tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for row in rows:
            w.writerow([_cell(row.get(c)) for c in columns])
    os.replace(tmp, path)
    return columns


def write_hdf5(path, runs, rows_by_key):
    """One dataset per column: float64 where every cell is a number (NaN where missing), else
    strings; the attribute `columns` keeps their order."""
    import h5py
    import numpy as np
    rows = table_rows(runs, rows_by_key)
    columns = columns_of(rows, runs)
    with h5py.File(path, "w") as f:
        for c in columns:
            values = [row.get(c) for row in rows]
            numeric = all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool))
                          for v in values) and any(v is not None for v in values)
            if numeric:
                f[c] = np.array([np.nan if v is None else float(v) for v in values])
            else:
                f.create_dataset(c, data=[_cell(v) for v in values],
                                 dtype=h5py.string_dtype())
        f.attrs["columns"] = columns
