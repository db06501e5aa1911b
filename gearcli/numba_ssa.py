"""Compile-time fix for numba's SSA reconstruction: each variable's rewrite visits only the
blocks that name it.

numba rebuilds static single assignment after the IR inliner (``numba.core.ssa._run_ssa``,
Choi et al.'s algorithm). For every variable assigned more than once it makes two rewrite
passes (``_fresh_vars``: a new name per assignment; ``_fix_ssa_vars``: each use to its reaching
definition, with phi nodes where definitions meet), and each pass walks every statement of
every block of the function, so the work grows as (variables assigned more than once) x
(statements). ``timeloop.run`` with the right-hand side and its pieces inlined has ~190 such
variables in ~425 blocks (~4 900 statements): ~1.5 s of its first compilation, the largest
share after type inference and lowering (bench/RESULTS.md, session 13).

A block that neither defines nor uses the variable is left as it was by both passes: every
statement goes through the handler unchanged (``_FreshVarHandler`` renames only assignments to
the variable; ``_FixSSAVars`` returns a statement unchanged unless the variable is among its
variables). Phi nodes for the variable are placed through the handler's state, by walking the
control-flow graph from the blocks that use it, not by visiting the other blocks. So the fix
indexes, once per function, the blocks in which each variable name occurs and hands numba's own
``_run_block_rewrite`` only those blocks, in numba's order; every other block is carried over as
a new block with the same statements (as numba's rewrite makes it). The renaming of one variable
adds names of that variable only, so the index stays right for the others, provided every
name in the blocks is in the scope numba renames in (a new name is new to the scope, and could
otherwise be one the IR already uses, e.g. ``x.1`` left outside the scope by numba's inliner);
a function with a name outside its scope is left to numba's walk of every block. The IR that
comes out is numba's, name for name (tests/unit/test_numba_ssa.py compares the two on the
kernel's own functions, on adversarial shapes, and on every SSA step of a compilation).

:func:`apply` installs it only when numba's SSA module has that shape (``_run_ssa`` calling
``_fresh_vars`` and ``_fix_ssa_vars`` through the module's ``_run_block_rewrite(blocks, states,
handler)``, with the variable in ``states["varname"]``); otherwise numba is left alone, which
costs compile time only. It is installed with the inliner's fix (gearcli/numba_inline.py), at
the process's first compilation; the environment variable ``GEARCLI_NUMBA_PATCHES=0`` (read
when :mod:`gearcli.core` is first imported; numba_inline.patches_enabled) installs neither,
leaving numba untouched, with the same results and a slower first compilation.
"""

from __future__ import annotations

import contextvars
import functools

#: Blocks (labels) in which each variable name occurs, for the _run_ssa call in progress;
#: None outside it (then numba's rewrite walks every block).
_MENTIONS: contextvars.ContextVar[dict | None] = contextvars.ContextVar("mentions", default=None)


def _index(blocks) -> dict:
    """Variable name -> the set of labels of the blocks whose statements name it."""
    mentions: dict = {}
    for label, block in blocks.items():
        for stmt in block.body:
            for var in stmt.list_vars():
                mentions.setdefault(var.name, set()).add(label)
    return mentions


def _index_if_scoped(blocks) -> dict | None:
    """The index of :func:`_index`, or None (numba's own rewrite of every block) when a name
    in the blocks is not in the scope numba renames in (the first block's). Renaming a variable
    ``x`` makes names ``x.1``, ``x.2``, ... that are new to the scope, and a name the IR uses
    but the scope lacks can be one of them (numba's inliner leaves such names, its
    NumbaIRAssumptionWarning): then later variables' blocks are no longer those indexed,
    and only numba's walk of every block gives numba's output."""
    if not blocks:
        return None
    mentions = _index(blocks)
    scope = next(iter(blocks.values())).scope
    if all(name in scope.localvars for name in mentions):
        return mentions
    return None


def _has_known_shape(module) -> bool:
    code_names = (module._run_ssa.__code__.co_names + module._fresh_vars.__code__.co_names
                  + module._fix_ssa_vars.__code__.co_names)
    return (all(hasattr(module, name) for name in ("_run_ssa", "_fresh_vars", "_fix_ssa_vars",
                                                   "_run_block_rewrite", "reconstruct_ssa"))
            and "_run_block_rewrite" in code_names
            and module._run_block_rewrite.__code__.co_varnames[:3]
            == ("blocks", "states", "handler"))


def apply() -> bool:
    """Install the fix into numba's SSA module; True when it is (or already was) installed,
    False when the module has another shape (or anything about it is unexpected)."""
    try:
        from numba.core import ir
        from numba.core import ssa as module

        if getattr(module._run_ssa, "_gearcli_indexed", False):
            return True
        if not _has_known_shape(module):
            return False
        run_ssa = module._run_ssa
        rewrite = module._run_block_rewrite
    except Exception:  # noqa: BLE001  (a numba we do not know: leave it alone)
        return False

    @functools.wraps(run_ssa)
    def indexed_run_ssa(blocks):
        token = _MENTIONS.set(_index_if_scoped(blocks))
        try:
            return run_ssa(blocks)
        finally:
            _MENTIONS.reset(token)

    @functools.wraps(rewrite)
    def indexed_rewrite(blocks, states, handler):
        mentions = _MENTIONS.get()
        varname = states.get("varname")
        if mentions is None or varname is None:
            return rewrite(blocks, states, handler)
        named = mentions.get(varname, ())
        done = rewrite({label: block for label, block in blocks.items() if label in named},
                       states, handler)
        out = {}
        for label, block in blocks.items():
            if label in done:
                out[label] = done[label]
            else:  # unchanged statements in a new block, as numba's rewrite makes it
                out[label] = carried = ir.Block(scope=block.scope, loc=block.loc)
                carried.body = list(block.body)
        return out

    indexed_run_ssa._gearcli_indexed = True
    module._run_ssa = indexed_run_ssa
    module._run_block_rewrite = indexed_rewrite
    return True


def remove() -> None:
    """Undo :func:`apply` (tests compare numba's IR with and without the fix)."""
    from numba.core import ssa as module

    if getattr(module._run_ssa, "_gearcli_indexed", False):
        module._run_ssa = module._run_ssa.__wrapped__
        module._run_block_rewrite = module._run_block_rewrite.__wrapped__
