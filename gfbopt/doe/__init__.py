"""Design of experiments: sample plans, a kill-safe Parquet results store, and Sobol
sensitivity indices.

=======================  ==================================================================
module                   what it holds
=======================  ==================================================================
:mod:`.sampling`         factorial, Latin hypercube, Sobol, explicit lists, Saltelli designs
:mod:`.store`            one tidy table per study as atomic Parquet parts, fixed schema, resume
:mod:`.sensitivity`      first-order and total Sobol indices with confidence intervals
:mod:`.points`           the analyses of a sampled study, run on chunks of neighbouring points
:mod:`.run`              ``run_doe``: your function over your plan, into a store, with resume
:mod:`.engine`           chunks to an executor, rows to the store (timer, signals, retries)
:mod:`.limits`           the size of a job estimated before it starts; rules of fixed inputs
=======================  ==================================================================
"""
from .run import run_doe
from .sampling import METHODS, SamplePlan, Variable, sample
from .store import ResultStore, read_results

__all__ = ["METHODS", "ResultStore", "SamplePlan", "Variable", "read_results", "run_doe",
           "sample"]
