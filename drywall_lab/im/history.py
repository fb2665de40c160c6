"""The action history (spec section 4): one row per accepted command, the paper's nine fields."""
from __future__ import annotations

from pathlib import Path
from typing import Iterable

import pandas as pd

from drywall_lab.errors import Refusal
from drywall_lab.im.command import HISTORY_FIELDS, RobotCommand, placement_of_row
from drywall_lab.site import Site, SiteState, default_site

_GEOMETRY_TOLERANCE = 1e-4  # metres: a saved coordinate may be rounded to 0.1 mm


class ActionHistory:
    """The commands accepted so far, as a pandas DataFrame with the paper's nine columns.

    Only ``record`` adds a row, and only for a command that can be carried out on
    the site as the history leaves it; a refused instruction never reaches it.

    >>> h = ActionHistory()
    >>> h.record(RobotCommand.build(h.site, "500320", "500100", "vertical_left"))
    >>> h.frame[["stud_id", "drywall_id", "ver_hor"]].values.tolist()
    [['500100', '500320', 'vertical']]
    """

    def __init__(self, site: Site | None = None) -> None:
        self.site = site or default_site()
        self._commands: list[RobotCommand] = []
        self._state: SiteState = self.site.fresh()

    # --- building ----------------------------------------------------------------
    @classmethod
    def from_commands(cls, commands: Iterable[dict], site: Site | None = None) -> "ActionHistory":
        """A history of ``{"drywall_id", "stud_id", "placement"}`` commands, each checked in turn."""
        history = cls(site)
        for c in commands:
            history.record(RobotCommand.build(history.site, c["drywall_id"], c["stud_id"], c["placement"]))
        return history

    def record(self, command: RobotCommand) -> None:
        """Append an accepted command; a ``Refusal`` (and no change) if the site does not allow it."""
        self._state = self._state.install(command.drywall_id, command.stud_id, command.placement)
        self._commands.append(command)

    def copy(self) -> "ActionHistory":
        other = ActionHistory(self.site)
        other._commands, other._state = list(self._commands), self._state
        return other

    # --- reading -------------------------------------------------------------------
    @property
    def state(self) -> SiteState:
        """The site as this history leaves it: what is on the wall, what is left in the stacks."""
        return self._state

    @property
    def commands(self) -> list[RobotCommand]:
        return list(self._commands)

    @property
    def last(self) -> dict | None:
        """The last accepted command as ``{"drywall_id", "stud_id", "placement"}``; None when empty."""
        return self._commands[-1].as_contract() if self._commands else None

    @property
    def frame(self) -> pd.DataFrame:
        """The history table (a copy): the paper's nine columns, one row per accepted command."""
        return pd.DataFrame([c.history_row() for c in self._commands], columns=list(HISTORY_FIELDS))

    def __len__(self) -> int:
        return len(self._commands)

    def __repr__(self) -> str:
        return f"ActionHistory({len(self)} rows)\n{self.frame.to_string()}" if len(self) else "ActionHistory(empty)"

    def _repr_html_(self) -> str:
        return self.frame.to_html(index=False)

    # --- CSV -------------------------------------------------------------------------
    def to_csv(self, path: Path | str) -> Path:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        self.frame.to_csv(path, index=False, float_format="%.6f")
        return path

    @classmethod
    def from_csv(cls, path: Path | str, site: Site | None = None) -> "ActionHistory":
        """Read a history saved by ``to_csv``; a ``ValueError`` naming the row for anything inconsistent.

        Each row is checked against the site: its ids exist, its coordinates match its
        stud and placement, and it could be carried out after the rows before it.
        """
        path = Path(path)
        if not path.exists():
            raise FileNotFoundError(f"no action history at {path}")
        try:
            df = pd.read_csv(path, dtype=str, keep_default_na=False)
        except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
            raise ValueError(f"{path} is not an action history CSV ({e})") from None
        missing = [c for c in HISTORY_FIELDS if c not in df.columns]
        if missing:
            raise ValueError(f"{path} is not an action history: the column(s) {', '.join(missing)} are missing; "
                             f"expected {', '.join(HISTORY_FIELDS)}")
        history = cls(site)
        for number, row in enumerate(df.to_dict("records"), start=2):  # line 1 is the header
            where = f"{path}, line {number}"
            try:
                placement = placement_of_row(row)
                command = RobotCommand.build(history.site, row["drywall_id"], row["stud_id"], placement)
                for column, value in (("installed_x_left", command.x_left), ("installed_x_right", command.x_right)):
                    saved = float(row[column])
                    if abs(saved - value) > _GEOMETRY_TOLERANCE:
                        raise ValueError(f"{column} is {saved} but panel {command.drywall_id} on stud "
                                         f"{command.stud_id} ({placement.value}) gives {value:.6f}")
                history.record(command)
            except Refusal as r:
                raise ValueError(f"{where}: {r.message}") from None
            except ValueError as e:
                raise ValueError(f"{where}: {e}") from None
        return history
