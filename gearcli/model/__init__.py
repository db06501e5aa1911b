"""Gear model: involute geometry, tooth profiles, mass and stiffness parameters (pure functions)."""
