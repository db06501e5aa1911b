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
the IR being copied (its blocks share one scope). Everything else is copied exactly as numba
copies it, and inline_ir only reads the callee's scope before it points every inlined block at
the caller's scope, so the inlined IR, and the machine code, are the same.

:func:`apply` installs it only when numba's inliner still has that shape (a nested ``copy_ir``
that calls ``deepcopy`` through the module's ``copy``); otherwise numba is left alone, which
costs compile time only. numba internals are touched nowhere else. :func:`apply_when_compiling`
defers it to numba's first compilation in the process (its ``numba:compile`` event, which a
cache hit never raises): importing the inliner costs ~50 ms that a run from the cache would
otherwise pay before numba needs it.
"""

from __future__ import annotations

import contextvars
import copy
import types

#: Scope copies of the inline_ir call in progress: id(original scope) -> (scope, its copy);
#: None outside inline_ir (then deepcopy behaves exactly as copy.deepcopy).
_SCOPES: contextvars.ContextVar[dict | None] = contextvars.ContextVar("scopes", default=None)


def _deepcopy(obj, memo=None):
    """``copy.deepcopy`` for numba's inliner: an ``ir.Block`` copied inside ``inline_ir``
    reuses the one copy of its scope made for this call."""
    from numba.core import ir

    scopes = _SCOPES.get()
    if memo is None and scopes is not None and isinstance(obj, ir.Block):
        key = id(obj.scope)
        if key not in scopes:  # the scope object is kept alive by the tuple (no id reuse)
            scopes[key] = (obj.scope, copy.deepcopy(obj.scope))
        memo = {key: scopes[key][1]}
    return copy.deepcopy(obj, memo)


def _inliner_has_known_shape(module) -> bool:
    worker = getattr(module, "InlineWorker", None)
    inline_ir = getattr(worker, "inline_ir", None)
    if inline_ir is None or getattr(module, "copy", None) is not copy:
        return False
    nested = [c for c in inline_ir.__code__.co_consts if isinstance(c, types.CodeType)]
    return any(c.co_name == "copy_ir" and "deepcopy" in c.co_names for c in nested)


def apply() -> bool:
    """Install the fix into numba's inliner; True when it is (or already was) installed."""
    from numba.core import inline_closurecall as module

    if getattr(module.InlineWorker.inline_ir, "_gearcli_shared_scope", False):
        return True
    if not _inliner_has_known_shape(module):
        return False
    original = module.InlineWorker.inline_ir

    def inline_ir(self, *args, **kwargs):
        token = _SCOPES.set({})
        try:
            return original(self, *args, **kwargs)
        finally:
            _SCOPES.reset(token)

    inline_ir._gearcli_shared_scope = True
    inline_ir.__doc__ = original.__doc__
    module.copy = types.SimpleNamespace(deepcopy=_deepcopy, copy=copy.copy)
    module.InlineWorker.inline_ir = inline_ir
    return True


def apply_when_compiling() -> None:
    """Install the fix at the start of the process's first numba compilation (not before:
    a run whose compiled code all comes from the cache never imports the inliner for it)."""
    from numba.core import event

    class _OnCompile(event.Listener):
        def on_start(self, ev):
            apply()  # idempotent; cheap once installed

        def on_end(self, ev):
            pass

    event.register("numba:compile", _OnCompile())
