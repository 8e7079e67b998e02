"""Baselines of the registered NetCatch ids: Stable-Baselines3 and sb3-contrib algorithms trained
at a fixed budget of environment steps per id, several seeds each, evaluated on the same held-out
episodes, aggregated with interquartile means and stratified bootstrap intervals.

- :mod:`~agents.baselines.grid`: the algorithm x id x seed grid and the budgets;
- :mod:`~agents.baselines.runs`: one run, trained and evaluated, as a JSON-ready record;
- :mod:`~agents.baselines.runner`: the runs not yet done, in parallel processes or as Ray tasks;
- :mod:`~agents.baselines.stats`: IQM, bootstrap intervals, normalisation, performance profiles;
- :mod:`~agents.baselines.cells`: the result files as (algorithm, id) cells: learners, tasks, ranking,
  common task sets, captures by throw;
- :mod:`~agents.baselines.analysis`: the rliable statistics over the cells, stored as ``stats.json``;
- :mod:`~agents.baselines.tables`: every markdown table of the report and the docs, with its caption;
- :mod:`~agents.baselines.figures`: the learning curves and performance profiles;
- :mod:`~agents.baselines.report`: ``report.md``, ``stats.json`` and the figures from the result files.

``python scripts/baselines.py --out runs/baselines`` runs it all.
"""
