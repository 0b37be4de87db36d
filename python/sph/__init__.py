# SPDX-License-Identifier: BSD-3-Clause
"""sph: run smoothed-particle hydrodynamics cases from Python, and read what
they write as NumPy arrays (doc/python.md).

    import sph
    run = sph.run("cases/martin_moyce_coarse.yaml", outdir="out/mm",
                  overrides={"time.end": 0.1})
    d = run.diagnostics            # sph.Table: d["time"], d["front_x"], ...
    s = run.snapshot(-1)           # sph.Snapshot: s["x"], s["p"], s.time

The cases run in libsph (2-D) or libsph3 (3-D), the libraries of the `sph`
command, loaded through ctypes: the same case gives the same bits as `sph
run`. Needs NumPy; h5py for snapshots.
"""
from ._library import CaseError, Error, version
from .case import Case
from .output import Output
from .run import BlowUpError, Progress, Run, run
from .snapshot import Snapshot
from .table import Table, read_table

__all__ = [
    "BlowUpError", "Case", "CaseError", "Error", "Output", "Progress", "Run", "Snapshot",
    "Table", "read_table", "run", "version",
]
