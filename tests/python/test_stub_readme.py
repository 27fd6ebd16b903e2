"""The .pyi stub covers the module, the docstrings carry units, the README's example runs."""
import ast
import os
import re

import pinmask


def stub_names(path):
    tree = ast.parse(open(path).read())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return names, tree


def test_stub_lists_every_public_name(source_dir):
    stub = os.path.join(os.path.dirname(pinmask.__file__), "__init__.pyi")
    assert os.path.exists(stub), "the stub must sit beside the module, as the package's __init__.pyi"
    assert open(stub).read() == open(source_dir / "python" / "pinmask.pyi").read()
    names, tree = stub_names(stub)
    public = {n for n in dir(pinmask) if not n.startswith("_")} | {"__version__"}
    assert public - names == set(), "missing from pinmask.pyi"
    # Class members too.
    classes = {n.name: n for n in tree.body if isinstance(n, ast.ClassDef)}
    for cls_name, node in classes.items():
        members = set()
        for b in node.body:
            if isinstance(b, ast.FunctionDef):
                members.add(b.name)
            elif isinstance(b, ast.AnnAssign):
                members.add(b.target.id)
        cls = getattr(pinmask, cls_name)
        public_members = {n for n in vars(cls) if not n.startswith("_")}
        assert public_members - members == set(), cls_name


def test_every_function_has_a_docstring():
    for name in dir(pinmask):
        obj = getattr(pinmask, name)
        if callable(obj) and not name.startswith("_"):
            doc = obj.__doc__ or ""
            # pybind11 puts the signature first; the text must follow it.
            assert len(doc.split("\n", 1)[-1].strip()) > 20, name
    assert "metres" in pinmask.__doc__


def test_readme_python_example_runs(source_dir, tmp_path, monkeypatch):
    text = (source_dir / "README.md").read_text()
    section = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    assert len(blocks) == 1, "the Python section holds one python example"
    monkeypatch.chdir(tmp_path)
    exec(compile(blocks[0], "README.md (Python example)", "exec"), {})


def test_stub_parameters_match_the_module(source_dir):
    """Every function's parameter names in pinmask.pyi are the module's, in the same order."""
    _, tree = stub_names(str(source_dir / "python" / "pinmask.pyi"))
    checked = 0
    for node in tree.body:
        if not isinstance(node, ast.FunctionDef):
            continue
        doc = (getattr(pinmask, node.name).__doc__ or "").split("\n", 1)[0]
        m = re.match(rf"{node.name}\((.*)\) ->", doc)
        if not m:  # overloaded or not a pybind11 function
            continue
        # pybind11 writes "name: type = default" per parameter; defaults may hold commas.
        names = re.findall(r"(?:^|, )(\w+): ", m.group(1))
        assert [a.arg for a in node.args.args + node.args.kwonlyargs] == names, node.name
        checked += 1
    assert checked > 30
