"""numba options, set once for every kernel of :mod:`gearcli.core`.

``cache=True`` writes compiled code to ``NUMBA_CACHE_DIR``, which :mod:`gearcli.numba_cache`
points (before numba is imported, here, whoever imports the core first) to a user folder keyed
by a hash of the core's sources: it survives read-only site-packages and never serves code
compiled from older sources (numba issue #6845).
"""

import functools

# the two non-core imports: numba's configuration, no physics
from gearcli.numba_cache import configure
from gearcli.numba_inline import apply_when_compiling as fix_inliner

configure()

import numba  # noqa: E402  (after the cache folder is set)

fix_inliner()  # the IR inliner's copies, linear, not quadratic (gearcli/numba_inline.py)

#: Decorator for every compiled function of the core.
jit = functools.partial(numba.njit, cache=True, fastmath=False, nogil=True, error_model="numpy")
