"""numba options, set once for every kernel of :mod:`gearcli.core`.

``cache=True`` writes compiled code next to the sources or, when site-packages is read-only,
to ``NUMBA_CACHE_DIR`` (the CLI points that to a user cache folder).
"""

import functools

import numba

#: Decorator for every compiled function of the core.
jit = functools.partial(numba.njit, cache=True, fastmath=False, nogil=True, error_model="numpy")
