"""The modal stage of the whole-drive model for an analysis: modes, the spans' transverse
frequencies, the working frequencies, the resonance table and the Campbell data
(docs/dynamics.md §3); :class:`DriveDynamics` is what ``Analysis.dynamics`` returns.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from chaindrive.dynamics.drive_model import DriveModel
from chaindrive.dynamics.modes import DriveModes, StateModes, drive_modes
from chaindrive.dynamics.resonance import (
    CampbellData,
    Resonance,
    WorkingFrequency,
    campbell_data,
    resonance_table,
    working_frequencies,
)
from chaindrive.dynamics.transverse import span_transverse_frequencies
from chaindrive.kinematics import tooth_frequency
from chaindrive.units import TWO_PI

if TYPE_CHECKING:
    from chaindrive.geometry.results import GeometryResult
    from chaindrive.model import Drive

__all__ = ["DriveDynamics", "model_dynamics"]


@dataclass(frozen=True, slots=True, eq=False)
class DriveDynamics:
    """Everything a designer reads about a drive's vibration (JSON ``dynamics``).

    Parameters
    ----------
    model : DriveModel
        The whole-drive model (:class:`~chaindrive.dynamics.drive_model.DriveModel`).
    modal : DriveModes
        Its modes at the sprockets (:class:`~chaindrive.dynamics.modes.DriveModes`).
    state : StateModes
        Its complex elastic modes (with damping).
    span_transverse_hz : ndarray
        (spans, modes) transverse natural frequencies of the spans [Hz] (empty without span
        tensions).
    working : tuple of WorkingFrequency
        The working frequencies (tooth frequencies and their harmonics, shaft speeds).
    resonances : tuple of Resonance
        The resonance table: every working frequency against the nearest natural one.
    campbell : CampbellData or None
        Campbell data over the speed range (None: not computed).
    damping_ratio : float
        Damping ratio ζ of the chain's reference mode [-].
    """

    model: DriveModel
    modal: DriveModes
    state: StateModes
    span_transverse_hz: NDArray[np.float64]
    working: tuple[WorkingFrequency, ...]
    resonances: tuple[Resonance, ...]
    campbell: CampbellData | None
    damping_ratio: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict."""
        m = self.modal.to_dict()
        st = self.span_transverse_hz
        return {
            "model": self.model.to_dict(),
            **{k: m[k] for k in ("natural_frequencies_hz", "natural_frequencies_rad_s",
                                 "damped_frequencies_hz", "modal_damping_ratios",
                                 "rigid_body_modes", "mode_shapes", "normalized_amplitudes",
                                 "governing_elements", "chain_strain_energy_share")},
            "span_transverse_frequencies_hz": st[:, 0].tolist() if st.size else [],
            "span_transverse_modes_hz": st.tolist(),
            "working_frequencies": [w.to_dict() for w in self.working],
            "resonances": [r.to_dict() for r in self.resonances],
            "campbell": None if self.campbell is None else self.campbell.to_dict(),
            "damping_ratio": self.damping_ratio,
        }


def model_dynamics(drive: Drive, geometry: GeometryResult, model: DriveModel, *,
                   harmonics: int = 3, transverse_modes: int = 3,
                   speed_range: tuple[float, float] | None = None,
                   speed_points: int = 61) -> DriveDynamics:
    """Modes, span transverse frequencies, resonance table and Campbell data of a drive.

    Parameters
    ----------
    drive : Drive
        The drive.
    geometry : GeometryResult
        Its contour.
    model : DriveModel
        Its whole-drive model.
    harmonics : int
        Harmonics of the tooth frequency among the working frequencies.
    transverse_modes : int
        Transverse modes per span.
    speed_range : tuple of float | None
        (ω_min, ω_max) of the driver [rad/s] for the Campbell data (None: none).
    speed_points : int
        Speeds of the Campbell data.

    Returns
    -------
    DriveDynamics

    References
    ----------
    [MultimassChainDrives, §3.2–3.3] (working frequencies, resonances); docs/dynamics.md.
    """
    modal, state = drive_modes(model)
    spec = drive.chain.spec
    driver = drive.driver
    teeth = [s.teeth for s in drive.sprockets]
    names = [s.name for s in drive.sprockets]
    lengths = np.array([sp.length for sp in geometry.spans])
    tensions = model.ring.span_tensions_n
    transverse = np.zeros((0, transverse_modes))
    working: tuple[WorkingFrequency, ...] = ()
    rows: tuple[Resonance, ...] = ()
    fz = None
    if driver.speed is not None:
        v = driver.teeth * spec.pitch * driver.speed / TWO_PI
        if tensions is not None:
            transverse = span_transverse_frequencies(lengths, tensions, spec.mass_per_length, v,
                                                     modes=transverse_modes)
        working = working_frequencies(driver.speed, driver.teeth, teeth, names, harmonics)
        fz = float(tooth_frequency(driver.teeth, driver.speed))
    if working:
        rows = resonance_table(modal, working, transverse[:, 0] if transverse.size else None,
                               fz, [f"{sp.start_name}→{sp.end_name}" for sp in geometry.spans])
    campbell = None
    if speed_range is not None:
        speeds = np.linspace(speed_range[0], speed_range[1], speed_points)
        campbell = campbell_data(modal, speeds, driver.teeth, teeth, names, harmonics,
                                 lengths if tensions is not None else None, tensions,
                                 spec.mass_per_length, spec.pitch)
    return DriveDynamics(model, modal, state, transverse, working, rows, campbell,
                         modal.damping_ratio)
