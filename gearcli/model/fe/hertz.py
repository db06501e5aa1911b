"""Hertz line contact and Weber's local approach: the contact part of the FE tooth compliance.

The FE model reads its global displacement at a depth h below the contact and adds Weber's
flattening δ(h) between the surface and h (docs/theory.md, "The contact split"). The formulas
(Johnson 1985 eqs 4.43–4.49; Weber 1949; Weber & Banaschek 1953) live in
:mod:`gearcli.model.contact_compliance`, shared with the tooth law of §4b, which takes the same
δ to the tooth centreline.
"""

from __future__ import annotations

from gearcli.model.contact_compliance import contact_modulus, hertz_half_width, weber_approach

__all__ = ["contact_modulus", "hertz_half_width", "weber_approach"]
