# SPDX-License-Identifier: BSD-3-Clause
"""Finding and loading libsph (2-D) and libsph3 (3-D) through ctypes.

The two libraries export the same names, one per dimension; each is loaded
on first use with RTLD_LOCAL, so both live in one process without meeting.
Where a library is looked for, in order: $SPH_LIBDIR; the build tree this
package sits in (python/sph beside src/.libs); the directory `make install`
put the libraries in (written into _paths.py at install). The structures a
call fills (sph_error, sph_run_options, sph_run_result) are mirrored below
and checked against the library's own sizes (sph_bind_sizeof) at load, so
a mirror that falls behind the C headers stops the import with a message
instead of corrupting memory.
"""
import ctypes
import os
from pathlib import Path

_NAMES = {2: "libsph", 3: "libsph3"}
_loaded = {}


class Error(Exception):
    """A failure reported by libsph: its message, as the command line prints it."""


class CaseError(Error, ValueError):
    """A case the reader refused (file, line, key and what was expected)."""


Error.__module__ = CaseError.__module__ = "sph"  # as the user names them: sph.CaseError


def _directories():
    env = os.environ.get("SPH_LIBDIR")
    if env:
        yield Path(env)
    here = Path(__file__).resolve().parent
    yield here.parent.parent / "src" / ".libs"  # the build tree
    try:
        from . import _paths
    except ImportError:
        return
    yield Path(_paths.LIBDIR)


def _find(dim):
    base = _NAMES[dim]
    tried = []
    for d in _directories():
        for name in (base + ".so", base + ".so.2" if dim == 2 else base + ".so.0"):
            path = d / name
            tried.append(str(path))
            if path.exists():
                return path
    raise Error(
        "cannot find %s.so (looked for %s); build sph (make), install it (make install), "
        "or name its directory in SPH_LIBDIR" % (base, ", ".join(tried))
    )


class ErrorBuffer(ctypes.Structure):
    _fields_ = [("msg", ctypes.c_char * 1024)]


PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_void_p)
ROW = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_void_p)


class RunOptions(ctypes.Structure):
    _fields_ = [
        ("outdir", ctypes.c_char_p),
        ("progress", PROGRESS),
        ("progress_ctx", ctypes.c_void_p),
        ("interrupt", ctypes.POINTER(ctypes.c_int)),  # volatile sig_atomic_t: int on Linux
        ("row", ROW),
        ("row_ctx", ctypes.c_void_p),
    ]


class RunResult(ctypes.Structure):
    _fields_ = [
        ("status", ctypes.c_int),
        ("steps", ctypes.c_long),
        ("outputs", ctypes.c_size_t),
        ("last_snapshot", ctypes.c_char * 4096),
    ]


_MIRRORS = {"sph_error": ErrorBuffer, "sph_run_options": RunOptions, "sph_run_result": RunResult}


def _declare(lib):
    P, I, D, L, S = ctypes.c_void_p, ctypes.c_int, ctypes.c_double, ctypes.c_long, ctypes.c_size_t
    C = ctypes.c_char_p
    sigs = {
        "sph_version": (C, []),
        "sph_bind_sizeof": (S, [C]),
        "sph_bind_case_new": (P, []),
        "sph_bind_case_delete": (None, [P]),
        "sph_bind_free": (None, [P]),
        "sph_set_threads": (I, [I]),
        "sph_case_text_dimension": (I, [C, S, C, ctypes.POINTER(C), S, ctypes.POINTER(I), P]),
        "sph_case_parse": (I, [C, S, C, ctypes.POINTER(C), S, P, P]),
        "sph_case_describe": (P, [P]),
        "sph_sim_create": (I, [P, ctypes.POINTER(P), P]),
        "sph_sim_free": (None, [P]),
        "sph_sim_time": (D, [P]),
        "sph_sim_steps": (L, [P]),
        "sph_run_stop_measure": (I, [P, ctypes.POINTER(D), ctypes.POINTER(D)]),
        "sph_run": (I, [P, ctypes.POINTER(RunOptions), ctypes.POINTER(RunResult), P]),
        "sph_run_status_name": (C, [I]),
        "sph_case_find": (P, [C, C, S, C, S]),
    }
    for name, (res, args) in sigs.items():
        f = getattr(lib, name)
        f.restype = res
        f.argtypes = args
    for name, mirror in _MIRRORS.items():
        want = lib.sph_bind_sizeof(name.encode())
        if want != ctypes.sizeof(mirror):
            raise Error(
                "%s: %s is %d bytes in the library, %d in python/sph/_library.py: the module "
                "and the library are not of one version (rebuild, or reinstall both)"
                % (lib._name, name, want, ctypes.sizeof(mirror))
            )


def library(dim):
    """The loaded library of dimension dim (2 or 3)."""
    if dim not in _NAMES:
        raise Error("dimension %r: expected 2 or 3" % (dim,))
    if dim not in _loaded:
        lib = ctypes.CDLL(str(_find(dim)), mode=os.RTLD_LOCAL)
        _declare(lib)
        _loaded[dim] = lib
    return _loaded[dim]


def error_buffer():
    return ErrorBuffer()


def message(err):
    return err.msg.decode("utf-8", "replace")


def take_string(lib, ptr):
    """A malloc'd C string from the library, as str, freed."""
    if not ptr:
        return None
    try:
        return ctypes.string_at(ptr).decode("utf-8", "replace")
    finally:
        lib.sph_bind_free(ptr)


def version():
    """The library's version string, e.g. 'sph 0.2.0'."""
    return library(2).sph_version().decode()
