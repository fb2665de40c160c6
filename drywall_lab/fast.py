"""The project's fast mode: the one reading of ``DRYWALL_FAST`` (README, "Fast mode").

Every notebook and the library modules that change with it (``drywall_lab.rc.settings``) read it through
:func:`fast_mode`; ``drywall_lab.course`` re-exports it for the notebooks. This module imports nothing of the
project, so that any module may use it.
"""
from __future__ import annotations

import os

#: Values of ``DRYWALL_FAST`` (compared without case or surrounding spaces) that switch fast mode on / off.
FAST_ON = ("1", "true", "yes", "on")
FAST_OFF = ("", "0", "false", "no", "off")


def fast_mode() -> bool:
    """True when the environment variable ``DRYWALL_FAST`` asks for the course's fast mode.

    ``1``, ``true``, ``yes`` or ``on`` (any case) switch it on; unset, empty, ``0``, ``false``, ``no`` or
    ``off`` leave the notebooks in full mode. Any other value is a ``ValueError`` naming the accepted ones,
    so a typo never silently picks a mode.
    """
    value = os.environ.get("DRYWALL_FAST", "").strip().lower()
    if value in FAST_ON:
        return True
    if value in FAST_OFF:
        return False
    raise ValueError(
        f"DRYWALL_FAST={os.environ['DRYWALL_FAST']!r} is not understood: use one of "
        f"{', '.join(FAST_ON)} for fast mode or {', '.join(v for v in FAST_OFF if v)} (or leave it unset) "
        "for full mode"
    )
