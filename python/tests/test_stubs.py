"""The committed type stubs (python/proxima/__init__.pyi, d2.pyi) parse and name every public
item of the compiled module, so editors complete the whole API; rerun
python/tools/make_stubs.py when this fails."""

import ast
import inspect
import pathlib

import proxima
import proxima._proxima as native

PACKAGE = pathlib.Path(__file__).parents[1] / "proxima"


def stub_names(path):
    tree = ast.parse(path.read_text())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names


def public(module):
    return {n for n, v in vars(module).items() if not n.startswith("_") and not inspect.ismodule(v)}


def test_the_stubs_name_every_public_item():
    assert public(native) <= stub_names(PACKAGE / "__init__.pyi")
    assert public(native.d2) <= stub_names(PACKAGE / "d2.pyi")


def test_every_function_has_a_docstring():
    for module in (native, native.d2):
        for name, value in vars(module).items():
            if not name.startswith("_") and callable(value) and not inspect.isclass(value):
                assert (value.__doc__ or "").count("\n\n") >= 1, name  # signature line, then the text
    assert proxima.d2.Circle is native.d2.Circle
