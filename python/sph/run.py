# SPDX-License-Identifier: BSD-3-Clause
"""Running a case: sph.run(case, outdir=..., threads=..., progress=...).

The run is libsph's sph_run, the loop `sph run` drives: the same snapshots,
diagnostics.csv, probes.csv and gauges.csv, bit for bit, for the same case
text and overrides (tests/check_python compares them byte for byte). The
progress callback is called from the run's own thread between steps, at
most every `progress_every` seconds of wall time (0: after every step),
and once at the end; returning True ends the run as Ctrl-C does for the
command line: after the current step, with a final snapshot, status
"interrupted". An exception in the callback ends the run the same way and
is raised again once the final snapshot is written. Ctrl-C (SIGINT) and
SIGTERM during a run called from the main thread do the same and then
raise KeyboardInterrupt (SystemExit for SIGTERM); a second one ends the
process at once, as for `sph run`. A blow-up raises sph.BlowUpError (its .run names the last good
state, last_good.h5); an I/O failure sph.Error.
"""
import ctypes
import os
import signal
import threading
import time
from collections import namedtuple
from pathlib import Path

from . import _library
from .case import Case
from .output import Output

Progress = namedtuple("Progress", "time step end fraction wall")
Progress.__doc__ = """Where a run stands: simulated time (s), steps taken, the
case's end time (s), the fraction done (by time, or by the case's stop
condition when that is nearer), wall seconds since the start."""

_STATUS = {0: "end", 1: "stopped", 2: "interrupted", 3: "blowup", 4: "error"}


class BlowUpError(_library.Error):
    """The run blew up; .run is the sph.Run with what was written before."""

    __module__ = "sph"

    def __init__(self, msg, run):
        super().__init__(msg)
        self.run = run


class Run(Output):
    """A finished run: status ("end", "stopped" by the case's stop
    condition, "interrupted"), the time reached (s), steps, outputs,
    last_snapshot, wall seconds,
    and its output directory's files (sph.Output: diagnostics, probes,
    gauges, snapshots)."""

    def __init__(self, case, outdir, status, reached, steps, outputs, last_snapshot, wall):
        super().__init__(outdir)
        self.case = case
        self.status = status
        self.time = reached
        self.steps = steps
        self.outputs = outputs
        self.last_snapshot = last_snapshot
        self.wall = wall

    def __repr__(self):
        return "<sph.Run %s: %s after %d steps, %d outputs in %s>" % (
            self.case.name, self.status, self.steps, self.outputs, self.directory)


def _clamp(x):
    return 0.0 if x < 0.0 else 1.0 if x > 1.0 else x


def run(case, outdir=None, overrides=None, threads=None, progress=None, progress_every=1.0):
    """Runs a case (an sph.Case, a case file's path or name, or a dict) to its
    end; returns an sph.Run. outdir defaults to out/<case name>, as for `sph
    run`; threads (default: as OpenMP decides, all cores) does not change a
    bit of the results; progress(p) gets an sph.Progress."""
    if not isinstance(case, Case):
        case = Case(case, overrides)
    elif overrides:
        raise TypeError("overrides belong to sph.Case(...) when a Case is given")
    lib = case._lib
    if threads is not None:
        if int(threads) < 1:
            raise ValueError("threads: expected a whole number >= 1, got %r" % (threads,))
        lib.sph_set_threads(int(threads))
    outdir = Path(outdir if outdir is not None else Path("out") / case.name)
    err = _library.error_buffer()
    sim = ctypes.c_void_p()
    if lib.sph_sim_create(case._ptr, ctypes.byref(sim), ctypes.byref(err)):
        raise _library.CaseError(_library.message(err))
    interrupt = ctypes.c_int(0)
    state = {"raised": None, "last": None, "m0": None}
    start = time.monotonic()

    def report(s, final=False):
        now = time.monotonic()
        if not final and state["last"] is not None and now - state["last"] < progress_every:
            return
        state["last"] = now
        t = lib.sph_sim_time(s)
        frac = _clamp(t / case.end) if case.end > 0 else 1.0
        m, stop = ctypes.c_double(), ctypes.c_double()
        if lib.sph_run_stop_measure(s, ctypes.byref(m), ctypes.byref(stop)):
            if state["m0"] is None:
                state["m0"] = m.value
            if stop.value != state["m0"]:
                frac = max(frac, _clamp((m.value - state["m0"]) / (stop.value - state["m0"])))
        if progress(Progress(t, lib.sph_sim_steps(s), case.end, frac, now - start)):
            interrupt.value = 1

    def on_step(ctx, s):
        # Every step comes here, with or without a progress callback: the
        # interpreter runs its signal handlers only while Python code runs, so
        # this is where Ctrl-C reaches a long run.
        if state["raised"] is not None:
            return
        try:
            if progress is not None:
                report(s)
        except BaseException as e:  # noqa: B036 - raised again after the final snapshot
            state["raised"] = e
            interrupt.value = 1

    def on_signal(sig, frame):
        # runs between two steps (the interpreter's handlers run in on_step)
        if state.get("signal"):
            signal.signal(sig, signal.SIG_DFL)
            os.kill(os.getpid(), sig)
            return
        state["signal"] = sig
        interrupt.value = 1

    callback = _library.PROGRESS(on_step)
    opts = _library.RunOptions()
    opts.outdir = os.fsencode(outdir)
    opts.progress = callback
    opts.interrupt = ctypes.pointer(interrupt)
    result = _library.RunResult()
    caught = {}
    if threading.current_thread() is threading.main_thread():
        for sig in (signal.SIGINT, signal.SIGTERM):
            caught[sig] = signal.signal(sig, on_signal)
    try:
        outdir.mkdir(parents=True, exist_ok=True)
        lib.sph_run(sim, ctypes.byref(opts), ctypes.byref(result), ctypes.byref(err))
        reached = lib.sph_sim_time(sim)
        if progress is not None and state["raised"] is None:
            try:
                report(sim, final=True)
            except BaseException as e:  # noqa: B036
                state["raised"] = e
    finally:
        lib.sph_sim_free(sim)
        for sig, handler in caught.items():
            signal.signal(sig, handler)
    status = _STATUS.get(result.status, "error")
    r = Run(case, outdir, status, reached, result.steps, result.outputs,
            result.last_snapshot.decode() or None, time.monotonic() - start)
    if state["raised"] is not None:
        raise state["raised"]
    if state.get("signal") == signal.SIGINT:
        raise KeyboardInterrupt("interrupted at t = %.9g s; final snapshot %s" % (
            r.time, r.last_snapshot))
    if state.get("signal") == signal.SIGTERM:
        raise SystemExit(128 + signal.SIGTERM)
    if status == "blowup":
        raise BlowUpError(_library.message(err), r)
    if status == "error":
        raise _library.Error(_library.message(err))
    return r
