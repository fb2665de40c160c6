"""What the rules may consult besides the tags: the site tables, its state, the last action."""
from __future__ import annotations

from dataclasses import dataclass

from drywall_lab.errors import Refusal
from drywall_lab.site import Site, SiteState


@dataclass(frozen=True)
class MappingContext:
    """The building component information and the action history's last row, for one instruction.

    ``last`` is the last *accepted* command (``drywall_id``, ``stud_id``, ``placement``):
    refused instructions never reach the history, so "previous" never points at them
    (spec section 3).
    """

    site: Site
    state: SiteState
    last: dict | None = None

    def require_last(self, said: str) -> dict:
        """The last accepted command, or the ``no_history`` refusal when there is none yet."""
        if self.last is None:
            raise Refusal(
                "no_history",
                f"{said} refers to the last panel installed, but nothing has been installed yet: "
                "name the panel or the stud another way.",
            )
        return self.last
