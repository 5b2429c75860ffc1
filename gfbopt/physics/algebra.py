"""Elementwise arithmetic that evaluates on numpy arrays and on CasADi symbols alike.

The physics is written once (``docs/ARCHITECTURE.md``): every pointwise law uses these helpers
instead of ``np.*`` or ``ca.*`` directly, so the same function builds the symbolic CasADi model
and re-checks its solution in numpy.
"""
from __future__ import annotations

import casadi as ca
import numpy as np


def is_symbolic(*values) -> bool:
    """True if any value is a CasADi SX, MX or DM."""
    return any(isinstance(v, (ca.SX, ca.MX, ca.DM)) for v in values)


def cos(x):
    """cos on numbers or CasADi symbols."""
    return ca.cos(x) if is_symbolic(x) else np.cos(x)


def sin(x):
    """sin on numbers or CasADi symbols."""
    return ca.sin(x) if is_symbolic(x) else np.sin(x)


def positive_part(x):
    """max(x, 0) elementwise on numbers or CasADi symbols."""
    return ca.fmax(x, 0) if is_symbolic(x) else np.maximum(x, 0.0)


def weighted_sum(weights: np.ndarray, x):
    """Σ_k weights_k x_k on numbers or CasADi symbols."""
    return ca.dot(ca.DM(weights), x) if is_symbolic(x) else float(np.dot(weights, x))
