"""`gearcli sweep`: parametric studies. ``study`` reads and expands a study file, ``run`` runs
its points (in parallel, resumable) into summary.csv, ``metrics`` measures one point, ``trends``
ranks the parameters' effects (trends.csv/.md and the figures)."""
