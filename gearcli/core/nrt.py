"""Decorator for the hot inner functions of the kernel: :data:`gearcli.core.jit.jit` without
numba's reference counting.

Every compiled function that receives arrays increments and decrements their reference counts
on entry and exit (atomic operations of numba's runtime, NRT). The right-hand side is called
a few hundred thousand times per run with a dozen arrays, and on the target machines these
atomics took about 60 % of the run time (perf). Functions that never allocate arrays, never
return arrays and never keep a view beyond the call do not need the counts, so they are
compiled with ``_nrt=False``, the option numba itself uses for its allocation-free helpers
(numba/core/extending.py, numba/cpython/unicode.py). Such a function cannot call np.empty /
np.zeros (compilation fails loudly), which is exactly the contract of these helpers.

Everything else about the options (cache, fastmath, error model) comes from ``jit.py``.
"""

from gearcli.core.jit import jit

#: ``@jit_noalloc`` on functions that take arrays but never allocate or return them.
jit_noalloc = jit(_nrt=False)

#: The same, inlined into every caller at numba-IR level. For the right-hand side and its
#: pieces: a call that passes a dozen arrays (7-11 machine words each) costs about as much as
#: the physics inside, and LLVM does not inline functions that large by itself. Use it only for
#: functions with few call sites (timeloop.run evaluates the right-hand side at one place):
#: each inlined copy adds compile time.
jit_noalloc_inline = jit(_nrt=False, inline="always")
