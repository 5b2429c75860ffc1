"""The words every text report and figure uses for the bearing model that made its numbers.

A conventions or options dict (``ModelOptions.to_dict``, ``BearingModel.options``, a rotor
bearing's conventions, a stability result's) becomes one phrase: the foil (with hardening
bumps when the foil law is ``hardened`` or a hardening exponent is stated), the deflection
law, the loss factor η and the bumps' Coulomb friction μ_f (with κ = k_f/k_b) when stated —
so a report never says "simple foil" for a model whose JSON says ``foil_law: "hardened"``
or leaves out a friction coefficient the numbers were computed with.
"""
from __future__ import annotations

import math


def _number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) \
        and math.isfinite(value)


def hardened(conv: dict) -> bool:
    """The model's bumps harden (foil law 'hardened', or a hardening exponent n > 0)."""
    n = conv.get("hardening_exponent")
    return conv.get("foil_law") == "hardened" or (_number(n) and n > 0)


def foil_words(conv: dict) -> str:
    """'simple foil', 'simple foil with hardening bumps (n = 3)', 'beam foil', …"""
    text = f"{conv.get('foil') or 'simple'} foil"
    if hardened(conv):
        n = conv.get("hardening_exponent")
        text += " with hardening bumps" + (f" (n = {n:g})" if _number(n) else "")
    return text


def friction_words(conv: dict) -> str:
    """'bump friction μ_f = 0.5 (κ = 2)' when the model's bumps have Coulomb friction, else ''."""
    mu = conv.get("friction_coefficient")
    if not (_number(mu) and mu > 0):
        return ""
    kappa = conv.get("friction_stiffness_ratio")
    return f"bump friction μ_f = {mu:g}" + (f" (κ = {kappa:g})" if _number(kappa) else "")


def model_words(conv: dict, law: str = "deflection law") -> str:
    """'simple foil, mean deflection law, loss factor 0[, bump friction μ_f = 0.5 (κ = 2)]'."""
    eta = conv.get("loss_factor")
    parts = [foil_words(conv)]
    if conv.get("deflection_law"):
        parts.append(f"{conv['deflection_law']} {law}")
    if _number(eta):
        parts.append(f"loss factor {eta:g}")
    friction = friction_words(conv)
    if friction:
        parts.append(friction)
    return ", ".join(parts)


def _zone_words(zone: dict) -> str:
    extra = [f"{key.replace('_', ' ')} {value:g}" for key, value in zone.items()
             if key not in ("start_deg", "end_deg") and _number(value)]
    return (f"{zone.get('start_deg', 0):g}–{zone.get('end_deg', 360):g}°"
            + (f" ({', '.join(extra)})" if extra else ""))


def built_words(conv: dict) -> str:
    """'3 shims, preload 8 µm, 60° wide; pads at 0, 120, 240°; bump zones 0–180° (friction
    coefficient 0.3), 180–360°' for a bearing as built (bore, pads, zones), else ''."""
    parts = []
    bore = conv.get("bore")
    if bore and bore != "round":
        text = f"{conv['bore_count']} {bore}" if _number(conv.get("bore_count")) else f"{bore}"
        depth, ratio = conv.get("bore_preload_depth_m"), conv.get("bore_preload_ratio")
        if _number(depth):
            text += f", preload {depth * 1e6:.3g} µm"
        elif _number(ratio):
            text += f", preload {ratio:.3g} c"
        if _number(conv.get("bore_width_deg")):
            text += f", {conv['bore_width_deg']:g}° wide"
        parts.append(text)
    pads = conv.get("pads_leading_end_deg")
    if pads:
        parts.append("pads at " + ", ".join(f"{p:g}" for p in pads) + "°")
    zones = conv.get("zones")
    if zones:
        parts.append("bump zones " + ", ".join(_zone_words(z) for z in zones))
    return "; ".join(parts)
