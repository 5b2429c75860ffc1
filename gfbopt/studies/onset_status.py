"""The ``onset_status`` of an onset search's row (the onset study kinds, isothermal or at the
running condition): an onset found, or why there is none — an answer, never a silent gap."""

ONSET = "onset"
STABLE = "stable over the range"
UNSTABLE_LOW = "unstable at the lowest speed"
UNSTABLE_ALL = "unstable at every mass"
OVERLOAD = "load exceeds capacity"
FAILED = "failed"
#: no running state before the onset (the running onset's thermal_limit_kind)
THERMAL_RUNAWAY = "thermal runaway"
CLOSURE = "clearance closure"
