"""Catalogue sources as a reader reads them.

A catalogue row names where its numbers come from in its ``source`` cell; a row whose
numbers are partly estimates lists the estimated columns after ``ESTIMATED:`` (the
convention of ``chaindrive/catalog/data/chains_polymer.csv``), e.g. ::

    dims: ISO 606:1994 16B [ISO606]; material: PA66-GF30 = 30 % glass-fibre PA66 [HPT] via
    materials.csv; ESTIMATED: breaking_load_kN|mass_kg_m|allowable_load_kN|max_speed_m_s
    (header formulas; speed: [TsubakiGuide] Table 4.1 transferred)

The report shows it short, with the word "estimate" and the citations kept (the references
are collected from them)::

    estimate: breaking load, mass per length, allowable load, speed limit (formulas of the
    catalogue; speed: [TsubakiGuide] Table 4.1 transferred); dimensions [ISO606];
    material [HPT]

Nothing is computed: the text is rearranged.
"""

from __future__ import annotations

import re

from chaindrive.model import ESTIMATE_MARK, estimated_columns

__all__ = ["ESTIMATE_MARK", "FIELD_NAMES", "catalogue_estimates", "estimate_note", "readable_source"]

#: Catalogue columns → what the report calls them.
FIELD_NAMES: dict[str, str] = {
    "breaking_load_kN": "breaking load",
    "mass_kg_m": "mass per length",
    "allowable_load_kN": "allowable load",
    "max_speed_m_s": "speed limit",
}
#: Labels of the parts of a source cell → the report's words.
_LABELS = {"dims": "dimensions"}
_UNIT_SUFFIX = re.compile(r"_(kN|N|kg_m|m_s|mm|mm2|kg)$")
_CITATION = re.compile(r"\[[^\]]+\]")


def _field_name(column: str) -> str:
    """The report's name of a catalogue column (``max_speed_m_s`` → "speed limit")."""
    return FIELD_NAMES.get(column) or _UNIT_SUFFIX.sub("", column).replace("_", " ")


def _split_estimate(source: str) -> tuple[str, list[str], str] | None:
    """(what precedes the mark, the estimated columns, the note in brackets after them), or
    None when the source marks no estimate."""
    head, mark, tail = source.partition(ESTIMATE_MARK)
    if not mark:
        return None
    note = tail.strip().partition(" (")[2].strip()
    if note.endswith(")"):
        note = note[:-1]
    return head, list(estimated_columns(source)), note.strip()


def catalogue_estimates(source: str) -> tuple[str, ...]:
    """The quantities a catalogue row marks as estimates, by the report's names.

    Parameters
    ----------
    source : str
        The row's source cell (:attr:`chaindrive.model.ChainSpec.source`).

    Returns
    -------
    tuple of str
        E.g. ``("breaking load", "mass per length", "allowable load", "speed limit")``;
        empty when the row marks none.
    """
    parts = _split_estimate(source)
    return () if parts is None else tuple(_field_name(c) for c in parts[1])


def estimate_note(source: str) -> str:
    """How a catalogue row says its estimates were made (the words in brackets after the
    estimated columns), "" when it says nothing.

    Parameters
    ----------
    source : str
        The row's source cell.

    Returns
    -------
    str
        E.g. "formulas of the catalogue; speed: [TsubakiGuide] Table 4.1 transferred".
    """
    parts = _split_estimate(source)
    return "" if parts is None else parts[2].replace("header formulas", "formulas of the catalogue")


def readable_source(source: str) -> str:
    """A catalogue source short and readable: "estimate: <quantities> (<how>)", then each
    labelled part of the rest by its label and citations. A source that marks no estimate is
    returned as it is.

    Parameters
    ----------
    source : str
        A source text (a check's source, a catalogue row's source cell).

    Returns
    -------
    str
        The text to show.
    """
    parts = _split_estimate(source)
    if parts is None:
        return source
    head, columns, _ = parts
    note = estimate_note(source)
    prefix = ""
    if head.startswith("catalogue row:"):
        prefix, head = "catalogue row, ", head[len("catalogue row:"):]
    out = [f"{prefix}estimate: {', '.join(_field_name(c) for c in columns)}"
           + (f" ({note})" if note else "")]
    for segment in head.split(";"):
        label, colon, text = segment.strip().partition(":")
        if not segment.strip():
            continue
        keys = _CITATION.findall(text if colon else segment)
        name = _LABELS.get(label.strip(), label.strip())
        out.append(f"{name} {', '.join(keys)}" if colon and keys else segment.strip())
    return "; ".join(out)
