"""Python values → TOML text, for scenes given as dicts and for --set style overrides, and
back (one value's TOML text → a Python value, for Scene.to_dict).

The text goes through the same scene parser as a file, so every error carries the parser's
message (key, what is wrong, what is accepted)."""

import math
import numbers

try:
    import tomllib as _tomllib  # Python 3.11
except ImportError:  # pragma: no cover - older interpreters read values themselves
    _tomllib = None

__all__ = ["dumps", "loads_value", "value_text"]


def _key(k):
    k = str(k)
    if k and all(c.isalnum() or c in "_-" for c in k):
        return k
    return _string(k)


def _string(s):
    out = ['"']
    for c in s:
        if c in '"\\':
            out.append("\\" + c)
        elif ord(c) < 0x20 or ord(c) == 0x7F:
            out.append("\\u%04x" % ord(c))
        else:
            out.append(c)
    out.append('"')
    return "".join(out)


def value_text(v):
    """one value as TOML text: strings quoted, booleans lower case, lists as arrays"""
    if isinstance(v, bool) or type(v).__name__ == "bool_":
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        x = float(v)
        if math.isnan(x):
            return "nan"
        if math.isinf(x):
            return "inf" if x > 0 else "-inf"
        return repr(x)
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k)} = {value_text(x)}" for k, x in v.items()) + "}"
    if hasattr(v, "tolist"):
        return value_text(v.tolist())
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value_text(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} {v!r} as a TOML value")


def _is_table_array(v):
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _emit(table, prefix, lines):
    # plain keys first, then sub-tables and arrays of tables (TOML needs that order)
    for k, v in table.items():
        if not isinstance(v, dict) and not _is_table_array(v):
            lines.append(f"{_key(k)} = {value_text(v)}")
    for k, v in table.items():
        name = f"{prefix}.{_key(k)}" if prefix else _key(k)
        if isinstance(v, dict):
            lines.append("")
            lines.append(f"[{name}]")
            _emit(v, name, lines)
        elif _is_table_array(v):
            for item in v:
                lines.append("")
                lines.append(f"[[{name}]]")
                _emit(item, name, lines)


def dumps(doc):
    """a dict of tables (as a scene file holds them) as TOML text"""
    if not isinstance(doc, dict):
        raise TypeError("a scene must be a dict of tables")
    lines = []
    _emit(doc, "", lines)
    return "\n".join(lines).lstrip("\n") + "\n"


def loads_value(text):
    """one TOML value (as Scene.resolved holds it: '8.0', '"name"', '[0.1, 0.2]') as a Python
    value: int, float, bool, str, list or dict; text that is not a TOML value is returned as is"""
    if _tomllib is not None:
        try:
            return _tomllib.loads("v = " + text)["v"]
        except _tomllib.TOMLDecodeError:
            return text
    try:
        value, rest = _value(text.strip())
    except (ValueError, IndexError):
        return text
    return value if not rest.strip() else text


def _value(t):
    """(value, rest of the text) for the TOML subset a scene's values use"""
    import json

    t = t.lstrip()
    if t.startswith("["):
        out, t = [], t[1:].lstrip()
        while not t.startswith("]"):
            v, t = _value(t)
            out.append(v)
            t = t.lstrip()
            t = t[1:].lstrip() if t.startswith(",") else t
        return out, t[1:]
    if t.startswith("{"):
        out, t = {}, t[1:].lstrip()
        while not t.startswith("}"):
            k, t = t.split("=", 1)
            v, t = _value(t)
            out[k.strip().strip('"')] = v
            t = t.lstrip()
            t = t[1:].lstrip() if t.startswith(",") else t
        return out, t[1:]
    if t.startswith('"'):
        end = 1
        while t[end] != '"':
            end += 2 if t[end] == "\\" else 1
        return json.loads(t[: end + 1]), t[end + 1:]
    if t.startswith("'"):
        end = t.index("'", 1)
        return t[1:end], t[end + 1:]
    n = 0
    while n < len(t) and t[n] not in ",]}":
        n += 1
    word, rest = t[:n].strip(), t[n:]
    if word in ("true", "false"):
        return word == "true", rest
    if word.lstrip("+-") in ("inf", "nan"):
        return float(word), rest
    word = word.replace("_", "")
    try:
        return int(word, 0) if word.lstrip("+-")[:2] in ("0x", "0o", "0b") else int(word), rest
    except ValueError:
        return float(word), rest
