"""Checks on the span forces: an idler or tensioner on a span that carries the driving force,
and the largest span force against the chain's fatigue strength.

Idlers and tensioners
---------------------
A chain is adjusted by moving a shaft, else by "an adjustable idler sprocket engaging with the
unloaded strand of the chain" [Renold-DG, chain adjustment]: on the slack span, leaving the
driver, the idler carries only the sag and centrifugal tension F_0 + F_v. On a span that
carries the driving force (the tight span into the driver, or a span between two driven
sprockets) it is pushed back by the working tension: a spring tensioner yields and lets the
slack into the driver's mesh, a fixed idler's shaft carries the load of the working tension
on both its spans. :func:`idler_checks` fails a tensioner (an idler marked ``adjustable``) whose
spans carry more than the slack-span tension, and writes its shaft load in the note; a fixed
idler on a loaded span (a guide on the tight span, or between two driven sprockets of a
serpentine) is said in a warning with its shaft load (:func:`idler_warnings`): a fixed shaft
holds its place under the working tension, and a guide often cannot sit anywhere else, but
its bearings carry that load.

Fatigue
-------
[ISO606] gives a minimum dynamic (fatigue) strength for its chains, tested by the fatigue
test of [ISO15654]; manufacturers' selectors judge the chain against it. The largest force
the chain's spans carry — in steady running the static tension plus the steady dynamic load
of the span F_R,i + F_2,i (:mod:`chaindrive.dynamics.steady`), and the peak at start-up
(:mod:`chaindrive.dynamics.startup`) — is held to the chain's fatigue strength
(:attr:`chaindrive.model.ChainSpec.fatigue_strength`) where the catalogue gives it (column
``fatigue_strength_kN``, the standard's minimum or the maker's value).

The packaged catalogues carry no such value (the standard's table could not be consulted).
For a steel roller chain the check then holds the force to an estimate said as such next to
the number. A chain maker puts a roller chain's fatigue strength at 15–20 % of its breaking
force, depending on the chain's specification and quality [IwisFatigue], so

    F_D,est = 0.15·Q

with Q the catalogue's minimum breaking load of the whole chain — the low end of the maker's
range, on the standard's minimum breaking load (the same maker's rule of thumb, a safety
factor of 7 on the breaking force, is 14.3 %). A force between 0.15·Q and 0.20·Q lies inside
the band of the estimate: the check fails against the low end and its note says the margin
lies inside the band (fatigue possible, not decided); above 0.20·Q it fails over the whole
band. A chain that is not steel (the polymer catalogue) has no such rule: "cannot be
verified".
"""

from __future__ import annotations

from collections.abc import Sequence

from chaindrive._docstrings import shared_parameters
from chaindrive.checks import Check, judged
from chaindrive.errors import ChainDriveWarning, Quantities
from chaindrive.model import ChainSpec, Drive
from chaindrive.strength.loads import LoadsResult

__all__ = ["FATIGUE_FRACTION_HIGH", "FATIGUE_FRACTION_LOW", "SHARE_TOLERANCE",
           "estimated_fatigue_strength", "fatigue_check", "idler_checks", "idler_warnings"]

#: Share of the peripheral force below which a span counts as slack [-] (round-off of the
#: tension balance).
SHARE_TOLERANCE = 1e-9
#: Fatigue strength of a steel roller chain as a fraction of its breaking force, the low and
#: the high end of the maker's range [-] [IwisFatigue].
FATIGUE_FRACTION_LOW, FATIGUE_FRACTION_HIGH = 0.15, 0.20


def _idler_states(drive: Drive, loads: LoadsResult) -> list[tuple[int, float]]:
    """(index, share of F_t its spans carry beyond the slack-span tension) of every idler."""
    slack = loads.span_tensions[loads.slack_span]
    ft = loads.peripheral_force
    out = []
    for i, s in enumerate(drive.sprockets):
        if s.role != "idler":
            continue
        tension = loads.span_tensions[i]  # the span leaving it; the arriving one is equal
        share = (tension - slack) / ft if ft > 0 else 0.0
        out.append((i, 0.0 if abs(share) < SHARE_TOLERANCE else share))
    return out


def _guide(drive: Drive, index: int, share: float) -> bool:
    """A fixed idler on a span that carries part or all of the driving force."""
    return not drive.sprockets[index].adjustable and share > 0.0


@shared_parameters
def idler_warnings(drive: Drive, loads: LoadsResult) -> list[ChainDriveWarning]:
    """Say the shaft load of every fixed idler that guides the chain on a loaded span
    (module docstring).

    Parameters
    ----------
    %(drive)s
    loads : LoadsResult
        Its static loads.

    Returns
    -------
    list of ChainDriveWarning
        One per such idler.
    """
    n = len(drive.sprockets)
    out = []
    for i, share in _idler_states(drive, loads):
        if not _guide(drive, i, share):
            continue
        q = Quantities()
        s = drive.sprockets[i]
        out.append(ChainDriveWarning(
            "strength.idler-on-loaded-span", f"sprockets[{s.name}]",
            f"idler {s.name} guides the chain on a loaded span ({drive.sprockets[i - 1].name} → "
            f"{s.name} → {drive.sprockets[(i + 1) % n].name}, "
            f"{q(loads.span_tensions[i], 'force', '.4g')}, {share:.0%} of the peripheral force): its shaft "
            f"carries {q(loads.shaft_load_magnitudes[i], 'force', '.4g')}; a tensioner "
            "there would be pushed back by the working tension", q.items))
    return out


def idler_checks(drive: Drive, loads: LoadsResult) -> list[Check]:
    """Every tensioner (an adjustable idler) on the slack side: the share of the peripheral
    force its span carries beyond the slack span ≤ 0 (fixed idlers on a loaded span are left
    to :func:`idler_warnings`).

    Parameters
    ----------
    drive : Drive
        The design (its sprockets in the order of travel, as the loads).
    loads : LoadsResult
        The static loads of the contour (span tensions, shaft loads).

    Returns
    -------
    list of Check
        One check per tensioner ("idler on slack span", value (T − T_slack)/F_t [-], limit 0);
        a failure names the span, its tension and the idler's shaft load.

    References
    ----------
    [Renold-DG, chain adjustment].
    """
    n = len(drive.sprockets)
    out: list[Check] = []
    for i, share in _idler_states(drive, loads):
        s = drive.sprockets[i]
        if not s.adjustable:  # a fixed idler: a warning on a loaded span, nothing to check
            continue
        tension = loads.span_tensions[i]
        q = Quantities()
        what = "tensioner" if s.adjustable else "idler"
        span = f"{drive.sprockets[i - 1].name} → {s.name} → {drive.sprockets[(i + 1) % n].name}"
        if share > 0:
            note = (f"{what} on a span carrying the driving force ({span}, "
                    f"{q(tension, 'force', '.4g')}, {share:.0%} of the peripheral force): shaft load "
                    f"{q(loads.shaft_load_magnitudes[i], 'force', '.4g')}; place it on the "
                    f"slack span leaving {drive.driver.name}, or reverse the rotation")
        else:
            note = (f"{what} on the slack side ({span}, {q(tension, 'force', '.4g')}): shaft "
                    f"load {q(loads.shaft_load_magnitudes[i], 'force', '.4g')}")
        out.append(judged("idler on slack span", s.name, share, 0.0, "max",
                          "[Renold-DG, chain adjustment]", note=note, part="geometry",
                          item=s.name, note_quantities=q.items))
    return out


def estimated_fatigue_strength(spec: ChainSpec) -> float | None:
    """The estimate of a steel chain's fatigue strength, F_D,est = 0.15·Q (module docstring).

    Parameters
    ----------
    spec : ChainSpec
        The chain (its minimum breaking load Q [N] and material).

    Returns
    -------
    float or None
        F_D,est [N]; None for a chain that is not steel (no such rule for it).

    References
    ----------
    [IwisFatigue] (fatigue strength 15–20 % of the breaking force).
    """
    if spec.material != "steel":
        return None
    return FATIGUE_FRACTION_LOW * spec.breaking_load


def fatigue_check(spec: ChainSpec, steady_peak: float | None,
                  startup_peak: float | None) -> Check:
    """The largest span force ≤ the chain's fatigue strength, or ≤ its estimate
    :func:`estimated_fatigue_strength` when the catalogue gives none (module docstring).

    Parameters
    ----------
    spec : ChainSpec
        The chain (its ``fatigue_strength`` [N], None when the catalogue has none).
    steady_peak : float or None
        Largest static + steady dynamic span force F_R,i + F_2,i [N] (None: not computed).
    startup_peak : float or None
        Largest span force at start-up [N] (None: no start-up run).

    Returns
    -------
    Check
        "fatigue" [N], ``limit_estimated`` when the limit is the estimate; "cannot be
        verified" when neither the catalogue nor the estimate gives a fatigue strength, or
        no span force was computed.

    References
    ----------
    [ISO606] (minimum dynamic strength); [ISO15654] (its test); [IwisFatigue] (the estimate).
    """
    peaks: Sequence[tuple[str, float]] = [
        (k, v) for k, v in (("steady running", steady_peak), ("start-up", startup_peak))
        if v is not None]
    q = Quantities()
    estimate = None if spec.fatigue_strength is not None else estimated_fatigue_strength(spec)
    limit = spec.fatigue_strength if estimate is None else estimate
    source = "[ISO606]; [ISO15654]" + ("" if estimate is None else "; [IwisFatigue]")
    if not peaks:
        return judged("fatigue", spec.designation, None, limit, "max", source, "N",
                      note="no span forces of the dynamic response (run the analysis with "
                      "the response)", part="chain", limit_estimated=estimate is not None)
    where, value = max(peaks, key=lambda kv: kv[1])
    shown = ", ".join(f"{k} {q(v, 'force', '.4g')}" for k, v in peaks)
    if limit is None:
        note = (f"cannot be verified: no fatigue strength in the catalogue for "
                f"{spec.designation} (catalogue column fatigue_strength_kN) and no estimate "
                f"for a {spec.material} chain; largest span force {shown}")
    elif estimate is not None:
        high = FATIGUE_FRACTION_HIGH * spec.breaking_load
        low_pc, high_pc = 100 * FATIGUE_FRACTION_LOW, 100 * FATIGUE_FRACTION_HIGH
        note = (f"limit an estimate: {low_pc:g} % of the minimum breaking load "
                f"{q(spec.breaking_load, 'force', '.5g')} (a chain's fatigue strength is "
                f"{low_pc:g}–{high_pc:g} % of it [IwisFatigue]); no published fatigue strength "
                f"in the catalogue (column fatigue_strength_kN); largest span force in "
                f"{where}: {shown}")
        if limit < value <= high:
            note += (f"; inside the band of the estimate (up to {q(high, 'force', '.5g')}): "
                     "fatigue possible, not decided")
    else:
        note = f"largest span force in {where}; {shown}"
    return judged("fatigue", spec.designation, value, limit, "max", source, "N", note=note,
                  part="chain", note_quantities=q.items,
                  limit_estimated=estimate is not None)
