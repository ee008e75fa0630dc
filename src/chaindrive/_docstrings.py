"""The numpydoc parameter entries many docstrings share, written once.

A docstring names a shared entry by a line that holds only ``%(name)s``; the decorator
:func:`shared_parameters` replaces that line, when the module is imported, by the entry of
:data:`PARAMETERS` of that name, indented as the line was. The idea is SciPy's
``scipy._lib.doccer`` and pandas' ``@doc``, kept to whole lines: a ``%`` anywhere else in a
docstring is left alone, and an unknown name fails at import (KeyError), never silently.
``help()``, :func:`inspect.getdoc`, numpydoc and the docstring tests read the expanded text.

Put the decorator directly above ``def`` (under ``@property`` or ``@staticmethod``, which
copy the docstring when they wrap the function) and above ``@dataclass`` on a class (which,
with ``slots=True``, makes a new class)::

    @shared_parameters
    def loads_of(drive: Drive, geometry: GeometryResult) -> Loads:
        \"\"\"Static loads of a drive.

        Parameters
        ----------
        %(drive_geometry)s

        Returns
        -------
        Loads
        \"\"\"
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from types import MappingProxyType
from typing import TypeVar

__all__ = ["PARAMETERS", "expand", "shared_parameters"]

T = TypeVar("T")

#: Name → numpydoc entry (first line ``name : type`` — or the type alone in ``Returns`` —,
#: the description indented by four).
PARAMETERS: Mapping[str, str] = MappingProxyType({
    "drive": "drive : Drive\n    The design.",
    "geometry": "geometry : GeometryResult\n    Its contour.",
    "drive_geometry": "drive : Drive\n    The design.\ngeometry : GeometryResult\n"
                      "    Its contour.",
    "pitch": "pitch : float\n    Chain pitch p [m].",
    "teeth": "teeth : int\n    Number of teeth z [-].",
    # compute side (dynamics/, geometry/, kinematics, strength/, synthesis/, ...)
    # the Parameters section of a function of the design alone, and the Returns heading
    "drive_returns": "Parameters\n----------\ndrive : Drive\n    The design.\n\nReturns\n-------",
    "pitch_teeth_returns": "Parameters\n----------\npitch : float or array_like\n"
                           "    Chain pitch p [m].\nteeth : int or array_like\n"
                           "    Number of teeth z [-].\n\nReturns\n-------",
    "pitch_teeth_roller_returns": "Parameters\n----------\npitch : float or array_like\n"
                                  "    Chain pitch p [m].\nteeth : int or array_like\n"
                                  "    Number of teeth z [-].\n"
                                  "roller_diameter : float or array_like\n"
                                  "    Roller diameter d1 [m].\n\nReturns\n-------",
    "teeth_returns": "Parameters\n----------\nteeth : int or array_like\n"
                     "    Number of teeth z [-].\n\nReturns\n-------",
    "node_dof_factor": "node_dof : ndarray\n    (nodes,) coordinate of each node [-].\n"
                       "factor : ndarray\n    (nodes,) φ_node / q [-].",
    "teeth_array": "teeth : int or array_like\n    Number of teeth z [-].",
    "pitch_t_array": "pitch : float or array_like\n    Chain pitch t [m].",
    "chain": "chain : ChainSpec\n    The chain.",
    "risk": "risk : float\n    The risk level [-].",
    "c4": "c4 : float\n    C₄ [-].",
    "max_clearance": "max_clearance : float\n    z_max [m].",
    "samples_rng": "n : int\n    Samples [-].\nrng : numpy.random.Generator or int or None\n"
                   "    A generator or the seed of one.",
    "links": "links : float\n    Chain length L_p [pitches].",
    "drive_power": "drive : Drive\n    The design (power and driver speed given).",
    "small_sprocket": "teeth : int\n    Teeth of the small sprocket [-].",
    "driver_teeth": "driver_teeth : int\n    Teeth z_1 of the driver [-].",
    "sprocket_names": "names : sequence of str or None\n"
                      "    Names of the sprockets (None: S1, S2, …).",
    "harmonics": "harmonics : int\n    Harmonics of the tooth frequency [-].",
    "contour_geometry": "geometry : GeometryResult\n"
                        "    The contour's geometry (spans in ring order, wraps, pitch).",
    "tooth_angular_frequency": "tooth_angular_frequency : float\n"
                               "    Tooth frequency ω_z = z₁ω₁ [rad/s].",
    "probe_returns": "Parameters\n----------\nprobe : ResonanceProbe\n    The check and its band.\n"
                     "band_percent : float\n    The least detuning required [%].\n\nReturns\n-------",
    "selection_catalog": "design_factor : float\n    n_d [-].\ncatalog : sequence of ChainSpec or None\n"
                         "    The chains to choose from.\nextra_files : sequence of str\n"
                         "    The user's catalogue files.",
    "hinge_force_returns": "Parameters\n----------\ntension : array_like\n"
                           "    Static span tension F_0 [N].\nrelative_amplitude : array_like\n"
                           "    ȳ_0 [-].\ncoefficients : HingeFrictionCoefficients\n"
                           "    The chain's F_max fit (default: the paper's ПР-12,7-1820-1).\n\n"
                           "Returns\n-------",
    "pitch_p_returns": "Parameters\n----------\npitch : float\n    p [m].\n\nReturns\n-------",
    "roller_diameter_returns": "Parameters\n----------\nroller_diameter : float or array_like\n"
                               "    Roller diameter d1 [m].\n\nReturns\n-------",
    "pitch_t_teeth": "pitch : float\n    Chain pitch t [m].\nteeth : int\n    Number of teeth z [-].",
    "study": "study : str\n    The study's name.",
    "roller_diameter": "roller_diameter : float\n    Roller diameter d1 [m].",
    "drive_model": "model : DriveModel\n    The model.",
    "batch_masses": "masses : numpy.ndarray\n    (B, n) reduced masses [kg].",
    "design_path": "path : str\n    A ``sprockets[2].x``-style path.",
    "geometry_the_contour": "geometry : GeometryResult\n    The contour.",
    # the last parameter and the Returns section of a tooth-gap wall
    "wall_returns": "samples : int\n    Points per arc [-].\n\nReturns\n-------\nnumpy.ndarray\n"
                    "    (k, 2) points of the wall, x along the tangent, y radial outward [m].",
    # the Parameters heading and the first three parameters of a drive's checks
    "checks_params": "Parameters\n----------\ndrive : Drive\n"
                     "    The design (power and driver speed given).\n"
                     "geometry : GeometryResult\n    Its contour.\nsettings : CheckSettings or None\n"
                     "    What the checks are held to (None: :func:`settings_for` the drive).",
    # the whole Parameters section and the Returns type of a matrix with some spans slack
    "span_active_matrix": "Parameters\n----------\nspan_active : array_like | None\n"
                          "    (spans,) 1 for a span that carries, 0 for a slack one [-] "
                          "(None: all carry).\n\nReturns\n-------\nndarray",
    "active_matrix": "Parameters\n----------\nactive : ndarray of bool | None\n"
                     "    (S,) the spans that carry (None: all).\n\nReturns\n-------\nndarray",
    "pitch_teeth_array": "pitch : float or array_like\n    Chain pitch p [m].\n"
                         "teeth : int or array_like\n    Number of teeth z [-].",
    "roller_diameter_array": "roller_diameter : float or array_like\n"
                             "    Roller diameter d1 [m].",
    "ax": "ax : Axes or None\n    Axes to draw into (None: a new figure).",
    "units": 'units : {"SI", "US"}\n'
             "    The output unit system (:data:`chaindrive.display.UNIT_SYSTEMS`).",
    "units_force": 'units : {"SI", "US"}\n    Unit system of the forces: N (SI) or lbf (US)\n'
                   '    (:data:`chaindrive.display.QUANTITIES`, kind ``"force"``).',
    "returns_figure": "Figure\n    The figure drawn into.",
    "inp": "inp : ReportInput\n    The analysis and the report's settings.",
    # the whole Parameters and Returns sections of a report section's builder
    "section": "Parameters\n----------\ninp : ReportInput\n"
               "    The analysis and the report's settings.\n\nReturns\n-------\n"
               "list of Block | None\n    The section's blocks (None: the section does not apply).",
    "section_blocks": "Parameters\n----------\ninp : ReportInput\n"
                      "    The analysis and the report's settings.\n\nReturns\n-------\n"
                      "list of Block\n    The section's blocks.",
})

_PLACEHOLDER = re.compile(r"^(?P<indent>[ \t]*)%\((?P<name>\w+)\)s[ \t]*$", re.MULTILINE)


def expand(doc: str) -> str:
    """``doc`` with every line ``%(name)s`` replaced by the entry ``name`` of
    :data:`PARAMETERS`, indented as the line.

    Parameters
    ----------
    doc : str
        A docstring as written (its lines indented as in the source).

    Returns
    -------
    str
        The docstring with the shared entries written out.

    Raises
    ------
    KeyError
        A placeholder names no entry of :data:`PARAMETERS`.
    """
    def entry(m: re.Match[str]) -> str:
        indent = m.group("indent")
        return "\n".join(indent + line if line else ""
                         for line in PARAMETERS[m.group("name")].splitlines())

    return _PLACEHOLDER.sub(entry, doc)


def shared_parameters(obj: T) -> T:
    """Decorator: expand the shared parameter entries of ``obj``'s docstring (module
    docstring); ``obj`` is returned itself, its type unchanged.

    Parameters
    ----------
    obj : function or class
        What the docstring belongs to.

    Returns
    -------
    function or class
        ``obj``, its ``__doc__`` expanded (unchanged without a docstring, as under ``-OO``).
    """
    doc = getattr(obj, "__doc__", None)
    if doc:
        obj.__doc__ = expand(doc)
    return obj
