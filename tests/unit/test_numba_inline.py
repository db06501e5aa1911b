"""The compile-time fix of numba's IR inliner (gearcli/numba_inline.py): the copied blocks of
one IR share one copy of its scope, everything else is copied as numba copies it, and inlined
functions compute what the Python source computes."""

import copy
import re
import types
import warnings

import numba
import pytest
from numba.core import compiler, inline_closurecall, ir
from numba.extending import overload

from gearcli import numba_inline


def _installed():
    """The fix is installed unless numba's inliner changed shape (then numba is left alone)."""
    if not numba_inline.apply():
        pytest.skip("numba's IR inliner changed shape: the fix is not installed "
                    "(gearcli/numba_inline.py)")


def _callee(x, n):
    total = 0.0
    for i in range(n):
        if i % 3 == 0:
            total += x * i
        elif i % 3 == 1:
            total -= x
        else:
            total += 1.0
    return total


def _copy_blocks(func_ir):
    """What numba's copy_ir does with the blocks: one deepcopy per block, no shared memo."""
    return {label: inline_closurecall.copy.deepcopy(block)
            for label, block in func_ir.blocks.items()}


def test_blocks_of_one_copy_share_one_scope_copy():
    _installed()
    func_ir = compiler.run_frontend(_callee)
    scopes = {id(b.scope) for b in func_ir.blocks.values()}
    assert len(func_ir.blocks) > 3 and len(scopes) == 1  # the IR being copied: one scope

    token = numba_inline._SCOPES.set({})
    try:
        first = _copy_blocks(func_ir)
        second = _copy_blocks(func_ir)  # a second copy of the same IR in the same call
        of_copy = _copy_blocks(types.SimpleNamespace(blocks=first))  # numba's second copy
    finally:
        numba_inline._SCOPES.reset(token)
    original_scope = next(iter(func_ir.blocks.values())).scope
    copied = {id(b.scope) for b in first.values()}
    assert len(copied) == 1 and id(original_scope) not in copied
    scope = next(iter(first.values())).scope
    assert sorted(scope.localvars._con) == sorted(original_scope.localvars._con)
    assert scope.localvars is not original_scope.localvars  # a deep copy, not a shallow one
    assert scope.localvars._con["x"] is not original_scope.localvars._con["x"]
    # every copy of an IR has a scope of its own, shared by its blocks only
    for other in (second, of_copy):
        ids = {id(b.scope) for b in other.values()}
        assert len(ids) == 1 and not ids & copied and id(original_scope) not in ids
    # renaming in one copy's scope (what inline_ir does) leaves the original and the others
    scope.redefine("renamed_by_the_inliner", loc=scope.loc)
    for untouched in (original_scope, next(iter(second.values())).scope):
        assert "renamed_by_the_inliner" not in untouched.localvars._con
    # the statements themselves are fresh copies, equal to the original ones
    for label, block in func_ir.blocks.items():
        assert first[label] is not block
        assert [str(s) for s in first[label].body] == [str(s) for s in block.body]
        assert all(a is not b for a, b in zip(first[label].body, block.body, strict=True))

    # outside inline_ir the module's deepcopy is copy.deepcopy: a scope copy per block
    plain = _copy_blocks(func_ir)
    assert len({id(b.scope) for b in plain.values()}) == len(plain)


def test_plain_deepcopy_outside_the_inliner_is_untouched():
    block = next(iter(compiler.run_frontend(_callee).blocks.values()))
    memo = {}
    assert isinstance(numba_inline._deepcopy(block, memo), ir.Block)
    assert id(block) in memo  # the caller's memo is used as given
    assert numba_inline._deepcopy([1, [2]]) == copy.deepcopy([1, [2]])


def _nested(inner):
    """``outer`` calls ``middle`` at two sites, ``middle`` calls ``inner`` at two (all three
    IR-inlined into ``outer``); returns ``(outer, middle)``."""

    @numba.njit(inline="always")
    def middle(x, n):
        return inner(x, n) + inner(2.0 * x, n + 1)

    @numba.njit
    def outer(x, n):
        return middle(x, n) + middle(-x, n)

    return outer, middle


def _nested_python(x, n):
    return (_callee(x, n) + _callee(2.0 * x, n + 1)) + (_callee(-x, n) + _callee(-2.0 * x, n + 1))


@pytest.mark.parametrize("x, n", [(0.5, 0), (1.25, 7), (-2.0, 31)])
def test_nested_inlined_functions_compute_the_python_result(x, n):
    _installed()
    outer, _ = _nested(numba.njit(inline="always")(_callee))
    assert outer(x, n) == _nested_python(x, n)  # the same operations in the same order: exact


def test_installed_by_the_first_compilation_not_by_the_import():
    """A run from the cache never pays for the inliner's import; the first compile installs
    the fix before anything is inlined (numba's 'numba:compile' event)."""
    import subprocess
    import sys

    code = ("import sys, gearcli.core.jit, numba\n"
            "print('numba.core.inline_closurecall' in sys.modules and getattr("
            "sys.modules['numba.core.inline_closurecall'].InlineWorker.inline_ir, "
            "'_gearcli_shared_scope', False))\n"
            "numba.njit(lambda x: x + 1)(1)\n"
            "from numba.core import inline_closurecall as m\n"
            "from gearcli import numba_inline\n"
            "print(getattr(m.InlineWorker.inline_ir, '_gearcli_shared_scope', False) or "
            "not numba_inline._inliner_has_known_shape(m))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.split() == ["False", "True"], out.stderr[-500:]


def _typed_target(x):
    return x


@overload(_typed_target, inline="always")  # numba's typed inlining (update_type_and_call_maps)
def _typed_target_impl(x):
    def impl(x):
        y = 0.0
        for i in range(3):
            y += x * i
        return y
    return impl


def _canonical_names(text: str) -> str:
    """Every local name of each function of the module (values ``%name`` and block labels)
    replaced by its rank of first appearance in that function: two IRs that differ only in
    how their values are named compare equal, and a different use of a value (another
    operand, another branch target) still differs. numba and LLVM name values after
    process-wide counters (numba's inlined-variable versions, LLVM's uniquifying suffixes), so
    the names of one compilation depend on what the process compiled before."""
    parts = []
    for function in re.split(r"(?=^define )", text, flags=re.M):
        names: dict[str, str] = {}

        def rank(m, names=names):
            if m.group(1) is not None:
                return "%" + names.setdefault(m.group(1), f"n{len(names)}")
            return names.setdefault(m.group(2), f"n{len(names)}") + ":"

        parts.append(re.sub(r"%([-\w.$]+)|^([-\w.$]+):", rank, function, flags=re.M))
    return "".join(parts)


def _compiled_llvm() -> str:
    """LLVM IR of a fresh chain of IR-inlined and typed-inlined functions, with the local
    names canonical (:func:`_canonical_names`) and the global names, string lengths and the
    padding before comments, which differ between two compilations, normalised."""
    inner = numba.njit(inline="always")(_callee)

    @numba.njit(inline="always")
    def middle(x, n):
        return inner(x, n) + _typed_target(x)

    @numba.njit
    def outer(x, n):
        return middle(x, n) + middle(2.0 * x, n)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # numba's own pedantic SSA note on overload inlining
        outer(1.0, 3)
    text = _canonical_names(next(iter(outer.inspect_llvm().values())))
    for pattern, repl in ((r"_ZN[\w$.]+", "F"), (r"\b(outer|middle|inner)\b", "F"),
                          (r"\[\d+ x i8\]", "[n x i8]"),
                          (r"(source_filename|; ModuleID) = .*", ""), (r" +", " ")):
        text = re.sub(pattern, repl, text)
    return text


def test_canonical_names_keep_what_uses_what():
    a = "define f() {\nB1:\n  %x.1 = add i64 %a, 1\n  br label %B1\n}\n"
    renamed = "define f() {\nB7:\n  %x.9 = add i64 %a, 1\n  br label %B7\n}\n"
    other_use = "define f() {\nB7:\n  %x.9 = add i64 %x.9, 1\n  br label %B7\n}\n"
    assert _canonical_names(a) == _canonical_names(renamed)
    assert _canonical_names(a) != _canonical_names(other_use)


def test_the_same_machine_code_with_and_without_the_fix():
    """Both fixes (the shared scope copy, the untyped IR kept for the process): the same LLVM
    IR up to names, also when other compilations ran before in the process (they move
    numba's and LLVM's naming counters; bench/RESULTS.md session 11)."""
    _installed()
    try:
        numba_inline.remove()
        assert not getattr(inline_closurecall.InlineWorker.inline_ir, "_gearcli_shared_scope",
                           False)
        without = _compiled_llvm()
    finally:
        assert numba_inline.apply()
    assert getattr(inline_closurecall.InlineWorker.inline_function, "_gearcli_untyped_cache",
                   False) or not numba_inline._inline_function_has_known_shape(
                       inline_closurecall)
    first = _compiled_llvm()  # analyses _callee and keeps its IR
    assert first == without
    assert _compiled_llvm() == without  # every site given the kept IR


def test_each_inlined_function_is_analysed_once():
    """The untyped passes of a function inlined at several sites (and inside a function
    inlined at several sites) run once; numba runs them at every site."""
    _installed()
    if not getattr(inline_closurecall.InlineWorker.inline_function, "_gearcli_untyped_cache",
                   False):
        pytest.skip("numba's inline_function changed shape: no untyped-IR cache")
    # a function object of its own: the cache of this process may hold _callee already
    fresh = types.FunctionType(_callee.__code__, _callee.__globals__, "fresh")
    outer, middle = _nested(numba.njit(inline="always")(fresh))

    analysed = []
    original = inline_closurecall.InlineWorker.run_untyped_passes

    def counting(self, func, enable_ssa=False):
        analysed.append(func)
        return original(self, func, enable_ssa)

    inline_closurecall.InlineWorker.run_untyped_passes = counting
    try:
        got = outer(0.75, 5)
    finally:
        inline_closurecall.InlineWorker.run_untyped_passes = original
    assert analysed.count(fresh) == 1 and analysed.count(middle.py_func) == 1
    assert got == _nested_python(0.75, 5)
