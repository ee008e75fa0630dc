"""Plausibility of a design as a whole, beyond the bounds of its fields
(:mod:`chaindrive.io.limits`): a given inertia cannot be less than the sprocket's own."""

from __future__ import annotations

from chaindrive.catalog import find_material
from chaindrive.errors import DesignError
from chaindrive.geometry.sprocket import sprocket_mass_and_inertia
from chaindrive.io.limits import MIN_INERTIA_SHARE
from chaindrive.model import Drive

__all__ = ["check_inertias"]


def check_inertias(drive: Drive) -> None:
    """Refuse a sprocket whose given inertia is below :data:`MIN_INERTIA_SHARE` of the
    inertia of its own plate.

    The inertia of a sprocket is that of *everything turning with it*, so it cannot be less
    than the sprocket's own; the plate estimate is the one the dynamics uses when no inertia
    is given (:func:`chaindrive.geometry.sprocket.sprocket_mass_and_inertia`: a plate of the
    chain's width with lightening holes), and a tenth of it leaves room for spoked or
    polymer wheels. A smaller value is a slip of a unit (g for kg, mm² for m²) — and would
    make the ring's highest natural frequency, and with it the start-up's step count, grow
    as 1/√J.

    Parameters
    ----------
    drive : Drive
        The design as read.

    Raises
    ------
    DesignError
        On ``sprockets[i].inertia`` with the value and the least plausible one [kg·m²].
    """
    spec = drive.chain.spec
    for i, s in enumerate(drive.sprockets):
        if s.inertia is None:
            continue
        material = find_material(s.material, field=f"sprockets[{i}].material")
        plate = sprocket_mass_and_inertia(
            spec.pitch, s.teeth, spec.inner_width, material.density, material.is_polymer,
            strands=spec.strands, transverse_pitch=spec.transverse_pitch).moment_of_inertia
        least = MIN_INERTIA_SHARE * plate
        if s.inertia < least:
            raise DesignError(
                f"sprockets[{i}].inertia",
                f"{s.inertia:.3g} kg·m² is less than a tenth of the inertia of the sprocket's "
                f"own plate ({plate:.3g} kg·m² for {s.teeth} teeth of {spec.designation} in "
                f"{material.name}); give the inertia of everything turning with it, at least "
                f"{least:.3g} kg·m²")
