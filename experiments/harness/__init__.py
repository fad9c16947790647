"""Experiment harness: expands declarative experiment configs into renders, measures them
against long references with the `metrics` tool, and writes results, tables and plots.

Entry point: experiments/run.py (see `experiments/run.py --help`)."""
