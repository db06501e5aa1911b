"""File output: atomic writes, never silently overwriting results."""
