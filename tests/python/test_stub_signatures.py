"""The stub cannot drift: every function and method of python/pinmask.pyi against the module's
runtime signature (pybind11 writes it as the first line of each docstring, from the py::arg
names and defaults): the same parameters in the same order, the same defaults, and return types
that agree."""
import ast
import math
import re

import pytest

import pinmask

STUB_PATH = "python/pinmask.pyi"


def split_top(text, sep=","):
    """Splits at separators outside brackets and quotes."""
    parts, depth, quote, cur = [], 0, None, ""
    for ch in text:
        if quote:
            cur += ch
            if ch == quote:
                quote = None
            continue
        if ch in "'\"":
            quote = ch
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == sep and depth == 0:
            parts.append(cur.strip())
            cur = ""
            continue
        cur += ch
    if cur.strip():
        parts.append(cur.strip())
    return parts


def runtime_signature(obj, name):
    """[(name, default text or None)], return annotation text, from pybind11's docstring."""
    first = (obj.__doc__ or "").split("\n", 1)[0]
    m = re.match(rf"{re.escape(name)}\((.*)\) -> (.*)$", first)
    assert m, f"{name}: no pybind11 signature in its docstring ({first!r})"
    params = []
    for p in split_top(m.group(1)):
        if p.startswith("**"):  # **kwargs: checked against the stub's own **kwargs
            params.append((p, None))
            continue
        if p == "*":  # the keyword-only parameters follow
            params.append(("*", None))
            continue
        pname, rest = p.split(":", 1)
        default = None
        eq = split_top(rest, "=")
        if len(eq) == 2:
            default = eq[1]
        params.append((pname.strip(), default))
    return params, m.group(2).strip()


def normalise(value):
    """A literal as a comparable value: tuples and lists alike, floats by value."""
    if isinstance(value, (list, tuple)):
        return [normalise(v) for v in value]
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(value, (int, float)):
        return float(value)
    return value


def same_default(stub_node, runtime_text, where):
    if isinstance(stub_node, ast.Constant) and stub_node.value is Ellipsis:
        return  # the stub leaves it unsaid (a computed default)
    stub_value = normalise(ast.literal_eval(stub_node))
    try:
        runtime_value = normalise(ast.literal_eval(runtime_text))
    except (ValueError, SyntaxError):
        pytest.fail(f"{where}: runtime default {runtime_text!r} is not a literal; the stub says "
                    f"{ast.unparse(stub_node)}")
    if isinstance(stub_value, float) and isinstance(runtime_value, float):
        assert math.isclose(stub_value, runtime_value, rel_tol=1e-12), \
            (where, stub_value, runtime_value)
    else:
        assert stub_value == runtime_value, (where, stub_value, runtime_value)


# Return types: the runtime's (pybind11's names) and the stub's reduced to one family each.
RUNTIME_FAMILY = [(r"^None$", "None"), (r"^dict", "dict"), (r"^list", "list"),
                  (r"^tuple", "tuple"), (r"^numpy\.ndarray", "array"), (r"^str$", "str"),
                  (r"^float$", "float"), (r"^int$", "int"), (r"^bool$", "bool"),
                  (r"^bytes$", "bytes"), (r"^pinmask\.(\w+)$", r"\1")]
# pinmask.Result is a dict subclass (python/result.cpp): the bindings' signatures say dict.
STUB_FAMILY = [(r"^None$", "None"), (r"^(dict|Result$)", "dict"), (r"^list", "list"),
               (r"^tuple", "tuple"),
               (r"^(FloatArray|npt\.NDArray)", "array"), (r"^str$", "str"),
               (r"^float$", "float"), (r"^int$", "int"), (r"^bool$", "bool"),
               (r"^bytes$", "bytes"), (r"^(\w+)$", r"\1")]


def family(text, table):
    for pattern, repl in table:
        if re.match(pattern, text):
            return re.sub(pattern + ".*", repl, text)
    return None


def stub_functions():
    """(qualified name, runtime object, its name, stub FunctionDef) for every function and method."""
    import pathlib
    tree = ast.parse((pathlib.Path(__file__).resolve().parents[2] / STUB_PATH).read_text())
    out = []
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out.append((node.name, getattr(pinmask, node.name), node.name, node, False))
        elif isinstance(node, ast.ClassDef) and node.name != "Result":
            # Result is a Python class (python/result.cpp), tested in test_result.py; its
            # methods carry no pybind11 signature.
            cls = getattr(pinmask, node.name)
            for b in node.body:
                if isinstance(b, ast.FunctionDef) and not any(
                        isinstance(d, ast.Name) and d.id == "property" for d in b.decorator_list):
                    out.append((f"{node.name}.{b.name}", getattr(cls, b.name), b.name, b, True))
    return out


FUNCTIONS = stub_functions()


@pytest.mark.parametrize("qualified,obj,name,node,method", FUNCTIONS,
                         ids=[f[0] for f in FUNCTIONS])
def test_stub_signature_equals_runtime(qualified, obj, name, node, method):
    params, returns = runtime_signature(obj, name)
    if method:
        assert params[0][0] == "self", qualified
        params = params[1:]
    stub_args = node.args.args[1:] if method else node.args.args
    has_kwargs = bool(params) and params[-1][0].startswith("**")
    assert (node.args.kwarg is not None) == has_kwargs, f"{qualified}: **kwargs in one only"
    if has_kwargs:
        params = params[:-1]
    if ("*", None) in params:  # keyword-only: the stub's kwonlyargs, in order
        star = params.index(("*", None))
        params, kwonly = params[:star], params[star + 1:]
        assert [a.arg for a in node.args.kwonlyargs] == [p[0] for p in kwonly], qualified
        for arg, d, (pname, runtime_default) in zip(node.args.kwonlyargs, node.args.kw_defaults,
                                                    kwonly):
            assert (d is None) == (runtime_default is None), f"{qualified}({pname})"
            if d is not None:
                same_default(d, runtime_default, f"{qualified}({pname})")
    else:
        assert not node.args.kwonlyargs, f"{qualified}: keyword-only in the stub only"
    assert [a.arg for a in stub_args] == [p[0] for p in params], qualified
    defaults = node.args.defaults
    stub_defaults = [None] * (len(stub_args) - len(defaults)) + list(defaults)
    for arg, d, (pname, runtime_default) in zip(stub_args, stub_defaults, params):
        where = f"{qualified}({pname})"
        assert (d is None) == (runtime_default is None), \
            f"{where}: default in the stub {d and ast.unparse(d)}, at run time {runtime_default}"
        if d is not None:
            same_default(d, runtime_default, where)
    stub_return = family(ast.unparse(node.returns), STUB_FAMILY)
    runtime_return = family(returns, RUNTIME_FAMILY)
    if runtime_return is not None and returns != "object":
        assert stub_return == runtime_return, (qualified, ast.unparse(node.returns), returns)


def test_every_public_function_is_checked():
    checked = {f[0] for f in FUNCTIONS if "." not in f[0]}
    functions = {n for n in dir(pinmask)
                 if not n.startswith("_") and callable(getattr(pinmask, n))
                 and not isinstance(getattr(pinmask, n), type)}
    assert functions - checked == set()
    assert len(FUNCTIONS) > 40

