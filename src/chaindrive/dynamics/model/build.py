"""The dynamic model of a whole drive: the chain contour with every sprocket's train, the
chain's own mass, the motor and the driven machines (docs/dynamics.md §1).

:func:`drive_model` builds it from a :class:`~chaindrive.model.Drive` and its contour as a
:class:`~chaindrive.dynamics.torsional.model.TorsionalEngine` [Rao2011, ch. 6]:

* **sprockets** — rotating bodies of inertia J_i (``inertia``, ``reduced_mass``·R², or the
  sprocket body) with their flywheels;
* **the chain** — one translational node per sprocket (a body of unit radius: its "angle" is
  the chain's displacement [m] there) carrying the links wrapped on that sprocket; each span
  joins the chain nodes of its two sprockets as a tension-only spring c = k_link p/L · s_sag
  (docs/dynamics.md §2) with the span's mass q·L distributed consistently (m/3 on each end,
  m/6 between them; docs/torsional.md §5: +0.03 % in f₁ against a wave model of the span,
  the half-and-half lumping −3.5 %);
* **the wrap** — the teeth in mesh hold the chain node to its sprocket by the wrap stiffness
  (ladder of tooth springs, docs/dynamics.md §2), a spring that pulls and pushes. The chain
  runs on from span to span through the chain node, so a sprocket carries only the
  difference of the tensions of its two spans (an idler with a small wrap stays out of the
  load path);
* **trains** — shafts and couplings (springs with dampers), gear stages (rigid meshes with
  ratio and efficiency; the inertias behind a mesh are referred through it), rotors, springs
  to the frame;
* **motor** — its rotor on the outermost node of the driver's train (on the driver's shaft
  when it has none); its torque law acts there, through the efficiencies of the gear stages
  between it and the sprocket;
* **machines** — the outermost node of every driven sprocket's train takes the moment of
  resistance of its power share, divided by the efficiencies between it and the sprocket.

Nodes of zero inertia are condensed out statically [Guyan1965] (exact for the undamped
modes; a damper on such a node is condensed with the same static shape, an approximation
the model's ``notes`` state). The damping of the chain is the damping ratio of its material
pair [MultimassChainDrives, Table 1] (or the design's, or each span's hinge friction at its
own tension [ChainHingeDissipation]): span and wrap dampers d = 2ζ k/ω_ref proportional to
their stiffness, ω_ref the first elastic mode in which the chain holds most of the strain
energy, so that mode has the ratio ζ (times the chain's share of its strain energy).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive._docstrings import shared_parameters
from chaindrive.catalog import find_material
from chaindrive.dynamics.model.assembly import (
    CHAIN_NODE,
    DriveParts,
    LinearModel,
    LoadPlacement,
    MotorPlacement,
    assembled_parts,
    shaft_stiffness,
)
from chaindrive.dynamics.model.damping import (
    chain_damping,
    reference_angular_frequency,
    with_chain_dampers,
)
from chaindrive.dynamics.modes import Modes
from chaindrive.dynamics.parameters import RingParameters, drive_ring_parameters
from chaindrive.dynamics.ring import RingModel
from chaindrive.errors import ChainDriveWarning, DesignError
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive, Material

__all__ = [
    "CHAIN_NODE",
    "DriveModel",
    "LinearModel",
    "LoadPlacement",
    "MotorPlacement",
    "drive_model",
    "model_completeness",
    "ring_model",
    "shaft_stiffness",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, slots=True, eq=False)
class DriveModel(DriveParts):
    """The whole-drive model (module docstring) in the coordinates q of its
    :class:`LinearModel`: the fields of
    :class:`~chaindrive.dynamics.model.assembly.DriveParts` (the assembled model: torsional
    model, matrices, coordinates of sprockets, rotors, motor and machines, damping, ring,
    notes, trains) and the two below.

    Parameters
    ----------
    missing : tuple of str
        What makes the model incomplete (empty: complete).
    modes : Modes | None
        The modal analysis done while building (None: computed on demand).
    """

    missing: tuple[str, ...] = ()
    modes: Modes | None = None

    @property
    def complete(self) -> bool:
        """True when the driver carries its motor and every driven sprocket its machine."""
        return not self.missing

    def modal(self) -> Modes:
        """Undamped natural frequencies and shapes (:meth:`TorsionalEngine.modal`, computed
        when the model was built).

        Returns
        -------
        Modes
            Frequencies [Hz], shapes [rad] and strain-energy shares [-].
        """
        return self.modes if self.modes is not None else self.torsional.modal()

    def warnings(self) -> tuple[ChainDriveWarning, ...]:
        """One ``dynamics.model-incomplete`` warning when the model is incomplete.

        Returns
        -------
        tuple of ChainDriveWarning
            Empty when the model is complete.
        """
        if self.complete:
            return ()
        return (ChainDriveWarning(
            "dynamics.model-incomplete", "dynamics",
            "the dynamic model is incomplete (" + "; ".join(self.missing) + "): its natural "
            "frequencies are upper bounds and the start-up is not meaningful; give the motor "
            "([motor]) and what turns with every driven sprocket (its train, inertia or "
            "reduced_mass)"),)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: completeness, trains, motor, loads, damping.

        Returns
        -------
        dict
            Keys carry their unit (``torque_n_m``, ``nominal_speed_rpm`` …).
        """
        m = self.motor
        return {
            "complete": self.complete,
            "missing": list(self.missing),
            "notes": list(self.notes),
            "note_quantities": [q.to_dict() for q in self.note_quantities],
            "degrees_of_freedom": self.linear.size,
            "nodes": self.torsional.to_dict()["nodes"],
            "trains": self.trains,
            "motor": None if m is None else {
                "node": m.node, "rotor_inertia_kg_m2": m.rotor_inertia,
                "rotor_inertia_estimated": m.estimated, "efficiency": m.efficiency,
                "nominal_speed_rpm": m.nominal_speed * 30.0 / math.pi},
            "loads": [{"sprocket": ld.sprocket, "node": ld.node, "law": ld.kind,
                       "torque_n_m": ld.torque, "efficiency": ld.efficiency,
                       "nominal_speed_rpm": ld.nominal_speed * 30.0 / math.pi}
                      for ld in self.loads],
            "span_damping_ratios": self.span_damping_ratios.tolist(),
            "damping_source": self.damping_source,
            "damping_reference_frequency_hz": self.reference_frequency_hz,
            "span_stiffness_n_per_m": (self.linear.span_stiffness / self.contours).tolist(),
            "sprocket_inertias_kg_m2": self.ring.inertias_kg_m2.tolist(),
            "reduced_masses_kg": self.ring.masses_kg.tolist(),
            "pitch_radii_m": self.pitch_radii.tolist(),
            "wrap_stiffness_n_per_m": self.ring.wrap_stiffness_n_per_m.tolist(),
            "chain_stiffness_n_per_m": self.ring.chain_stiffness_n_per_m.tolist(),
            "sag_factors": self.ring.sag_factors.tolist(),
            "span_tensions_n": (None if self.ring.span_tensions_n is None
                                else self.ring.span_tensions_n.tolist()),
            "link_stiffness_n_per_m": self.ring.link_stiffness_n_per_m,
            "contours": self.contours,
        }


# --------------------------------------------------------------------------- completeness
@shared_parameters
def model_completeness(drive: Drive) -> tuple[str, ...]:
    """What the whole-drive model of ``drive`` lacks (empty when complete).

    The driver needs its motor: a ``[motor]`` table, or (without a train) its ``inertia`` or
    ``reduced_mass`` holding everything on its shaft; a driven sprocket needs what it drives:
    a train, or its ``inertia`` or ``reduced_mass``. Idlers need nothing.

    %(drive_returns)s
    tuple of str
        One phrase per gap.
    """
    out = []
    for s in drive.sprockets:
        given = s.inertia is not None or s.reduced_mass is not None
        if s.role == "driver" and drive.motor is None and (s.train or not given):
            out.append(f"the driver {s.name} has no motor")
        elif s.role == "driven" and not s.train and not given:
            out.append(f"the driven sprocket {s.name} has nothing on its shaft")
    return tuple(out)


def drive_model(drive: Drive, geometry: GeometryResult, *,
                span_tensions: Sequence[float] | None = None,
                material_lookup: Callable[[str], Material] | None = None,
                ring: RingParameters | None = None) -> DriveModel:
    """The whole-drive model of ``drive`` (module docstring).

    Parameters
    ----------
    drive : Drive
        The design (all its power: with m contours the spans carry all m).
    geometry : GeometryResult
        Its contour (sprockets where the take-up put them).
    span_tensions : sequence of float | None
        Static tension of every span of one contour [N] for the sag stiffness and the hinge
        friction (None: from the drive's loads when it has a power, else taut spans).
    material_lookup : callable | None
        name → Material (None: :func:`chaindrive.catalog.find_material`).
    ring : RingParameters | None
        The ring reduction to build on (sprocket inertias, span stiffnesses and tensions);
        None: :func:`chaindrive.dynamics.parameters.drive_ring_parameters` of the drive. A
        perturbed state of the drive (worn chain, scattered inertias) passes its own.

    Returns
    -------
    DriveModel

    References
    ----------
    [MultimassChainDrives, §3.1] (the ring of reduced masses it generalises), [Rao2011, ch. 6]
    (torsional systems), [Guyan1965] (condensation).
    """
    lookup = _memoized(material_lookup or find_material)
    if ring is None:
        ring = drive_ring_parameters(drive, geometry, span_tensions=span_tensions,
                                     material_lookup=lookup)
    model = assembled_parts(drive, geometry, ring, lookup)
    modes = model.torsional.modal()
    w_ref = reference_angular_frequency(modes)
    zs, zw, source = chain_damping(drive, geometry, ring, lookup)
    model = with_chain_dampers(model, zs, zw, w_ref)
    missing = model_completeness(drive)
    if missing and drive.dynamics.require_complete_model:
        raise DesignError("dynamics.require_complete_model", "the dynamic model is incomplete: "
                          + "; ".join(missing) + " (give the [motor] table and what turns with "
                          "every driven sprocket, or set require_complete_model = false)")
    values = {f.name: getattr(model, f.name) for f in fields(model)}
    values.update(span_damping_ratios=zs, damping_source=source,
                  reference_frequency_hz=w_ref / TWO_PI, missing=missing, modes=modes)
    return DriveModel(**values)


def _memoized(lookup: Callable[[str], Material]) -> Callable[[str], Material]:
    """The material lookup with its answers kept (a catalogue search per sprocket is slow)."""
    found: dict[str, Material] = {}

    def get(name: str) -> Material:
        if name not in found:
            found[name] = lookup(name)
        return found[name]

    return get


def ring_model(drive: Drive, geometry: GeometryResult, *, damping: float | None = None,
               span_tensions: Sequence[float] | None = None,
               link_stiffness: float | None = None,
               material_lookup: Callable[[str], Material] | None = None) -> RingModel:
    """The ring of reduced masses of a drive
    (:func:`~chaindrive.dynamics.parameters.drive_ring_parameters`), a second constructor of a
    linear model beside :func:`drive_model`.

    Parameters
    ----------
    drive : Drive
        The drive whose sprockets become the ring's masses.
    geometry : GeometryResult
        The contour its spans run on.
    damping : float or None
        Damping ratio ζ [-] (None: the mean of the spans' ratios the whole-drive model takes,
        :func:`chaindrive.dynamics.model.damping.chain_damping`).
    span_tensions : sequence of float or None
        Tension of every span [N] (None: the static tensions when the drive has a power, see
        :func:`static_span_tensions`).
    link_stiffness : float or None
        Stiffness of one link [N/m] from catalogue data (None: from the plates and pin).
    material_lookup : callable or None
        Name → Material (None: :func:`chaindrive.catalog.find_material`).

    Returns
    -------
    RingModel
        Masses, stiffnesses, damping ratio and sprocket names.
    """
    lookup = material_lookup or find_material
    p = drive_ring_parameters(drive, geometry, span_tensions=span_tensions,
                              link_stiffness=link_stiffness, material_lookup=lookup)
    return RingModel(masses_kg=p.masses_kg, stiffness_n_per_m=p.stiffness_n_per_m, closed=True,
                     damping_ratio=damping if damping is not None else float(
                         np.mean(chain_damping(drive, geometry, p, lookup)[0])),
                     names=tuple(s.name for s in drive.sprockets))
