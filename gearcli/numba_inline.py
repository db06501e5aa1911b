"""Compile-time fix for numba's IR inliner: one copy of a callee's scope per copied IR.

The kernel inlines the right-hand side and its pieces at numba-IR level (``inline="always"``,
:mod:`gearcli.core.nrt`). To inline, ``numba.core.inline_closurecall.InlineWorker.inline_ir``
copies the callee's IR twice with a nested ``copy_ir`` that deep-copies it block by block, each
block with its own ``copy.deepcopy`` memo. Every block refers to the function's one
``ir.Scope``, which holds every variable of the function with its location, so each block copy
copies the whole scope again: the work grows as blocks x variables, and the inlined right-hand
side has hundreds of blocks and thousands of variables (numba issue #8989, "Spurious deep copies
in inlining", open). Measured on the seed case with an empty cache: 49 % of the profiled compile
time was in ``copy.deepcopy``; the solver's first compilation took 34.8 s and 1.30 GB peak
memory before this fix, 21 s and 0.54 GB after (bench/RESULTS.md, session 7).

The fix gives the blocks of one copy one shared copy of their scope, which is the structure of
the IR being copied (its blocks share one scope); each copy of an IR gets its own. Everything
else is copied exactly as numba copies it. inline_ir reads the callee's variables from the
first block's scope, renames them there (and its SSA step adds versions), then points every
inlined block at the caller's scope: with numba's per-block copies only the first block's copy
saw those changes, with the fix the one shared copy does, and the inlined IR is the same.
tests/unit/test_numba_inline.py compares the LLVM IR of IR-inlined and typed-inlined functions
compiled with and without the fix.

:func:`apply` installs it only when numba's inliner still has that shape (a nested ``copy_ir``
that calls ``deepcopy`` through the module's ``copy``); otherwise numba is left alone, which
costs compile time only. numba internals are touched nowhere else.

A second fix, of the same kind: ``InlineWorker.inline_function`` runs the callee's untyped
passes (bytecode to canonical IR, with the inlining of its own callees) at every call site,
so a function inlined at k sites, or inside a function inlined at k sites (the right-hand side
evaluates ``flank`` for both flank families; ``flank`` inlines its pieces and the contact
laws), is analysed k times. :func:`apply` keeps the IR of each (function, compile flags but
``enable_ssa``, which run_untyped_passes sets itself) for the process and gives every later
site the kept IR; ``inline_ir`` deep-copies the callee's IR before it changes anything
(numba's comment there: "Always copy the callee IR, it gets mutated"), so the kept IR is
never changed and each site gets the IR it would have made, up to the names of its
variables and blocks (numba's process-wide counters). Measured (bench/RESULTS.md, session 11):
the seed's first compilation ~4 % less CPU time, the kernel's results bit for bit the same
(bench/identity.py) and its run time the same within the A/B spread.
tests/unit/test_numba_inline.py checks that each inlined function is analysed once, computes
what the Python source computes, and that the LLVM IR with and without both fixes is the same
up to local names.

:func:`apply_when_compiling`
defers it to numba's first compilation in the process (its ``numba:compile`` event, which a
cache hit never raises): importing the inliner costs ~50 ms that a run from the cache would
otherwise pay before numba needs it.

Opt-out: with the environment variable ``GEARCLI_NUMBA_PATCHES=0`` (also ``false``, ``no``,
``off``) when :mod:`gearcli.core` is first imported, :func:`apply_when_compiling` installs
nothing, neither this fix nor the SSA fix of gearcli/numba_ssa.py, and registers no listener:
numba is left exactly as it is. The compiled code computes the same results (the fixes change
how numba builds its IR, not what it means); only the first compilation is slower (the
figures above). tests/unit/test_numba_patches_opt_out.py compiles a kernel function with and
without the variable. :func:`apply` called explicitly still installs the fix.
"""

from __future__ import annotations

import contextvars
import copy
import functools
import os
import re
import types

#: Environment variable that turns both compile-time fixes off (``0``, ``false``, ``no``,
#: ``off``): :func:`apply_when_compiling` then leaves numba untouched.
OPT_OUT_VARIABLE = "GEARCLI_NUMBA_PATCHES"

#: Scope copies of the inline_ir call in progress: id(original scope) -> [scope, its copy,
#: ids of the blocks copied with it]; None outside inline_ir (then deepcopy is copy.deepcopy).
_SCOPES: contextvars.ContextVar[dict | None] = contextvars.ContextVar("scopes", default=None)


def _deepcopy(obj, memo=None):
    """``copy.deepcopy`` for numba's inliner: an ``ir.Block`` copied inside ``inline_ir``
    shares one copy of its scope with the other blocks of the same copy of the IR.

    A block copied a second time in the same call starts a second copy of the IR, which gets a
    scope copy of its own (numba copies the callee twice per call: one copy to mutate, one kept
    unmutated; they must not share a scope)."""
    from numba.core import ir

    scopes = _SCOPES.get()
    if memo is None and scopes is not None and isinstance(obj, ir.Block):
        key = id(obj.scope)
        entry = scopes.get(key)
        if entry is None or id(obj) in entry[2]:  # the scope is kept alive here: no id reuse
            entry = scopes[key] = [obj.scope, copy.deepcopy(obj.scope), set()]
        entry[2].add(id(obj))
        memo = {key: entry[1]}
    return copy.deepcopy(obj, memo)


class _CopyModule:
    """Stands in for the ``copy`` module inside numba's inliner: its ``deepcopy`` is
    :func:`_deepcopy`, every other name is the ``copy`` module's."""

    deepcopy = staticmethod(_deepcopy)

    def __getattr__(self, name):
        return getattr(copy, name)


def _inliner_has_known_shape(module) -> bool:
    worker = getattr(module, "InlineWorker", None)
    inline_ir = getattr(worker, "inline_ir", None)
    code = getattr(inline_ir, "__code__", None)
    if code is None or getattr(module, "copy", None) is not copy:
        return False
    nested = [c for c in code.co_consts if isinstance(c, types.CodeType)]
    return any(c.co_name == "copy_ir" and "deepcopy" in c.co_names for c in nested)


#: Untyped IR of the functions inlined so far: (function, flags without enable_ssa, the
#: caller's ``locals`` types) -> IR.
_UNTYPED: dict = {}


def _flags_key(flags) -> str:
    return re.sub(r"enable_ssa=\w+,? ?", "", repr(flags))


def _inline_function_has_known_shape(module) -> bool:
    """numba's inline_function still runs the untyped passes, then inline_ir, nothing else."""
    code = getattr(getattr(module.InlineWorker, "inline_function", None), "__code__", None)
    return code is not None and set(code.co_names) == {
        "run_untyped_passes", "__code__", "co_freevars", "inline_ir"}


def _install_untyped_cache(module) -> None:
    if getattr(module.InlineWorker.inline_function, "_gearcli_untyped_cache", False) \
            or not _inline_function_has_known_shape(module):
        return
    original = module.InlineWorker.inline_function

    @functools.wraps(original)
    def inline_function(self, caller_ir, block, i, function, arg_typs=None):
        key = (function, _flags_key(self.flags), repr(sorted(self.locals.items())))
        callee_ir = _UNTYPED.get(key)
        if callee_ir is None:
            callee_ir = _UNTYPED[key] = self.run_untyped_passes(function)
        return self.inline_ir(caller_ir, block, i, callee_ir, function.__code__.co_freevars,
                              arg_typs=arg_typs)

    inline_function._gearcli_untyped_cache = True
    module.InlineWorker.inline_function = inline_function


def apply() -> bool:
    """Install the fix into numba's inliner; True when it is (or already was) installed,
    False when numba's inliner has another shape (or anything about it is unexpected)."""
    try:
        from numba.core import inline_closurecall as module

        if getattr(module.InlineWorker.inline_ir, "_gearcli_shared_scope", False):
            return True
        if not _inliner_has_known_shape(module):
            return False
        original = module.InlineWorker.inline_ir
        _install_untyped_cache(module)
    except Exception:  # noqa: BLE001  (a numba we do not know: leave it alone)
        return False

    @functools.wraps(original)
    def inline_ir(self, *args, **kwargs):
        token = _SCOPES.set({})
        try:
            return original(self, *args, **kwargs)
        finally:
            _SCOPES.reset(token)

    inline_ir._gearcli_shared_scope = True
    module.copy = _CopyModule()
    module.InlineWorker.inline_ir = inline_ir
    return True


def remove() -> None:
    """Undo :func:`apply` (tests compare numba's code with and without the fix)."""
    from numba.core import inline_closurecall as module

    wrapped = module.InlineWorker.inline_ir
    if getattr(wrapped, "_gearcli_shared_scope", False):
        module.InlineWorker.inline_ir = wrapped.__wrapped__
        module.copy = copy
    cached = module.InlineWorker.inline_function
    if getattr(cached, "_gearcli_untyped_cache", False):
        module.InlineWorker.inline_function = cached.__wrapped__
    _UNTYPED.clear()


def patches_enabled() -> bool:
    """False when the environment opts out of both fixes (``GEARCLI_NUMBA_PATCHES=0``, or
    ``false``, ``no``, ``off``, any case); True otherwise, also when the variable is unset."""
    value = os.environ.get(OPT_OUT_VARIABLE, "1").strip().lower()
    return value not in ("0", "false", "no", "off")


def apply_when_compiling() -> None:
    """Install the fix, and the SSA fix of gearcli/numba_ssa.py, at the start of the process's
    first numba compilation (not before: a run whose compiled code all comes from the cache
    never imports the inliner for it). Nothing at all, not even the listener, when the
    environment opts out (:func:`patches_enabled`, ``GEARCLI_NUMBA_PATCHES=0``)."""
    if not patches_enabled():
        return
    from numba.core import event

    from gearcli import numba_ssa

    class _OnCompile(event.Listener):
        def on_start(self, ev):
            apply()  # idempotent; cheap once installed
            numba_ssa.apply()  # numba's SSA rewrite, per variable only where it occurs

        def on_end(self, ev):
            pass

    event.register("numba:compile", _OnCompile())
