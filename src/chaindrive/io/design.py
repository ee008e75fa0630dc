"""Design files: TOML ↔ :class:`~chaindrive.model.Drive`, and the schema of every field.

Every dimensional value in a design file is a string with a unit (``"25.4 mm"``,
``"300 rpm"``), parsed with pint here and nowhere else; inside the package everything is SI.
A mistake gives one :class:`~chaindrive.errors.DesignError` line that names the field,
the value and what is allowed.
"""

from __future__ import annotations

import math
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import tomli_w

from chaindrive.errors import DesignError, did_you_mean
from chaindrive.model import (
    MAX_CONTOURS,
    MAX_SPROCKETS,
    MAX_TEETH,
    MIN_SPROCKETS,
    MIN_TEETH,
    MOTORS,
    RESISTANCES,
    ROLES,
    ROUNDINGS,
    SIDES,
    TOOTH_FORMS,
    Chain,
    ChainRequest,
    ChainSpec,
    Drive,
    DynamicsSettings,
    Sprocket,
)
from chaindrive.units import DIMENSIONS, parse_quantity


@dataclass(frozen=True, slots=True)
class Field:
    """One field of a design file: its kind, unit, default, allowed range and meaning.

    kind: a dimension of :data:`chaindrive.units.DIMENSIONS` (value is a string with a
    unit), or ``"int"``, ``"float"``, ``"str"``, ``"bool"``, ``"choice"``, ``"links"`` (a
    whole number or a rounding rule of :data:`chaindrive.model.ROUNDINGS`).
    """

    name: str
    kind: str
    description: str
    required: bool = False
    default: Any = None
    minimum: float | None = None
    maximum: float | None = None
    choices: tuple[str, ...] = ()
    exclusive_minimum: bool = False

    def allowed(self) -> str:
        """Human description of the allowed values."""
        if self.kind == "choice":
            return "one of " + ", ".join(f'"{c}"' for c in self.choices)
        if self.kind == "bool":
            return "true or false"
        if self.kind == "str":
            return "text"
        lo = "" if self.minimum is None else (f"> {self.minimum:g}" if self.exclusive_minimum
                                               else f"≥ {self.minimum:g}")
        hi = "" if self.maximum is None else f"≤ {self.maximum:g}"
        span = " and ".join(x for x in (lo, hi) if x)
        if self.kind == "links":
            return (f'a whole number from {self.minimum:g} to {self.maximum:g}, '
                    '"round up" or "round down"')
        if self.kind == "int":
            if self.minimum is not None and self.maximum is not None:
                return f"a whole number from {self.minimum:g} to {self.maximum:g}"
            return "a whole number" + (f" {span}" if span else "")
        if self.kind == "float":
            return "a number" + (f" {span}" if span else "")
        unit = DIMENSIONS[self.kind][2]
        return f'a {self.kind.replace("_", " ")} with a unit such as "{unit}"' + (
            f", {span} (SI)" if span else "")


DRIVE_FIELDS: tuple[Field, ...] = (
    Field("name", "str", "name of the drive", required=True),
    Field("power", "power", "power transmitted from the driver", minimum=0,
          exclusive_minimum=True),
    Field("tooth_form", "choice", "sprocket tooth form (default: GOST 591 for GOST chains, "
          "ISO 606 otherwise)", choices=TOOTH_FORMS),
    Field("service_factor", "float", "service (application) factor of the drive", minimum=1.0,
          maximum=5.0),
)
CHAIN_FIELDS: tuple[Field, ...] = (
    Field("designation", "str", 'catalogue designation, e.g. "ISO 606 16B-1", "ANSI 80", '
          '"GOST 13568 ПР-25,4-60"'),
    Field("standard", "choice", "chain standard, used with pitch when no designation is given",
          choices=("ISO 606", "ANSI", "GOST 13568", "polymer")),
    Field("series", "choice", "series: ISO 606 A or B, ANSI heavy H", choices=("A", "B", "H")),
    Field("pitch", "length", "chain pitch, used with standard when no designation is given",
          minimum=0, exclusive_minimum=True),
    Field("strands", "int", "number of strands (rows)", default=1, minimum=1, maximum=8),
    Field("links", "links", 'impose the number of links (the take-up fits it), or how the '
          'tight length is rounded to an even count: "round up" (default) or "round down"',
          minimum=4, maximum=10000),
    Field("sag", "float", "installed sag of the slack span as a fraction of its length "
          "(default: laid out tight)", minimum=0.0, maximum=0.1, exclusive_minimum=True),
    Field("allow_odd", "bool", "allow an odd number of links (needs an offset link)",
          default=False),
    Field("contours", "int", "identical chain contours side by side on common shafts (seed 004)",
          default=1, minimum=1, maximum=MAX_CONTOURS),
    Field("catalog", "str", "a catalogue file of your own (CSV or TOML), relative to the design"),
)
SPROCKET_FIELDS: tuple[Field, ...] = (
    Field("name", "str", "unique name of the sprocket", required=True),
    Field("teeth", "int", "number of teeth", required=True, minimum=MIN_TEETH, maximum=MAX_TEETH),
    Field("x", "length", "x of the centre", required=True),
    Field("y", "length", "y of the centre", required=True),
    Field("role", "choice", "driver, driven or idler", default="driven", choices=ROLES),
    Field("speed", "speed", "rotational speed (driver only)", minimum=0, exclusive_minimum=True),
    Field("side", "choice", "outside: the chain wraps round it; inside: the chain wraps it from "
          "outside the loop (it turns the other way)", default="outside", choices=SIDES),
    Field("adjustable", "bool", "this sprocket moves to take up the chain length", default=False),
    Field("adjust_angle", "angle", "direction of the line of adjustment (default: away from "
          "the contour)"),
    Field("inertia", "inertia", "moment of inertia of everything turning with it", minimum=0,
          exclusive_minimum=True),
    Field("flywheel", "inertia", "inertia added as a steel flywheel on the shaft (in the "
          "dynamics, the mass and the cost)", default=0.0, minimum=0.0),
    Field("material", "str", "sprocket material (catalogue name)", default="steel"),
    Field("power_share", "float", "share of the power taken off here (driven sprockets)",
          minimum=0.0, maximum=1.0),
)
DYNAMICS_FIELDS: tuple[Field, ...] = (
    Field("damping_ratio", "float", "damping ratio ζ of the ring (seed 000: D = 0.06)",
          default=0.06, minimum=0.0, maximum=0.9),
    Field("harmonics", "int", "harmonics of the tooth frequency in the polygonal excitation",
          default=10, minimum=1, maximum=50),
    Field("transient", "bool", "run the start-up transient", default=True),
    Field("startup_duration", "time", "simulated time of the start-up", default=1.0,
          minimum=0.0, maximum=60.0, exclusive_minimum=True),
    Field("motor", "choice", "motor law on the driver: induction motor (Kloss), constant "
          "torque or soft-start ramp", default="kloss", choices=MOTORS),
    Field("breakdown_ratio", "float", "Kloss motor: breakdown torque / rated torque",
          default=2.5, minimum=1.0, maximum=5.0, exclusive_minimum=True),
    Field("critical_slip", "float", "Kloss motor: critical slip", default=0.25, minimum=0.0,
          maximum=1.0, exclusive_minimum=True),
    Field("ramp_time", "time", "ramp motor: time to full torque", default=0.5, minimum=0.0,
          exclusive_minimum=True),
    Field("resistance", "choice", "resistance law on the driven sprockets", default="linear",
          choices=RESISTANCES),
    Field("eccentricity", "length", "eccentricity of every sprocket (disturbance once per "
          "revolution)", default=0.0, minimum=0.0),
    Field("pitch_scatter", "length", "scatter (standard deviation) of the link pitches",
          default=0.0, minimum=0.0),
    Field("accumulated_error", "length", "accumulated error of the chain length", default=0.0,
          minimum=0.0),
)
#: ``[uncertainty]``: what scatters in a built drive and how far its chain wears, read by
#: :mod:`chaindrive.robust` (defaults from the standards, sources in docs/robust.md).
UNCERTAINTY_FIELDS: tuple[Field, ...] = (
    Field("samples", "int", "quasi-Monte Carlo samples of the probabilities (Sobol points, a "
          "power of two per replicate)", default=256, minimum=8, maximum=1 << 20),
    Field("replicates", "int", "independent scramblings of the Sobol points (the spread gives "
          "the confidence interval)", default=8, minimum=2, maximum=64),
    Field("seed", "int", "random seed of the scrambling (same seed, same samples)", default=0,
          minimum=0, maximum=2**31 - 1),
    Field("confidence", "float", "confidence level of the intervals", default=0.95,
          minimum=0.5, maximum=0.999),
    Field("wear", "choice", "wear state of the chain: new, worn to the allowable elongation, "
          "or life (uniform from new to worn)", default="life", choices=("new", "worn", "life")),
    Field("smooth_running", "bool", "the drive must run smoothly: allowable elongation 1.5 % "
          "(Diamond Chain)", default=False),
    Field("allowable_elongation", "float", "wear elongation at which the chain is replaced "
          "(default: 3 %, 200/z % for a large sprocket, 1.5 % for fixed centres or parallel "
          "chains)", minimum=0.0, maximum=0.1, exclusive_minimum=True),
    Field("chain_length_tolerance", "float", "length tolerance of a new chain, 0 to this "
          "fraction (ISO 606: +0.15 %)", default=0.0015, minimum=0.0, maximum=0.05),
    Field("eccentricity", "length", "largest eccentricity of every sprocket (default: half the "
          "ASME B29.1 commercial runout by root diameter)", minimum=0.0),
    Field("centre_distance_tolerance", "length", "± position tolerance of every shaft "
          "(default: ±1 mm up to 1 m from the driver, ±a/1000 beyond)", minimum=0.0),
    Field("key_fit", "choice", "keyway fit of the keyed sprockets of parallel contours "
          "([Lyashuk])", default="normal", choices=("tight", "normal", "free")),
    Field("inertia_scatter", "float", "± relative scatter of every reduced inertia (uniform)",
          default=0.10, minimum=0.0, maximum=0.5),
    Field("stiffness_scatter", "float", "± relative scatter of the chain stiffness (uniform)",
          default=0.10, minimum=0.0, maximum=0.5),
    Field("temperature_min", "float", "lowest operating temperature of polymer parts, °C",
          default=23.0, minimum=-60.0, maximum=150.0),
    Field("temperature_max", "float", "highest operating temperature of polymer parts, °C",
          default=23.0, minimum=-60.0, maximum=150.0),
    Field("take_up_capacity", "length", "chain length the take-up can absorb (default: two "
          "pitches, Diamond Chain)", minimum=0.0, exclusive_minimum=True),
    Field("wear_states", "int", "wear states of the batched modal path over the life "
          "(midpoint rule in the life fraction)", default=8, minimum=1, maximum=64),
    Field("sensitivity_samples", "int", "base samples N of the Sobol sensitivity indices "
          "(N·(groups + 2) evaluations)", default=32, minimum=4, maximum=1 << 16),
)
SECTIONS: dict[str, tuple[Field, ...]] = {
    "drive": DRIVE_FIELDS,
    "chain": CHAIN_FIELDS,
    "sprockets": SPROCKET_FIELDS,
    "dynamics": DYNAMICS_FIELDS,
    "uncertainty": UNCERTAINTY_FIELDS,
}


#: Sections read by other parts of chaindrive, not by the drive loader: ``[optimize]``
#: (the synthesis problem, :mod:`chaindrive.synthesis`).
OTHER_SECTIONS: tuple[str, ...] = ("optimize",)


def schema() -> dict[str, list[dict[str, Any]]]:
    """Every field of a design file with its kind, unit, default and allowed values."""
    out: dict[str, list[dict[str, Any]]] = {}
    for section, fields in SECTIONS.items():
        out[section] = [
            {
                "field": f.name,
                "kind": f.kind,
                "si_unit": DIMENSIONS[f.kind][1] if f.kind in DIMENSIONS else "",
                "example": DIMENSIONS[f.kind][2] if f.kind in DIMENSIONS else "",
                "required": f.required,
                "default": f.default,
                "allowed": f.allowed(),
                "description": f.description,
            }
            for f in fields
        ]
    return out


def _number_text(value: Any) -> str:
    return repr(value) if isinstance(value, str) else str(value)


def _check_range(f: Field, path: str, value: float, shown: Any) -> None:
    low_bad = f.minimum is not None and (value <= f.minimum if f.exclusive_minimum
                                         else value < f.minimum)
    high_bad = f.maximum is not None and value > f.maximum
    if low_bad or high_bad or not math.isfinite(value):
        raise DesignError(path, f"must be {f.allowed()}, got {_number_text(shown)}")


def parse_field(f: Field, value: Any, path: str) -> Any:
    """Check and convert one value of a design file (SI for quantities)."""
    if f.kind == "str":
        if not isinstance(value, str) or not value.strip():
            raise DesignError(path, f"must be non-empty text, got {value!r}")
        return value.strip()
    if f.kind == "bool":
        if not isinstance(value, bool):
            raise DesignError(path, f"must be true or false, got {value!r}")
        return value
    if f.kind == "choice":
        if value not in f.choices:
            raise DesignError(path, f"must be {f.allowed()}, got {value!r}"
                              + did_you_mean(str(value), f.choices))
        return value
    if f.kind == "links" and isinstance(value, str):
        if value not in ROUNDINGS:
            raise DesignError(path, f'must be a whole number, "round up" or "round down", '
                              f"got {value!r}" + did_you_mean(value, ROUNDINGS))
        return value
    if f.kind in ("int", "links"):
        if isinstance(value, bool) or not isinstance(value, int):
            raise DesignError(path, f"must be {f.allowed()}, got {_number_text(value)}")
        _check_range(f, path, value, value)
        return value
    if f.kind == "float":
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise DesignError(path, f"must be {f.allowed()}, got {_number_text(value)}")
        _check_range(f, path, float(value), value)
        return float(value)
    si = parse_quantity(value, f.kind, path)
    _check_range(f, path, si, value)
    return si


def parse_section(data: Any, fields: tuple[Field, ...], path: str) -> dict[str, Any]:
    """Check a TOML table against its fields: unknown names, required ones, values."""
    if not isinstance(data, Mapping):
        raise DesignError(path, f"must be a table, got {type(data).__name__}")
    known = {f.name: f for f in fields}
    for key in data:
        if key not in known:
            raise DesignError(f"{path}.{key}", "unknown field" + did_you_mean(key, known)
                              + f" (known: {', '.join(known)})")
    out: dict[str, Any] = {}
    for f in fields:
        if f.name in data:
            out[f.name] = parse_field(f, data[f.name], f"{path}.{f.name}")
        elif f.required:
            raise DesignError(f"{path}.{f.name}", f"is required ({f.allowed()})")
        else:
            out[f.name] = f.default
    return out


_STRANDS_SUFFIX = re.compile(r"-(\d)$")


def resolve_chain(values: dict[str, Any], base_dir: Path | None
                  ) -> tuple[ChainSpec, ChainRequest | None]:
    """The catalogue chain named by the [chain] table (designation, or standard + pitch), or
    — when only a standard is given — a provisional chain of that family and the request
    that :func:`chaindrive.analyze` selects from."""
    from chaindrive import catalog

    extra: tuple[Path, ...] = ()
    if values["catalog"]:
        path = Path(values["catalog"])
        if base_dir is not None and not path.is_absolute():
            path = base_dir / path
        if not path.is_file():
            raise DesignError("chain.catalog", f"no such file: {str(path)!r}")
        extra = (path,)
    strands = values["strands"]
    designation = values["designation"]
    if designation:
        spec = catalog.find_chain(designation, extra_files=extra)
        if spec.strands != strands:
            explicit = _STRANDS_SUFFIX.search(designation.strip()) or designation.strip()[0] in "234"
            if explicit and strands != 1:
                raise DesignError("chain.strands", f"{strands} contradicts the designation "
                                  f"{designation!r} ({spec.strands} strands)")
            if strands != 1:
                spec = _with_strands(spec, strands, extra)
        return spec, None
    if values["standard"] is None:
        raise DesignError("chain.designation", "give a designation, or a standard (and a pitch)")
    if values["pitch"] is None:
        family = [c for c in catalog.chains(extra) if c.standard == values["standard"]
                  and (values["series"] is None or c.series == values["series"])]
        if not family:
            raise DesignError("chain.series", f"no {values['standard']} chains of series "
                              f"{values['series']!r} in the catalogue")
        request = ChainRequest(values["standard"], values["series"], values["strands_given"])
        return min(family, key=lambda c: c.breaking_load), request
    found = [c for c in catalog.chains_by_pitch(values["pitch"], values["standard"])
             if c.strands == strands and (values["series"] is None
                                          or c.series == values["series"])]
    if not found:
        raise DesignError("chain.pitch", f"no {values['standard']} chain of pitch "
                          f"{values['pitch'] * 1e3:g} mm with {strands} strand(s) in the catalogue")
    return min(found, key=lambda c: c.breaking_load), None


def _with_strands(spec: ChainSpec, strands: int, extra: tuple[Path, ...]) -> ChainSpec:
    """The same chain with another number of strands, from the catalogue."""
    from chaindrive import catalog

    same = [c for c in catalog.chains(extra) if c.pitch == spec.pitch and c.series == spec.series
            and c.standard == spec.standard and c.strands == strands
            and abs(c.roller_diameter - spec.roller_diameter) < 1e-9]
    if not same:
        raise DesignError("chain.strands", f"no {strands}-strand version of {spec.designation} "
                          "in the catalogue")
    return same[0]


def drive_from_mapping(data: Mapping[str, Any], base_dir: Path | None = None) -> Drive:
    """Build a validated :class:`Drive` from the parsed TOML of a design file."""
    known = (*SECTIONS, *OTHER_SECTIONS)
    for key in data:
        if key not in known:
            raise DesignError(key, "unknown section" + did_you_mean(key, known)
                              + f" (known: {', '.join(known)})")
    drive_values = parse_section(data.get("drive", {}), DRIVE_FIELDS, "drive")
    parse_section(data.get("uncertainty", {}), UNCERTAINTY_FIELDS, "uncertainty")  # read by robust
    dynamics = DynamicsSettings(**parse_section(data.get("dynamics", {}), DYNAMICS_FIELDS,
                                                "dynamics"))
    chain_values = parse_section(data.get("chain", {}), CHAIN_FIELDS, "chain")
    raw_sprockets = data.get("sprockets")
    if raw_sprockets is None:
        raise DesignError("sprockets", "is required: list the sprockets as [[sprockets]] tables")
    if not isinstance(raw_sprockets, list):
        raise DesignError("sprockets", "must be a list of [[sprockets]] tables")
    n = len(raw_sprockets)
    if not MIN_SPROCKETS <= n <= MAX_SPROCKETS:
        raise DesignError("sprockets", f"a contour needs {MIN_SPROCKETS} to {MAX_SPROCKETS} "
                          f"sprockets, got {n}")
    sprockets = []
    seen: dict[str, int] = {}
    for i, raw in enumerate(raw_sprockets):
        v = parse_section(raw, SPROCKET_FIELDS, f"sprockets[{i}]")
        if v["name"] in seen:
            raise DesignError(f"sprockets[{i}].name", f"duplicate name {v['name']!r} (also "
                              f"sprockets[{seen[v['name']]}]); names must be unique")
        seen[v["name"]] = i
        if v["speed"] is not None and v["role"] != "driver":
            raise DesignError(f"sprockets[{i}].speed", "give the speed on the driver only "
                              f"(this one is {v['role']})")
        sprockets.append(Sprocket(**v))
    drivers = [i for i, s in enumerate(sprockets) if s.role == "driver"]
    if len(drivers) != 1:
        shown = ", ".join(f"sprockets[{i}]" for i in drivers) or "none"
        raise DesignError("sprockets.role", f"exactly one sprocket must be the driver, got "
                          f"{len(drivers)} ({shown})")
    if sprockets[drivers[0]].speed is None:
        raise DesignError(f"sprockets[{drivers[0]}].speed", 'the driver needs a speed such as '
                          '"300 rpm"')
    chain_values["strands_given"] = (data.get("chain") or {}).get("strands")
    spec, request = resolve_chain(chain_values, base_dir)
    if request is not None and drive_values["power"] is None:
        raise DesignError("drive.power", "is required when the design names no chain "
                          "(the chain is selected for the power)")
    tooth_form = drive_values["tooth_form"] or ("GOST 591" if spec.standard == "GOST 13568"
                                                else "ISO 606")
    links = chain_values["links"]
    chain = Chain(spec, links=links if not isinstance(links, str) else None,
                  allow_odd=chain_values["allow_odd"], request=request,
                  contours=chain_values["contours"],
                  rounding=links if isinstance(links, str) else "round up",
                  sag=chain_values["sag"])
    return Drive(name=drive_values["name"], chain=chain, sprockets=tuple(sprockets),
                 power=drive_values["power"], tooth_form=tooth_form,
                 service_factor=drive_values["service_factor"], dynamics=dynamics)


def parse_toml(text: str, name: str) -> dict[str, Any]:
    """The mapping of a TOML text; a syntax error is one :class:`DesignError` naming ``name``."""
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DesignError(name, f"TOML syntax error: {exc}") from None


def read_toml(path: str | Path, what: str = "design file") -> dict[str, Any]:
    """The mapping of a TOML file; a missing, unreadable or malformed file is one
    :class:`DesignError` naming it (``what`` says what kind of file was expected)."""
    p = Path(path)
    if not p.is_file():
        raise DesignError(str(path), f"no such {what}")
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise DesignError(str(path), f"cannot read the file ({exc.__class__.__name__})") from None
    return parse_toml(text, str(path))


def load_drive(path: str | Path) -> Drive:
    """Read and validate a TOML design file."""
    return drive_from_mapping(read_toml(path), base_dir=Path(path).parent)


def _q(value: float, factor: float, unit: str) -> str:
    """A quantity as the design file writes it: SI value × factor in ``unit``, 12 significant
    digits (re-read to 1e-12 relative)."""
    return f"{value * factor:.12g} {unit}"


def drive_to_mapping(drive: Drive) -> dict[str, Any]:
    """The tables of a design file of ``drive`` (lengths in mm, speeds in rpm): what
    :func:`drive_from_mapping` reads back to the same drive. A chain that was selected is
    written by its designation."""
    chain: dict[str, Any] = {"designation": drive.chain.spec.designation}
    if drive.chain.links is not None:
        chain["links"] = drive.chain.links
    elif drive.chain.rounding != "round up":
        chain["links"] = drive.chain.rounding
    if drive.chain.sag is not None:
        chain["sag"] = drive.chain.sag
    if drive.chain.allow_odd:
        chain["allow_odd"] = True
    if drive.chain.contours != 1:
        chain["contours"] = drive.chain.contours
    head: dict[str, Any] = {"name": drive.name}
    if drive.power is not None:
        head["power"] = _q(drive.power, 1e-3, "kW")
    head["tooth_form"] = drive.tooth_form
    if drive.service_factor is not None:
        head["service_factor"] = drive.service_factor
    return {"drive": head, "chain": chain,
            "sprockets": [_sprocket_table(s) for s in drive.sprockets],
            "dynamics": _dynamics_table(drive.dynamics)}


def _sprocket_table(s: Sprocket) -> dict[str, Any]:
    t: dict[str, Any] = {"name": s.name, "teeth": s.teeth, "x": _q(s.x, 1e3, "mm"),
                         "y": _q(s.y, 1e3, "mm"), "role": s.role}
    if s.speed is not None:
        t["speed"] = _q(s.speed, 30.0 / math.pi, "rpm")
    if s.side != "outside":
        t["side"] = s.side
    if s.adjustable:
        t["adjustable"] = True
    if s.adjust_angle is not None:
        t["adjust_angle"] = _q(s.adjust_angle, 180.0 / math.pi, "deg")
    if s.inertia is not None:
        t["inertia"] = _q(s.inertia, 1.0, "kg*m^2")
    if s.flywheel:
        t["flywheel"] = _q(s.flywheel, 1.0, "kg*m^2")
    if s.material != "steel":
        t["material"] = s.material
    if s.power_share is not None:
        t["power_share"] = s.power_share
    return t


def _dynamics_table(d: DynamicsSettings) -> dict[str, Any]:
    units = {"startup_duration": (1.0, "s"), "ramp_time": (1.0, "s"),
             "eccentricity": (1e3, "mm"), "pitch_scatter": (1e3, "mm"),
             "accumulated_error": (1e3, "mm")}
    out: dict[str, Any] = {}
    for f in DYNAMICS_FIELDS:
        value = getattr(d, f.name)
        out[f.name] = _q(value, *units[f.name]) if f.name in units else value
    return out


def drive_to_toml(drive: Drive) -> str:
    """A design file of ``drive`` (TOML written by tomli-w from :func:`drive_to_mapping`)."""
    return tomli_w.dumps(drive_to_mapping(drive))
