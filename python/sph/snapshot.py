# SPDX-License-Identifier: BSD-3-Clause
"""A snapshot (snap_NNNN.h5, last_good.h5) as NumPy arrays, read with h5py.

The fields are the datasets under /particles, in particle-id order
(doc/snapshot-format.md); the run's facts are the root's attributes. Text
attributes are stored as fixed-length strings and come back as str here.
"""


def _text(v):
    return v.decode("utf-8", "replace") if isinstance(v, bytes) else v


class Snapshot:
    """sph.Snapshot(path): .time, .step, .dx, .case_name, .fields (name ->
    array), .units (name -> units), .attrs (every root attribute); s["vx"] is
    s.fields["vx"]; s.fluid is the mask of fluid particles (kind 0)."""

    def __init__(self, path):
        try:
            import h5py
        except ImportError as e:
            raise ImportError("sph.Snapshot reads HDF5 with h5py: apt-get install python3-h5py") from e
        self.path = str(path)
        with h5py.File(self.path, "r") as f:
            self.attrs = {k: _text(v) for k, v in f.attrs.items()}
            group = f["particles"]
            self.fields = {name: group[name][()] for name in group}
            self.units = {name: _text(group[name].attrs.get("units", b"")) for name in group}
        self.time = float(self.attrs["time"])
        self.step = int(self.attrs["step"])
        self.dx = float(self.attrs["dx"])
        self.case_name = self.attrs["case_name"]

    def __getitem__(self, name):
        return self.fields[name]

    def __contains__(self, name):
        return name in self.fields

    @property
    def fluid(self):
        return self.fields["kind"] == 0

    def __repr__(self):
        return "<sph.Snapshot %s: %s at t = %.6g s, %d particles>" % (
            self.path, self.case_name, self.time, len(self.fields["kind"]))
