# SPDX-License-Identifier: BSD-3-Clause
"""A case: a case file or a dict, with overrides, read by libsph's reader.

A dict is written as JSON (a subset of YAML) and read by the same reader as
a file, so it takes the keys of doc/case-files.md and is refused with the
same messages (line numbers then count in the JSON text, `<dict>`). The
overrides are the command line's --set: dotted keys with values, each value
written as YAML (JSON), e.g. {"numerics.dx": 0.001, "physics.gravity":
[0, -9.81]}, or "key=value" strings as the command line takes them.
"""
import ctypes
import json
import os

from . import _library


def _override_strings(overrides):
    if overrides is None:
        return []
    if isinstance(overrides, dict):
        return ["%s=%s" % (k, json.dumps(v)) for k, v in overrides.items()]
    if isinstance(overrides, str):
        overrides = [overrides]
    out = []
    for s in overrides:
        if "=" not in s:
            raise _library.CaseError("override %r: expected key=value" % (s,))
        out.append(s)
    return out


def _find_case(name):
    """The case file name names, as `sph run NAME` finds it (libsph's
    sph_case_find): a path as given if it names a file; a bare name in
    ./cases, then among the installed example cases."""
    lib = _library.library(2)
    arg = os.fsencode(name)
    buf = ctypes.create_string_buffer(4096)
    why = ctypes.create_string_buffer(8192)
    found = lib.sph_case_find(arg, buf, len(buf), why, len(why))
    if not found:
        raise _library.CaseError(why.value.decode(errors="replace"))
    return os.fsdecode(buf.value if found == ctypes.addressof(buf) else arg)


def _parse_listing(text):
    """sph_case_describe's "dotted.key: value" lines as a dict; values read as
    YAML scalars/flow lists would be (numbers, lists of numbers, text)."""
    out = {}
    for line in text.splitlines():
        key, sep, value = line.partition(": ")
        if not sep:
            continue
        try:
            out[key] = json.loads(value)
        except ValueError:
            out[key] = value
    return out


class Case:
    """A case, loaded and validated by libsph.

    Case("cases/martin_moyce.yaml"), Case("martin_moyce") (an installed
    example), Case({...}) (a dict of the case file's keys), each with
    overrides=... . Raises sph.CaseError with the reader's message.
    """

    def __init__(self, source, overrides=None):
        if isinstance(source, dict):
            text = json.dumps(source, indent=2).encode()
            self.origin = "<dict>"
        else:
            self.origin = _find_case(os.fspath(source))
            with open(self.origin, "rb") as f:
                text = f.read()
        self.text = text
        self.overrides = _override_strings(overrides)
        sets = (ctypes.c_char_p * max(1, len(self.overrides)))(*[s.encode() for s in self.overrides])
        n = len(self.overrides)
        origin = self.origin.encode()
        err = _library.error_buffer()
        dim = ctypes.c_int(2)
        lib2 = _library.library(2)
        if lib2.sph_case_text_dimension(text, len(text), origin, sets, n, ctypes.byref(dim), ctypes.byref(err)):
            raise _library.CaseError(_library.message(err))
        self.dimension = dim.value
        self._lib = _library.library(self.dimension)
        self._ptr = self._lib.sph_bind_case_new()
        if not self._ptr:
            raise MemoryError("sph: no memory for a case")
        if self._lib.sph_case_parse(text, len(text), origin, sets, n, self._ptr, ctypes.byref(err)):
            self._lib.sph_bind_case_delete(self._ptr)
            self._ptr = None
            raise _library.CaseError(_library.message(err))
        self.listing = _library.take_string(self._lib, self._lib.sph_case_describe(self._ptr))
        self.parameters = _parse_listing(self.listing)
        self.name = self.parameters["name"]
        self.end = float(self.parameters["time.end"])

    def __del__(self):
        if getattr(self, "_ptr", None):
            self._lib.sph_bind_case_delete(self._ptr)
            self._ptr = None

    def __repr__(self):
        return "<sph.Case %s (%d-D, to t = %g s) from %s>" % (self.name, self.dimension, self.end, self.origin)

    def run(self, outdir=None, **kw):
        """Runs the case (sph.run); returns an sph.Run."""
        from .run import run

        return run(self, outdir=outdir, **kw)
