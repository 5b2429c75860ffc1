"""Exceptions raised by gfbopt.

``ParameterError`` is raised for bad input: its message names the parameter, the value
received and the rule it breaks.  ``ConvergenceError`` is raised when a solver could not
reach its tolerance; it carries the solver status and the residual achieved.
"""
from __future__ import annotations


class GfboptError(Exception):
    """Base class of all gfbopt errors."""


class ParameterError(GfboptError, ValueError):
    """An input parameter breaks a rule (name, value and rule are in the message)."""

    def __init__(self, name: str, value: object, rule: str):
        self.name = name
        self.value = value
        self.rule = rule
        super().__init__(f"{name} = {value!r}: {rule}")


class ConvergenceError(GfboptError, RuntimeError):
    """A solver stopped without meeting its tolerance."""

    def __init__(self, message: str, status: str = "", residual: float = float("nan")):
        self.status = status
        self.residual = residual
        super().__init__(f"{message} (status: {status}, residual: {residual:.3e})")
