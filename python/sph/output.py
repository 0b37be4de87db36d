# SPDX-License-Identifier: BSD-3-Clause
"""A run's output directory: sph.Output(directory) reads what `sph run`
or sph.run wrote there (a finished run, or one still going)."""
from pathlib import Path

from .snapshot import Snapshot
from .table import read_table


class Output:
    """.diagnostics, .probes, .gauges (sph.Table, None when the run writes
    no such file), .snapshots (the snapshot paths in output order),
    .snapshot(k) (an sph.Snapshot; k = -1 the last)."""

    def __init__(self, directory):
        self.directory = Path(directory)

    def _table(self, name):
        path = self.directory / name
        return read_table(path) if path.exists() else None

    @property
    def diagnostics(self):
        return self._table("diagnostics.csv")

    @property
    def probes(self):
        return self._table("probes.csv")

    @property
    def gauges(self):
        return self._table("gauges.csv")

    @property
    def snapshots(self):
        return sorted(self.directory.glob("snap_[0-9][0-9][0-9][0-9]*.h5"))

    def snapshot(self, k=-1):
        snaps = self.snapshots
        if not snaps:
            raise FileNotFoundError("%s: no snapshots" % self.directory)
        return Snapshot(snaps[k])

    def __repr__(self):
        return "<sph.Output %s>" % self.directory
