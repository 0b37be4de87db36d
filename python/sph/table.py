# SPDX-License-Identifier: BSD-3-Clause
"""The CSV files of a run (diagnostics.csv, probes.csv, gauges.csv) as
NumPy arrays.

Each header cell is a name with its units in parentheses ("time (s)",
"P1 (Pa)"; counts such as "step" have none). A Table maps the bare name to
its column (float64; a column without units whose every value is whole,
a count, as int64), and .units maps the name to its units ("" for none).
NumPy is imported when a table is read, so `import sph` and a run need
only the library.
"""


class Table(dict):
    """Columns by name (numpy arrays of one length), with .units and .columns
    (the names in the file's order)."""

    def __init__(self, columns, units):
        super().__init__(columns)
        self.units = units
        self.columns = list(columns)

    def __len__(self):
        return len(self[self.columns[0]]) if self.columns else 0

    @property
    def rows(self):
        return len(self)

    def to_pandas(self):
        """A pandas DataFrame with the bare names as columns."""
        import pandas

        return pandas.DataFrame({k: self[k] for k in self.columns})

    def __repr__(self):
        return "<sph.Table %d rows: %s>" % (len(self), ", ".join(self.columns))


def _split_header(cell):
    cell = cell.strip()
    if cell.endswith(")") and " (" in cell:
        name, _, unit = cell[:-1].partition(" (")
        return name, unit
    return cell, ""


def read_table(path):
    """Reads one of the run's CSV files into an sph.Table."""
    try:
        import numpy as np
    except ImportError as e:
        raise ImportError("sph.read_table needs NumPy: apt-get install python3-numpy") from e
    with open(path, "r", encoding="utf-8") as f:
        header = f.readline().rstrip("\n")
        if not header:
            raise ValueError("%s: empty file (no header line)" % path)
        names, units = zip(*(_split_header(c) for c in header.split(",")))
        data = np.loadtxt(f, delimiter=",", ndmin=2, dtype=np.float64)
    if data.size == 0:
        data = np.zeros((0, len(names)))
    if data.shape[1] != len(names):
        raise ValueError("%s: %d columns in the header, %d in the rows" % (path, len(names), data.shape[1]))
    columns = {}
    for k, (name, unit) in enumerate(zip(names, units)):
        col = data[:, k]
        if not unit and len(col) and np.all(np.isfinite(col)) and np.all(col == np.round(col)):
            col = col.astype(np.int64)
        columns[name] = col
    return Table(columns, dict(zip(names, units)))
