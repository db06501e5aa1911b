"""Orchestration of the commands: case -> model -> (core) -> results."""
