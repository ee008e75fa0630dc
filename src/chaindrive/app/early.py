"""The design on the page read before its widgets are drawn, so that its results go to the
browser first.

Streamlit sends the elements of a run in the order the script makes them, and the browser
draws them in that order: results made after some forty widgets (fields, the sprocket
table, the edit form, the sidebar) reached the screen only after the browser had redrawn
all of those. Every widget's value in a run is already in the session state when the run
starts (what the browser sent), or is its default for a widget not drawn before; so the
design of the run can be read from there first (:func:`design_from_state`), analysed, and
its results drawn before the widgets. The page then checks it against the design its
widgets give, and when the two differ it discards the early results and runs again with
the widgets' design (:mod:`chaindrive.app.main`): what stays on screen is always the
analysis of the design in the form.

The sprocket table's rows are in the session state as the table sent them
(:mod:`chaindrive.app.table`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any, Protocol

from chaindrive.app.state import DesignForm, design_from_form, is_empty
from chaindrive.app.table import merged_rows, table_rows_from_state

__all__ = ["AUTO_FORM", "CHAIN_PREFIX", "FORMS", "chain_values", "design_from_state",
           "drive_values"]

AUTO_FORM = "(by chain standard)"
#: The tooth forms of the form's select box (the first: by the chain's standard).
FORMS = (AUTO_FORM, "ISO 606", "GOST 591")
#: How a chain choice "select for the power of a standard" starts.
CHAIN_PREFIX = "(select for the power: "


class _State(Protocol):
    """What the page's session state is read through (a widget's key → its value)."""

    def get(self, key: str, default: Any, /) -> Any:
        """The value of ``key``, ``default`` when there is none."""

    def __contains__(self, key: object) -> bool:
        """Whether ``key`` has a value."""

    def __getitem__(self, key: str) -> Any:
        """The value of ``key``."""


def drive_values(drive: Mapping[str, Any], name: Any, tooth_form: Any, power: Any,
                 service_factor: Any) -> dict[str, Any]:
    """The ``[drive]`` table of the form from its fields' values (the other keys of the
    loaded file's table kept).

    Parameters
    ----------
    drive : Mapping
        The loaded form's ``[drive]`` table.
    name : object
        The drive name field.
    tooth_form : object
        The tooth form box (:data:`AUTO_FORM`: by the chain's standard).
    power : object
        The power field [kW] (None: empty).
    service_factor : object
        The service factor field [-] (None: empty).

    Returns
    -------
    dict
        The ``[drive]`` table of the design mapping.
    """
    extra = {k: v for k, v in drive.items()
             if k not in ("name", "power_kw", "service_factor", "tooth_form")}
    return {"name": name, "power_kw": power, "service_factor": service_factor,
            "tooth_form": None if tooth_form == AUTO_FORM else tooth_form, **extra}


def chain_values(chain: Mapping[str, Any], strands: Any, choice: str, links: Any,
                 contours: Any, allow_odd: Any, sag: Any, link_stiffness: Any
                 ) -> dict[str, Any]:
    """The ``[chain]`` table of the form from its fields' values: a catalogue chain, or a
    selection for the power within a standard (``choice``).

    Parameters
    ----------
    chain : Mapping
        The loaded form's ``[chain]`` table.
    strands : object
        The strands field [-] (None: empty).
    choice : str
        The chain box: a designation, or ``"(select for the power: <standard>)"``.
    links : object
        The links field [-] (None: empty).
    contours : object
        The contours field [-] (None: empty).
    allow_odd : object
        The odd-links box.
    sag : object
        The installed-sag field [-] (fraction of the slack span; None: empty).
    link_stiffness : object
        The link-stiffness field [N/m] (None: empty).

    Returns
    -------
    dict
        The ``[chain]`` table of the design mapping.
    """
    ch = dict(chain)
    if choice.startswith(CHAIN_PREFIX):
        ch.update(designation=None, standard=choice[len(CHAIN_PREFIX):-1])
    else:
        ch.update(designation=choice, standard=None, series=None, pitch_mm=None)
    ch.update(strands=strands, links=links, contours=contours, allow_odd=allow_odd, sag=sag,
              link_stiffness_n_per_m=link_stiffness)
    return ch


def design_from_state(base: DesignForm, state: _State, key: Callable[[str], str],
                      table_key: str, chain_choice: str, chain_options: list[str]
                      ) -> dict[str, Any] | None:
    """The design mapping the page's widgets will give in this run, read from the session
    ``state`` before they are drawn (a widget not drawn before gives its default, the
    value of the loaded form ``base``); None when it cannot be read there.

    Parameters
    ----------
    base : DesignForm
        The form the widgets are drawn from.
    state : mapping
        The session state (widget key → value).
    key : callable
        The page's widget key of a field name.
    table_key : str
        The widget key of the sprocket table.
    chain_choice : str
        The chain select box's default (the loaded design's chain).
    chain_options : list of str
        The chain select box's options.

    Returns
    -------
    dict | None
        The design mapping (:func:`chaindrive.app.state.design_from_form`).
    """
    d, ch = base.drive, base.chain
    given = d.get("tooth_form")

    def read(name: str, default: Any) -> Any:
        return state.get(key(name), default)

    def number(name: str, value: Any) -> Any:
        return read(name, None if is_empty(value) else value)

    choice = read("chain.choice", chain_choice)
    if choice not in chain_options:
        return None
    drive = drive_values(d, read("drive.name", d.get("name") or ""),
                         read("drive.tooth_form", given if given in FORMS else AUTO_FORM),
                         number("drive.power", d.get("power_kw")),
                         number("drive.sf", d.get("service_factor")))
    chain = chain_values(ch, number("chain.strands", ch.get("strands")), choice,
                         number("chain.links", ch.get("links")),
                         number("chain.contours", ch.get("contours")),
                         read("chain.allow_odd", bool(ch.get("allow_odd"))),
                         number("chain.sag", ch.get("sag")),
                         number("chain.link_stiffness", ch.get("link_stiffness_n_per_m")))
    held = table_rows_from_state(state, table_key)
    rows = base.sprockets if held is None else merged_rows(base.sprockets, held)
    return design_from_form(DesignForm(drive, chain, rows, base.other))
