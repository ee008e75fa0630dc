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

import numpy as np
from numpy.typing import ArrayLike

from chaindrive._docstrings import shared_parameters
from chaindrive.dynamics.model.build import drive_model
from chaindrive.dynamics.torsional.engine import (
    FloatArray,
    TorsionalEngine,
    TrainElement,
    nonneg,
    reducer_input_torque,
)
from chaindrive.dynamics.torsional.system import TorsionalSystem
from chaindrive.errors import DesignError
from chaindrive.geometry.contour import contour_geometry
from chaindrive.geometry.results import GeometryResult
from chaindrive.model import Drive

__all__ = ["FloatArray", "TorsionalModel", "TorsionalSystem", "TrainElement",
           "reducer_input_torque"]


_TRAIN_KEYS = frozenset({"name", "inertia", "stiffness", "damping", "ratio", "efficiency",
                         "same_sense", "ground_stiffness", "ground_damping"})


def _per_sprocket(field: str, values: ArrayLike | None, n: int, default: float) -> FloatArray:
    if values is None:
        return np.full(n, default)
    a = np.asarray(values, dtype=float)
    if a.shape != (n,):
        raise DesignError(field, f"need one value per sprocket ({n}), got shape {a.shape}")
    return a


class TorsionalModel(TorsionalEngine):
    """A torsional model of a drive train (see :class:`TorsionalEngine` for the elements and
    the modal analysis), with builders from plain data and from a design."""

    @classmethod
    @shared_parameters
    def from_drive(cls, drive: Drive, geometry: GeometryResult | None = None, *,
                   span_tensions: Sequence[float] | None = None) -> TorsionalEngine:
        """The whole-drive model of a design: its contour with the chain's own mass, the
        teeth, every sprocket's train, the motor and the machines
        (:func:`chaindrive.dynamics.model.build.drive_model`; docs/dynamics.md §1).

        Parameters
        ----------
        %(drive)s
        geometry : GeometryResult | None
            Its contour (None: :func:`chaindrive.geometry.contour.contour_geometry`).
        span_tensions : sequence of float | None
            Static span tensions [N] for the sag stiffness (None: from the drive's loads).

        Returns
        -------
        TorsionalEngine
            The model, built (frozen): its nodes, elements and modal analysis.
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

        Parameters
        ----------
        sprockets : sequence of str
            (n,) sprocket names in ring order; span i joins sprocket i and i+1 (the last one
            closes the ring when ``closed``), as in :class:`~chaindrive.dynamics.RingModel`.
        inertias_kg_m2 : array_like
            (n,) moment of inertia of each sprocket (with its hub) [kg·m²].
        pitch_radii_m : array_like
            (n,) pitch radii R_i [m] (> 0).
        span_stiffness_n_per_m : array_like
            (n,) span stiffnesses c_i [N/m] (0: slack).
        senses : sequence of int | None
            (n,) +1 or −1 [-] for a sprocket wrapped from the inside, which turns the other way
            (its signed radius is −R_i) (None: all +1).
        span_damping_n_s_per_m : array_like | None
            (n,) span dampers [N·s/m] (None: 0).
        trains : mapping | None
            Sprocket name → list of elements outward from the sprocket, each a mapping with
            ``name`` (the new node), ``inertia`` [kg·m²] (default 0) and either ``stiffness``
            [N·m/rad] (+ ``damping`` [N·m·s/rad]): a shaft or coupling from the previous node, or
            ``ratio`` [-] (+ ``efficiency`` [-], ``same_sense``): a gear mesh from the previous node
            (driver) to this one; optional ``ground_stiffness`` [N·m/rad], ``ground_damping``
            [N·m·s/rad].
        chain_mass_per_length_kg_per_m : float
            Chain mass per length q [kg/m] (0: massless chain).
        span_lengths_m : array_like | None
            (n,) span lengths L [m]: each span's mass q·L goes to its two sprockets (needed when
            q > 0).
        wrap_lengths_m : array_like | None
            (n,) length of chain wrapped on each sprocket [m]: those links turn with it (None:
            none).
        closed : bool
            False for an open contour (the last span is left out).
        consistent_mass : bool
            True: each span's mass q·L as the consistent mass of a linear velocity profile along
            it (coupling its two sprockets); False: lumped, split in halves (docs/torsional.md).


        Returns
        -------
        TorsionalEngine
            The model, built (frozen): the sprockets as nodes, the spans, the wrapped links
            and the trains.

        References
        ----------
        [MultimassChainDrives, §3.1] (the ring of sprockets and spans); [Rao2011, ch. 2]
        (consistent mass).
        """
        model = cls()
        names = [str(s) for s in sprockets]
        n = len(names)
        if n < 2 or len(set(names)) != n:
            raise DesignError("sprockets", f"need at least 2 distinct sprocket names, got {names}")
        J = _per_sprocket("inertias_kg_m2", inertias_kg_m2, n, 0.0)
        R = _per_sprocket("pitch_radii_m", pitch_radii_m, n, 0.0)
        c = _per_sprocket("span_stiffness_n_per_m", span_stiffness_n_per_m, n, 0.0)
        d = _per_sprocket("span_damping_n_s_per_m", span_damping_n_s_per_m, n, 0.0)
        s = _per_sprocket("senses", senses, n, 1.0)
        if not (np.all(R > 0) and np.all(np.isfinite(R))):
            raise DesignError("pitch_radii_m", f"must all be finite and > 0, got {R.tolist()}")
        if not np.all(np.abs(s) == 1.0):
            raise DesignError("senses", f"must each be +1 or -1, got {s.tolist()}")
        q = nonneg("chain_mass_per_length_kg_per_m", chain_mass_per_length_kg_per_m, "q [kg/m]")
        span_mass = q * _per_sprocket("span_lengths_m", span_lengths_m, n, 0.0)
        wrap_mass = q * _per_sprocket("wrap_lengths_m", wrap_lengths_m, n, 0.0)
        if q > 0.0 and span_lengths_m is None:
            raise DesignError("span_lengths_m", "a chain mass per length needs the span lengths")
        r = s * R
        for name, j in zip(names, J.tolist(), strict=True):
            model.add_inertia(name, j)
        for i in range(n if closed else n - 1):
            b = (i + 1) % n
            model.add_span(names[i], names[b], c[i], r[i], r[b], damping=d[i], mass=span_mass[i],
                           name=f"span:{names[i]}-{names[b]}", consistent_mass=consistent_mass)
        for name, m, radius in zip(names, wrap_mass.tolist(), R.tolist(), strict=True):
            if m > 0.0:
                model.add_chain_wrap(name, m, radius)
        for sprocket, train in (trains or {}).items():
            if sprocket not in model.node_names:
                raise DesignError(f"trains.{sprocket}", f"unknown sprocket; sprockets: {names}")
            _add_train(model, sprocket, train)
        model.build()
        return model


def _add_train(model: TorsionalEngine, sprocket: str, train: Sequence[TrainElement]) -> None:
    """Adds an open train outward from ``sprocket`` (see
    :meth:`TorsionalModel.from_contour`)."""
    previous = sprocket
    for k, element in enumerate(train):
        field = f"trains.{sprocket}[{k}]"
        unknown = set(element) - _TRAIN_KEYS
        if unknown or "name" not in element:
            raise DesignError(field, f"keys must be among {sorted(_TRAIN_KEYS)} with a 'name', "
                              f"got {sorted(element)}")
        node = str(element["name"])
        if ("stiffness" in element) == ("ratio" in element):
            raise DesignError(field, "give either 'stiffness' (shaft) or 'ratio' (gear mesh)")
        model.add_inertia(node, float(element.get("inertia", 0.0)))
        if "stiffness" in element:
            model.add_shaft(previous, node, float(element["stiffness"]),
                            float(element.get("damping", 0.0)))
        else:
            model.add_gear_mesh(previous, node, float(element["ratio"]),
                                float(element.get("efficiency", 1.0)),
                                bool(element.get("same_sense", False)))
        if "ground_stiffness" in element or "ground_damping" in element:
            model.add_ground_spring(node, float(element.get("ground_stiffness", 0.0)),
                                    float(element.get("ground_damping", 0.0)))
        previous = node
