"""Writes the type stubs of the compiled module (python/proxima/__init__.pyi and d2.pyi) from
the signatures pybind11 puts on the first line of each docstring, so that editors complete the
API. Run after building: PYTHONPATH=build/release/python /usr/bin/python3 python/tools/make_stubs.py
(python/tests/test_stubs.py checks that the committed stubs name every public item)."""

import inspect
import pathlib
import re
import sys

import numpy  # noqa: F401  (the dtypes' repr)

import proxima
import proxima._proxima as native

HEADER = '"""Type stubs of proxima (written by python/tools/make_stubs.py from the module; do not edit)."""\n'
IMPORTS = "from typing import Any, Iterator, List, Optional, Tuple\n\nimport numpy\n\n"


def clean(signature):
    """A pybind11 signature as Python stub syntax: py::handle arguments become Any (they take
    sequences, arrays or poses), module prefixes go, long numeric defaults become ...."""
    s = signature.replace("proxima._proxima.d2.", "").replace("proxima._proxima.", "")
    s = re.sub(r"\bhandle\b", "Any", s)
    s = re.sub(r"(?<=: )object\b|(?<=-> )object\b", "Any", s)
    s = elide_defaults(s)
    s = re.sub(r"\bnumpy\.ndarray\[[^\]]*\]", "numpy.ndarray", s)
    s = s.replace("numpy.ndarray[numpy.float64]", "numpy.ndarray")
    return s


def elide_defaults(signature):
    """name(a: T = <repr>, ...) -> R with every default written as `...` (a default's repr may
    hold commas and brackets, so the arguments are split at top-level commas)."""
    if "(" not in signature:
        return signature
    open_at = signature.index("(")
    depth, close_at = 0, None
    for i in range(open_at, len(signature)):
        depth += signature[i] in "([{"
        depth -= signature[i] in ")]}"
        if depth == 0:
            close_at = i
            break
    args, depth, current = [], 0, ""
    for ch in signature[open_at + 1:close_at]:
        if ch == "," and depth == 0:
            args.append(current.strip())
            current = ""
            continue
        depth += ch in "([{"
        depth -= ch in ")]}"
        current += ch
    if current.strip():
        args.append(current.strip())
    args = [a.split(" = ", 1)[0] + " = ..." if " = " in a else a for a in args]
    return signature[:open_at + 1] + ", ".join(args) + signature[close_at:]


def signatures(obj, name):
    """Every overload's signature line of a pybind11 callable."""
    doc = obj.__doc__ or ""
    lines = [ln for ln in doc.splitlines() if ln.startswith(name + "(")]
    return [clean(ln) for ln in lines] or [f"{name}(*args: Any, **kwargs: Any) -> Any"]


def summary(obj):
    doc = (obj.__doc__ or "").split("\n\n", 1)
    text = doc[1].strip() if len(doc) > 1 else ""
    return text.splitlines()[0].replace('"""', "'") if text else ""


def function_stub(obj, name, indent=""):
    out = []
    sigs = signatures(obj, name)
    for sig in sigs:
        if len(sigs) > 1:
            out.append(f"{indent}@overload")
        doc = summary(obj)
        body = f' """{doc}"""' if doc else " ..."
        out.append(f"{indent}def {sig}:{body}")
    return out


def class_stub(cls):
    bases = [b.__name__ for b in cls.__bases__ if b.__module__.startswith("proxima")]
    out = [f"class {cls.__name__}({', '.join(bases)}):" if bases else f"class {cls.__name__}:"]
    if cls.__doc__:
        out.append(f'    """{cls.__doc__.splitlines()[0]}"""')
    if hasattr(cls, "__members__"):  # an enumeration
        for member in cls.__members__:
            out.append(f"    {member}: {cls.__name__}")
        out.append("    def __int__(self) -> int: ...")
        out.append("    @property\n    def name(self) -> str: ...")
        return out
    for name, member in sorted(vars(cls).items()):
        if name.startswith("_") and name not in ("__init__", "__len__", "__contains__", "__mul__", "__eq__"):
            continue
        if isinstance(member, property):
            ret = "Any"
            if member.fget is not None and member.fget.__doc__:
                match = re.search(r"-> (.+)$", member.fget.__doc__.splitlines()[0])
                ret = clean(match.group(1)) if match else "Any"
            out.append(f"    @property\n    def {name}(self) -> {ret}: ...")
        elif isinstance(member, staticmethod) or type(member).__name__ == "builtin_function_or_method":
            out += ["    @staticmethod"] + function_stub(getattr(cls, name), name, "    ")
        elif callable(member):
            out += function_stub(member, name, "    ")
    return out


def module_stub(module):
    lines = [HEADER, IMPORTS, "from typing import overload\n"]
    for name, value in sorted(vars(module).items()):
        if name.startswith("_") or inspect.ismodule(value):
            continue
        if inspect.isclass(value) and issubclass(value, BaseException):
            lines.append(f"class {name}(ValueError):\n    code: str\n    field: str\n    message: str\n")
        elif inspect.isclass(value):
            lines.append("\n".join(class_stub(value)) + "\n")
        elif callable(value):
            lines.append("\n".join(function_stub(value, name)) + "\n")
        else:
            kind = "numpy.dtype" if isinstance(value, numpy.dtype) else type(value).__name__
            lines.append(f"{name}: {kind}\n")
    return "\n".join(lines)


def main():
    package = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parents[1] / "proxima")
    top = module_stub(native).replace(HEADER, HEADER + "\nfrom . import d2 as d2\n", 1)
    (package / "__init__.pyi").write_text(top + "\n__version__: str\n")
    (package / "d2.pyi").write_text(module_stub(native.d2))
    print(f"wrote {package / '__init__.pyi'} and {package / 'd2.pyi'}")


if __name__ == "__main__":
    main()
