"""The torsional model of a whole chain drive train: the ring of sprockets (with the chain's
own mass) and an open train of shafts, couplings, gear pairs and machines on every sprocket
(docs/torsional.md). The engine — nodes, elements, gear constraints, condensation, the modal
analysis — is :class:`chaindrive.dynamics.torsional.engine.TorsionalEngine`; this class adds
the builders from plain data and from a design::

    from chaindrive.dynamics import TorsionalModel
    t = TorsionalModel()
    t.add_inertia("motor", 400.0)                    # kg·m²; 0.0 is a massless node
    t.add_shaft("motor", "pinion", 1.88e5)           # N·m/rad
    t.add_gear_mesh("pinion", "wheel", ratio=3.0)    # the wheel turns 3× slower; rigid mesh
    t.add_ground_spring("wheel", 5.0e4)              # N·m/rad to a fixed frame
    modes = t.modal()
    TorsionalModel.from_drive(drive)                 # ring + every sprocket's train
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from numpy.typing import ArrayLike

from chaindrive.dynamics.model.build import drive_model
from chaindrive.dynamics.torsional.build import build_contour
from chaindrive.dynamics.torsional.engine import (
    FloatArray,
    TorsionalEngine,
    TrainElement,
    reducer_input_torque,
)
from chaindrive.dynamics.torsional.system import TorsionalModes, TorsionalSystem
from chaindrive.geometry.contour import contour_geometry
from chaindrive.geometry.results import GeometryResult
from chaindrive.model import Drive

__all__ = ["FloatArray", "TorsionalModel", "TorsionalModes", "TorsionalSystem", "TrainElement",
           "reducer_input_torque"]


class TorsionalModel(TorsionalEngine):
    """A torsional model of a drive train (see :class:`TorsionalEngine` for the elements and
    the modal analysis), with builders from plain data and from a design."""

    @classmethod
    def from_drive(cls, drive: Drive, geometry: GeometryResult | None = None, *,
                   span_tensions: Sequence[float] | None = None) -> TorsionalEngine:
        """The whole-drive model of a design: its contour with the chain's own mass, the
        teeth, every sprocket's train, the motor and the machines
        (:func:`chaindrive.dynamics.model.build.drive_model`; docs/dynamics.md §1).

        Parameters
        ----------
        drive : Drive
            The design.
        geometry : GeometryResult | None
            Its contour (None: :func:`chaindrive.geometry.contour.contour_geometry`).
        span_tensions : sequence of float | None
            Static span tensions [N] for the sag stiffness (None: from the drive's loads).

        Returns
        -------
        TorsionalEngine
            The model (its nodes, elements and modal analysis).
        """
        return drive_model(drive, geometry or contour_geometry(drive),
                           span_tensions=span_tensions).torsional

    @classmethod
    def from_contour(cls, sprockets: Sequence[str], inertias_kg_m2: ArrayLike,
                     pitch_radii_m: ArrayLike, span_stiffness_n_per_m: ArrayLike, *,
                     senses: Sequence[int] | None = None,
                     span_damping_n_s_per_m: ArrayLike | None = None,
                     trains: Mapping[str, Sequence[TrainElement]] | None = None,
                     chain_mass_per_length_kg_per_m: float = 0.0,
                     span_lengths_m: ArrayLike | None = None,
                     wrap_lengths_m: ArrayLike | None = None,
                     closed: bool = True, consistent_mass: bool = False) -> TorsionalEngine:
        """The model of a chain contour with a train on any sprocket, from plain data.

        The parameters are those of :func:`chaindrive.dynamics.torsional.build.build_contour`
        (which does the work) without its first, ``model``: this builds into a new model.

        Returns
        -------
        TorsionalEngine
            The model: the sprockets as nodes, the spans, the wrapped links and the trains.

        References
        ----------
        [MultimassChainDrives, §3.1] (the ring of sprockets and spans); [Rao2011, ch. 2]
        (consistent mass).
        """
        return build_contour(cls(), sprockets, inertias_kg_m2, pitch_radii_m,
                             span_stiffness_n_per_m, senses=senses,
                             span_damping_n_s_per_m=span_damping_n_s_per_m, trains=trains,
                             chain_mass_per_length_kg_per_m=chain_mass_per_length_kg_per_m,
                             span_lengths_m=span_lengths_m, wrap_lengths_m=wrap_lengths_m,
                             closed=closed, consistent_mass=consistent_mass)
