#!/usr/bin/python3
"""Type stubs of the compiled module gransim._gransim, from the signatures pybind11 writes into
its docstrings: python/gransim/_gransim.pyi (editors and type checkers read it; the test
tests/python/test_stubs.py checks that it matches the module built). Signatures only: the
descriptions, with their units, stay in the module's docstrings (help()).

usage: PYTHONPATH=build/python python3 tools/python_stubs.py [--check] [OUT.pyi]
"""
import argparse
import inspect
import os
import re
import sys

HEADER = '''"""Type stubs of gransim._gransim (written by tools/python_stubs.py from the module's
signatures; do not edit by hand)."""
# flake8: noqa
from typing import Any, Callable, Dict, Iterable, Iterator, List, Optional, Sequence, Tuple, Union, overload

import numpy
'''


def clean(sig):
    """a pybind11 signature as stub syntax: module paths dropped, numpy arrays kept"""
    sig = sig.replace("gransim._gransim.", "")
    sig = re.sub(r"numpy\.ndarray\[[^\]]*\]", "numpy.ndarray", sig)
    # default values pybind11 cannot print (<object at 0x…>) become ...
    sig = re.sub(r"= <[^>]*>", "= ...", sig)
    # a default repr that is not an expression (an enum's) becomes ...
    sig = re.sub(r"= ([A-Za-z_][\w.]*)\.([A-Za-z_]\w*)(?=[,)])", "= ...", sig)
    return sig


def signatures(obj, name):
    """the signature lines of a pybind11 function or method (overloads: several)"""
    doc = getattr(obj, "__doc__", None) or ""
    lines = [s.strip() for s in doc.splitlines()]
    out = [s for s in lines if s.startswith(name + "(")]
    # overloads are listed as "1. name(...)" after a generic "name(*args, **kwargs)"
    overloads = [re.sub(r"^\d+\. ", "", s) for s in lines
                 if re.match(r"^\d+\. " + re.escape(name) + r"\(", s)]
    if overloads:
        out = overloads
    return [clean(s) for s in out]


def function_stub(name, obj, indent=""):
    sigs = signatures(obj, name)
    if not sigs:
        return [f"{indent}def {name}(*args: Any, **kwargs: Any) -> Any: ..."]
    out = []
    for s in sigs:
        if len(sigs) > 1:
            out.append(f"{indent}@overload")
        out.append(f"{indent}def {s}: ...")
    return out


def property_stub(name, prop, indent):
    doc = getattr(prop.fget, "__doc__", "") or ""
    m = re.search(r"\) -> (.+)$", doc.splitlines()[0] if doc else "")
    ret = clean(m.group(1)) if m else "Any"
    return [f"{indent}@property", f"{indent}def {name}(self) -> {ret}: ..."]


def class_stub(name, cls):
    bases = [b.__name__ for b in cls.__bases__ if b.__name__ not in ("pybind11_object", "object")]
    out = [f"class {name}({', '.join(bases)}):" if bases else f"class {name}:"]
    for attr, value in sorted(vars(cls).items()):
        if attr.startswith("_") and attr not in ("__init__", "__len__", "__enter__", "__exit__"):
            continue
        if isinstance(value, property):
            out += property_stub(attr, value, "    ")
        elif callable(value) and type(value).__name__ in ("instancemethod", "builtin_function_or_method"):
            out += function_stub(attr, value, "    ")
        elif inspect.isfunction(value):  # added by the package in Python (Scene.to_dict)
            out.append(f"    def {attr}{inspect.signature(value)}: ...")
    if len(out) == 1:
        out.append("    ...")
    return out


def stubs(module):
    out = [HEADER]
    names = sorted(n for n in dir(module) if not n.startswith("__"))
    for n in names:
        v = getattr(module, n)
        if inspect.isclass(v) and issubclass(v, BaseException):
            out.append(f"class {n}({v.__bases__[-1].__name__}): ...")
    for n in names:
        v = getattr(module, n)
        if inspect.isclass(v) and not issubclass(v, BaseException):
            out += [""] + class_stub(n, v)
    out.append("")
    for n in names:
        v = getattr(module, n)
        if inspect.ismodule(v):
            out.append(f"{n}: Any  # submodule")
        elif callable(v) and not inspect.isclass(v):
            out += function_stub(n, v)
        elif isinstance(v, (bool, int, float, str)):
            out.append(f"{n}: {type(v).__name__}")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", default=os.path.join(
        os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "python", "gransim",
        "_gransim.pyi"))
    ap.add_argument("--check", action="store_true",
                    help="exit 1 when OUT differs from the module's stubs (nothing written)")
    a = ap.parse_args()
    from gransim import _gransim

    text = stubs(_gransim)
    if a.check:
        with open(a.out, encoding="utf-8") as f:
            if f.read() != text:
                print(f"{a.out} is not the stub of the module built: run tools/python_stubs.py")
                return 1
        return 0
    with open(a.out, "w", encoding="utf-8") as f:
        f.write(text)
    print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
