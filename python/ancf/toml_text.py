"""Python values as TOML text: the values of overrides and the scenes SceneBuilder writes.

Numbers are written so that they read back to the same double (repr), strings as TOML basic
strings, lists as arrays, dicts as inline tables. Only what the scene format uses is supported.
"""

import math
import numbers

__all__ = ["value", "document"]


def _string(s):
    out = ['"']
    for ch in s:
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append("\\u%04x" % ord(ch))
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _key(k):
    k = str(k)
    if k and all(c.isalnum() or c in "_-" for c in k):
        return k
    return _string(k)


def value(v):
    """TOML text of one value: bool, int, float, str, a sequence or a dict (inline table)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        f = float(v)
        if math.isnan(f):
            return "nan"
        if math.isinf(f):
            return "inf" if f > 0 else "-inf"
        text = repr(f)
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {value(x)}" for k, x in v.items()) + " }"
    if hasattr(v, "tolist"):  # numpy arrays and scalars
        return value(v.tolist())
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(value(x) for x in v) + "]"
    raise TypeError(f"no TOML value for {type(v).__name__}: {v!r}")


def _table(lines, header, table):
    """[header] with its plain keys, then its sub-tables ([header.sub]) and arrays of tables."""
    plain = {k: x for k, x in table.items() if not _is_table(x) and not _is_table_array(x)}
    if header is not None:
        lines.append("")
        lines.append(header)
    for k, x in plain.items():
        lines.append(f"{_key(k)} = {value(x)}")
    for k, x in table.items():
        name = _key(k) if header is None else f"{header.strip('[]')}.{_key(k)}"
        if _is_table(x):
            _table(lines, f"[{name}]", x)
        elif _is_table_array(x):
            for entry in x:
                _table(lines, f"[[{name}]]", entry)


def _is_table(x):
    return isinstance(x, dict)


def _is_table_array(x):
    return isinstance(x, (list, tuple)) and len(x) > 0 and all(isinstance(e, dict) for e in x)


def document(root):
    """A TOML document from nested dicts: dicts become tables, lists of dicts arrays of tables
    (one key per line, so that error lines point at the key)."""
    lines = []
    _table(lines, None, root)
    return "\n".join(lines).lstrip("\n") + "\n"
