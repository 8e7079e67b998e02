"""Benchmarks that need policies: whole episodes as a user trains on them, the fine-reference
episode agreement, environment and SB3 throughput, the first step's time, the held goal's
phases, capture outcomes per setting, and the benchmark report that gathers every section
(``scripts/report.py``)."""
