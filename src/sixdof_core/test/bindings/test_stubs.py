"""The type stubs (python/sixdof_core/__init__.pyi) against the module: the same public names, the same members of
every class (read-only exactly where the module's properties have no setter) and the same parameter names of every
function, method and overload (the module's own signatures, from pybind11's docstrings). Every class and function
has a docstring."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pytest

import sixdof_core

STUB = Path(__file__).resolve().parents[2] / "python" / "sixdof_core" / "__init__.pyi"
TREE = ast.parse(STUB.read_text(encoding="utf-8"))
STUB_CLASSES = {node.name: node for node in TREE.body if isinstance(node, ast.ClassDef)}

def public(name: str) -> bool:
    return not name.startswith("_") or name in ("__init__", "__bool__", "__copy__", "__deepcopy__")


def stub_parameters(node: ast.FunctionDef) -> tuple[str, ...]:
    names = [a.arg for a in node.args.posonlyargs + node.args.args + node.args.kwonlyargs]
    return tuple(n for n in names if n != "self")


def runtime_parameters(obj: object) -> list[tuple[str, ...]]:
    """Parameter names of every overload, from pybind11's signature lines "name(a: T, b: T = ...) -> R"."""
    signatures = []
    for line in (obj.__doc__ or "").splitlines():
        head = line.strip().split(". ", 1)[-1] if line.strip()[:1].isdigit() else line.strip()
        if "(" not in head or ") -> " not in head:
            continue
        inside = head[head.index("(") + 1:head.rindex(") -> ")]
        names, depth, current = [], 0, ""
        for char in inside + ",":
            depth += char in "([{<"
            depth -= char in ")]}>"
            if char == "," and depth == 0:
                names.append(current.split(":")[0].strip())
                current = ""
            else:
                current += char
        signatures.append(tuple(n for n in names if n and n != "self"))
    return signatures


def stub_members(node: ast.ClassDef) -> dict[str, tuple[ast.ClassDef, ast.stmt]]:
    """{name: (the class that declares it, its declaration)}; the stub's private bases (_Enum: what pybind11 gives
    every enum, _Result[Status]: the core's Result) count as the class's own."""
    members: dict[str, tuple[ast.ClassDef, ast.stmt]] = {}
    for base in node.bases:
        base_name = base.value if isinstance(base, ast.Subscript) else base
        if isinstance(base_name, ast.Name) and base_name.id.startswith("_"):
            members.update(stub_members(next(n for n in TREE.body if getattr(n, "name", "") == base_name.id)))
    for item in node.body:
        if isinstance(item, ast.FunctionDef) and public(item.name):
            members.setdefault(item.name, (node, item))
        elif isinstance(item, ast.AnnAssign) and isinstance(item.target, ast.Name):
            members[item.target.id] = (node, item)
    return members


def runtime_members(cls: type) -> dict[str, object]:
    """The class's own public members; a class without a constructor has only pybind11's refusing __init__."""
    members = {k: v for k, v in vars(cls).items() if public(k)}
    if (getattr(members.get("__init__"), "__doc__", "") or "").startswith("Initialize self"):
        del members["__init__"]
    return members


def overloads(node: ast.ClassDef | ast.Module, name: str) -> list[tuple[str, ...]]:
    return sorted(stub_parameters(n) for n in node.body if isinstance(n, ast.FunctionDef) and n.name == name)


def test_the_stub_declares_exactly_the_public_names():
    declared = {n.name for n in TREE.body if isinstance(n, ast.ClassDef | ast.FunctionDef) and public(n.name)}
    assert declared == set(sixdof_core.__all__)
    assert sixdof_core.__all__ == sorted(n for n in vars(sixdof_core._sixdof_core) if not n.startswith("_"))


@pytest.mark.parametrize("name", sixdof_core.__all__)
def test_members_and_parameters(name):
    obj = getattr(sixdof_core, name)
    assert (obj.__doc__ or "").strip(), f"{name} has no docstring"
    if not inspect.isclass(obj):
        assert overloads(TREE, name) == sorted(runtime_parameters(obj))
        return
    node = STUB_CLASSES[name]
    if issubclass(obj, Exception):
        return
    runtime = runtime_members(obj)
    stub = stub_members(node)
    assert set(stub) == set(runtime), f"{name}: stub-only {set(stub) - set(runtime)}, module-only " \
                                      f"{set(runtime) - set(stub)}"
    for member, value in runtime.items():
        owner, declared = stub[member]
        if isinstance(value, property):
            assert isinstance(declared, ast.AnnAssign), f"{name}.{member} is an attribute"
            read_only = isinstance(declared.annotation, ast.Subscript) and getattr(
                declared.annotation.value, "id", "") == "Final"
            assert read_only == (value.fset is None), f"{name}.{member}: Final exactly when read-only"
        elif isinstance(declared, ast.FunctionDef) and member in ("__init__", member.strip("_")):
            assert overloads(owner, member) == sorted(runtime_parameters(getattr(obj, member))), f"{name}.{member}"
