"""The type stubs (volspline/_volspline.pyi) describe the module as built."""
import ast
import importlib.util
import os
import pathlib

import volspline
import volspline._volspline as module

SOURCE = pathlib.Path(os.environ.get("VOLSPLINE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def load_generator():
    spec = importlib.util.spec_from_file_location("make_stubs", SOURCE / "python" / "tools" / "make_stubs.py")
    generator = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generator)
    return generator


def test_committed_stubs_are_what_the_module_gives():
    committed = (SOURCE / "python" / "volspline" / "_volspline.pyi").read_text()
    assert committed == load_generator().make_stubs(module), (
        "python/volspline/_volspline.pyi is stale: run python/tools/make_stubs.py (docs/python.md)"
    )


def test_stubs_parse_and_name_every_public_name():
    tree = ast.parse((SOURCE / "python" / "volspline" / "_volspline.pyi").read_text())
    defined = {node.name for node in tree.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    public = {name for name in dir(module) if not name.startswith("_")}
    assert public <= defined, public - defined
    exported = {name for name in volspline.__all__ if not name.startswith("_")} - {"to_meshio", "to_vtk"}
    assert exported <= defined, exported - defined
    # Every function has a docstring that help() shows.
    for name in public:
        assert getattr(module, name).__doc__, name
