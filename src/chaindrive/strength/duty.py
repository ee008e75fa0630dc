"""Duty of a drive: the service factor from the driver's and the driven machine's shock
classes, and the required wear life.

Every manufacturer's selector multiplies the transmitted power by a service (application)
factor K_s read from a grid of driver class × driven-machine class. A design file names the
two classes (``[drive] driver``, ``driven``); the factor comes from the table of the rating
method that checks the chain (:func:`chaindrive.strength.ratings.method_for`):

* ACA (ISO 606 A, ANSI and chains of another family), the ISO 606 B table and polymer chains:
  the 3 × 3 grid of [Mott2014, Table 7-17] (the ANSI/ACA practice; [Tsubaki, Table 4.2]
  prints the same numbers). The application-factor table f1 of [ISO10823] itself was not
  available: no value here is labelled as the ISO table. The driver classes map onto the
  grid's columns as

  ============== =========================================
  driver class   column of the grid
  ============== =========================================
  smooth         electric motor or turbine
  slight shock   internal-combustion engine, hydraulic drive
  moderate shock internal-combustion engine, mechanical drive
  ============== =========================================

  and the driven classes onto its rows (smooth, moderate shock, heavy shock);
* Kэ (GOST 13568): the dynamic-load factor kд of the operating coefficient
  Kэ = kд·kа·kн·kрег·kсм·kреж by the character of the load — 1.0 calm, 1.35 with shocks
  (the textbooks give 1.2…1.5, the programs that reproduce them use 1.35), 1.8 heavy
  shocks [ChainDesignRU, §1]. The driver class does not enter kд; the other factors of Kэ
  are not modelled (the design's service factor stands for the whole Kэ).

``service_factor`` in the design overrides the classes. With neither, the factor is 1.0 — a
default, said as a warning on every output (:func:`duty_warnings`).

The example machines of each class (:data:`DRIVER_EXAMPLES`, :data:`DRIVEN_EXAMPLES`) are
those of the sources: the driver columns of [Mott2014, Table 7-17] and [Tsubaki, Table 4.2],
the driven machines of the German Betriebsfaktor classes 1.0 / 1.5 / 2.0 [InggoBetriebsfaktor]
(the same three load classes).
"""

from __future__ import annotations

from dataclasses import dataclass

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import ChainDriveWarning
from chaindrive.model import DRIVEN_DUTIES, DRIVER_DUTIES, ChainSpec, Drive
from chaindrive.strength import iso10823, ke_method, ratings

__all__ = ["DRIVEN_EXAMPLES", "DRIVER_COLUMNS", "DRIVER_EXAMPLES", "SECONDS_PER_HOUR",
           "ServiceFactor", "duty_warnings", "required_life_h", "service_factor_for",
           "table_for"]

SECONDS_PER_HOUR = 3600.0
#: Column of the service-factor grid of [Mott2014, Table 7-17] / [Tsubaki, Table 4.2] for
#: each driver class (the keys of ``strength/data/iso10823.toml`` [service_factor]).
DRIVER_COLUMNS: dict[str, str] = {"smooth": "electric_motor",
                                  "slight shock": "ic_engine_hydraulic",
                                  "moderate shock": "ic_engine_mechanical"}
#: Row of that grid for each driven class.
DRIVEN_ROWS: dict[str, str] = {"smooth": "smooth", "moderate shock": "moderate_shock",
                               "heavy shock": "heavy_shock"}
#: kд of the Kэ method for each driven class (``strength/data/ke_method.toml``).
DRIVEN_KD: dict[str, str] = {"smooth": "calm", "moderate shock": "shocks",
                             "heavy shock": "heavy_shocks"}
#: Example drivers of each class ([Mott2014, Table 7-17]; [Tsubaki, Table 4.2]).
DRIVER_EXAMPLES: dict[str, str] = {
    "smooth": "electric motor, turbine",
    "slight shock": "internal-combustion engine with a hydraulic coupling or drive",
    "moderate shock": "internal-combustion engine with a mechanical coupling",
}
#: Example driven machines of each class [InggoBetriebsfaktor].
DRIVEN_EXAMPLES: dict[str, str] = {
    "smooth": "uniformly loaded conveyors, centrifugal pumps and compressors, liquid "
              "agitators, printing machines, main drives of machine tools",
    "moderate shock": "non-uniformly loaded conveyors, concrete mixers, ball mills, "
                      "three-cylinder piston pumps and compressors, presses and shears, "
                      "cranes and lifts, winches, vibrating screens",
    "heavy shock": "excavators and construction machines, hammer mills, one- and "
                   "two-cylinder piston pumps and compressors, roll crushers, rubber "
                   "machinery, oil-drilling rigs, brick machines",
}
assert tuple(DRIVER_COLUMNS) == DRIVER_DUTIES and tuple(DRIVEN_ROWS) == DRIVEN_DUTIES

_GRID = "[Mott2014, Table 7-17] ([Tsubaki, Table 4.2] agrees)"
_KD = "kд of the Kэ method [ChainDesignRU, §1]"


@dataclass(frozen=True, slots=True)
class ServiceFactor:
    """The service factor a drive is checked with, and where it comes from.

    Parameters
    ----------
    value : float
        K_s [-].
    origin : {"given", "duty classes", "default"}
        ``[drive] service_factor``; the duty classes ``[drive] driver`` / ``driven``; or
        neither (1.0).
    table : str
        The table the classes were read in (empty unless from the classes).
    note : str
        What the value rests on, in words.
    """

    value: float
    origin: str
    table: str = ""
    note: str = ""


def table_for(spec: ChainSpec) -> str:
    """The service-factor table of the method that checks a chain (module docstring).

    Parameters
    ----------
    spec : ChainSpec
        The chain.

    Returns
    -------
    str
        The table's reference.
    """
    return _KD if ratings.method_for(spec) == ratings.KE else _GRID


def _from_classes(driver: str, driven: str, spec: ChainSpec) -> float:
    """K_s of the two classes in the table of the chain's method (module docstring)."""
    if ratings.method_for(spec) == ratings.KE:
        return float(ke_method.data()["factors"]["dynamic"][DRIVEN_KD[driven]])
    return iso10823.service_factor(DRIVEN_ROWS[driven], DRIVER_COLUMNS[driver])


@shared_parameters
def service_factor_for(drive: Drive, spec: ChainSpec | None = None) -> ServiceFactor:
    """The service factor of a drive: given, from its duty classes, or the default 1.0.

    A class left out while the other is given is taken as "smooth" (and said so).

    Parameters
    ----------
    %(drive)s
    spec : ChainSpec or None
        The chain whose method's table is read (None: the design's chain).

    Returns
    -------
    ServiceFactor
        K_s with its origin and table.

    References
    ----------
    [Mott2014, Table 7-17]; [Tsubaki, Table 4.2]; [ChainDesignRU, §1] (kд).
    """
    if drive.service_factor is not None:
        return ServiceFactor(drive.service_factor, "given", note="[drive] service_factor")
    if drive.driver_duty is None and drive.driven_duty is None:
        return ServiceFactor(1.0, "default", note="no [drive] driver / driven duty classes "
                             "and no service_factor given: 1.0 assumed")
    spec = spec or drive.chain.spec
    driver = drive.driver_duty or "smooth"
    driven = drive.driven_duty or "smooth"
    assumed = [f"{k} \"smooth\" assumed" for k, v in (("driver", drive.driver_duty),
                                                      ("driven", drive.driven_duty)) if v is None]
    table = table_for(spec)
    note = (f"driver {driver}, driven {driven}: {table}"
            + (f" ({'; '.join(assumed)})" if assumed else ""))
    return ServiceFactor(_from_classes(driver, driven, spec), "duty classes", table, note)


@shared_parameters
def required_life_h(drive: Drive) -> float | None:
    """The required wear life of the design in hours (None: the rating method's basis).

    %(drive_returns)s
    float or None
        ``[drive] required_life`` [h], or None when it is not given.
    """
    return None if drive.required_life is None else drive.required_life / SECONDS_PER_HOUR


@shared_parameters
def duty_warnings(drive: Drive) -> list[ChainDriveWarning]:
    """Say when the service factor is the default 1.0 or a class was assumed.

    %(drive_returns)s
    list of ChainDriveWarning
        One warning when the factor rests on a default, none otherwise.
    """
    if drive.power is None:
        return []
    sf = service_factor_for(drive)
    if sf.origin == "default":
        return [ChainDriveWarning(
            "duty.service-factor-default", "drive.service_factor",
            "service factor 1.0 (default): no duty given — set [drive] driver and driven "
            "(duty classes, see `chaindrive schema`) or service_factor; the rating, wear-life "
            "and allowable-load checks assume a smooth motor on a smooth machine")]
    if sf.origin == "duty classes" and (drive.driver_duty is None or drive.driven_duty is None):
        missing = "driver" if drive.driver_duty is None else "driven"
        return [ChainDriveWarning(
            "duty.class-assumed", f"drive.{missing}",
            f"service factor {sf.value:g} from the duty classes with [drive] {missing} not "
            f"given (\"smooth\" assumed): {sf.note}")]
    return []
