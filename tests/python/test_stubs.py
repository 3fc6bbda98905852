"""The type stubs (python/cropsight/*.pyi) name what the package has: every public name of a module
is in its stub, and every class, method, property and attribute a stub declares exists."""
import ast
import importlib
import os

import pytest

import cropsight

STUB_ONLY = {"ConfigMapping"}  # the shape every crop's Config shares, declared once (_config.pyi)
MODULES = ["cropsight", "cropsight.broccoli", "cropsight.potato", "cropsight.seedling", "cropsight.grape",
           "cropsight.simulate"]


def stub_of(module_name):
    folder = os.path.dirname(cropsight.__file__)
    name = "__init__" if module_name == "cropsight" else module_name.split(".")[1]
    with open(os.path.join(folder, name + ".pyi")) as f:
        return ast.parse(f.read())


@pytest.mark.parametrize("module_name", MODULES)
def test_stub_matches_module(module_name):
    module = importlib.import_module(module_name)
    tree = stub_of(module_name)
    declared = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and node.name not in STUB_ONLY:
            members = set()
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    members.add(item.name)
                elif isinstance(item, ast.AnnAssign):
                    members.add(item.target.id)
            declared[node.name] = members
        elif isinstance(node, ast.FunctionDef):
            declared[node.name] = set()
        elif isinstance(node, ast.ImportFrom) and node.level == 1:  # explicit re-exports: "import X as X"
            for alias in node.names:
                if alias.asname == alias.name:
                    declared.setdefault(alias.name, set())
    public = set(getattr(module, "__all__", [])) - {"broccoli", "grape", "potato", "seedling", "simulate"}
    assert public <= set(declared), public - set(declared)
    for name, members in declared.items():
        assert hasattr(module, name), f"{module_name}.{name} in the stub only"
        for member in members:
            assert hasattr(getattr(module, name), member), f"{module_name}.{name}.{member} in the stub only"
