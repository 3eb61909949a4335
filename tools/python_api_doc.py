#!/usr/bin/python3
"""The API reference of the gransim Python package, generated from its docstrings:
docs/python-api.md (tests/python/test_stubs.py checks that it names everything the package
exports and every member of its classes).

usage: PYTHONPATH=build/python python3 tools/python_api_doc.py [OUT.md]
"""
import inspect
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def signature(name, obj):
    """name(arguments) from Python's signature, else from pybind11's first docstring line"""
    try:
        return name + re.sub(r"^\((self|cls)(, )?", "(", str(inspect.signature(obj)))
    except (TypeError, ValueError):
        pass
    doc = getattr(obj, "__doc__", "") or ""
    short = name.split(".")[-1]
    prefix = name[: len(name) - len(short)]
    found = []
    for line in doc.splitlines():
        line = re.sub(r"^\d+\. ", "", line.strip())
        if line.startswith(short + "(") and "*args, **kwargs" not in line:
            line = line.replace("gransim._gransim.", "")
            line = re.sub(r"numpy\.ndarray\[[^\]]*\]", "numpy.ndarray", line)
            found.append(prefix + re.sub(r"\(self: [\w.]+(, )?", "(", line))
    return " / ".join(found) if found else f"{name}(...)"


def description(obj):
    doc = inspect.getdoc(obj) or ""
    keep = [s for s in doc.splitlines()
            if not re.match(r"^(\d+\. )?\w+\(.*\)( -> .*)?$", s.strip())
            and s.strip() != "Overloaded function."]
    return "\n".join(keep).strip()


def entry(title, obj):
    text = description(obj)
    return f"### `{title}`\n\n{text}\n" if text else f"### `{title}`\n"


def members(cls):
    out = []
    for name, value in sorted(vars(cls).items()) + sorted(
            (n, v) for b in cls.__mro__[1:] if b.__module__.startswith("gransim")
            for n, v in vars(b).items() if n not in vars(cls)):
        if name.startswith("_") and name != "__init__":
            continue
        if name == "__init__" and "Initialize self" in (getattr(value, "__doc__", "") or ""):
            continue
        if isinstance(value, property):
            out.append(entry(f"{cls.__name__}.{name}", value))
        elif isinstance(value, classmethod):
            out.append(entry(signature(f"{cls.__name__}.{name}", value.__func__), value.__func__))
        elif callable(value):
            out.append(entry(signature(f"{cls.__name__}.{name}", value), value))
    return out


def page(gransim):
    out = ["# Python API reference", "",
           "Generated from the docstrings of the `gransim` package by "
           "`tools/python_api_doc.py`; the guide with examples is "
           "[python-module.md](python-module.md).", ""]
    names = sorted(gransim.__all__, key=str.lower)
    classes = [n for n in names if inspect.isclass(getattr(gransim, n))
               and not issubclass(getattr(gransim, n), BaseException)]
    errors = [n for n in names if inspect.isclass(getattr(gransim, n))
              and issubclass(getattr(gransim, n), BaseException)]
    functions = [n for n in names if n not in classes and n not in errors
                 and callable(getattr(gransim, n)) and not inspect.ismodule(getattr(gransim, n))]
    out += ["## Classes", ""]
    seen = set()
    for n in classes:
        cls = getattr(gransim, n)
        if cls in seen:
            continue
        seen.add(cls)
        out.append(f"## `{n}`\n\n{description(cls)}\n")
        out += members(cls)
    out += ["## Functions", ""]
    for n in functions:
        out.append(entry(signature(n, getattr(gransim, n)), getattr(gransim, n)))
    out += ["## Errors", ""]
    for n in errors:
        e = getattr(gransim, n)
        out.append(f"### `{n}` (a {e.__bases__[-1].__name__})\n")
    out += ["## What this build has", ""]
    what = {"have_movie": "True when the module was built with FFmpeg (MovieEncoder, "
                          "write_movie, probe_movie, movie_frame)",
            "have_osmesa": "True when the module was built with the OSMesa renderer"}
    for n in names:
        if isinstance(getattr(gransim, n), bool):
            out.append(f"### `{n}`\n\n{what.get(n, 'a flag of the build')}\n")
    out += ["## `rfm`: the Random Force Model's measurements", ""]
    for n in sorted(dir(gransim.rfm)):
        v = getattr(gransim.rfm, n)
        if n.startswith("_") or not callable(v):
            continue
        if inspect.isclass(v):
            out.append(f"## `rfm.{n}`\n\n{description(v)}\n")
            out += [s.replace(f"`{v.__name__}.", f"`rfm.{v.__name__}.") for s in members(v)]
        else:
            out.append(entry(signature(f"rfm.{n}", v), v))
    return "\n".join(out).rstrip() + "\n"


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "docs", "python-api.md")
    import gransim

    with open(out, "w", encoding="utf-8") as f:
        f.write(page(gransim))
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
