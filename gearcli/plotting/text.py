"""User-supplied names in figures as plain text.

Matplotlib reads text between two ``$`` as mathtext, so a case named ``$\\frac{1$`` fails the
figure (after all the computation) and ``$x$`` is drawn as math. :func:`plain` escapes every
``$`` (``\\$`` is a literal dollar sign in matplotlib text); a name with characters that are not
valid Unicode text (lone surrogates from undecodable bytes) gets them replaced.
"""

from __future__ import annotations


def plain(text) -> str:
    """``text`` as matplotlib draws it literally: no mathtext, valid Unicode."""
    s = str(text)
    s = s.encode("utf-8", "replace").decode("utf-8")  # lone surrogates (undecodable bytes)
    return s.replace("$", r"\$")
