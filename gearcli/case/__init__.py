"""Case files: YAML (with line numbers) -> validated, typed, unit-converted objects.

Public entry point: :func:`gearcli.case.load.load_case`.
"""
