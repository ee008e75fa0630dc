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

_UNITS = ('units : {"SI", "US"}\n'
          "    The output unit system (:data:`chaindrive.display.UNIT_SYSTEMS`).")
_DOCUMENT = ("document : dict\n"
             "    The analysis's JSON document (:meth:`chaindrive.analysis.Analysis.to_dict`).")
_CHECK = ("check : Check\n"
          "    A pass/fail rule (:class:`chaindrive.checks.Check`), value and limit in SI.")
_SYSTEM = 'system : {"SI", "US"}\n    The output unit system (:data:`UNIT_SYSTEMS`).'
_SCREEN = ("screen : Screen\n    The quick screen of the design on the page (its analysis and "
           "JSON document).")
_PITCH_TEETH_SPEED = ("pitch : float or array_like\n    Chain pitch p [m].\nteeth : int or "
                      "array_like\n    Number of teeth z [-].\nspeed : float or array_like\n"
                      "    Angular speed ω [rad/s].")
_PITCH_TEETH_SPEED_PHASE = f"{_PITCH_TEETH_SPEED}\nphase : float or array_like\n    Tooth phase ψ [rad]."
_ROWS = "list of dict\n    One dict per row: column header (with its unit) → cell."

#: Name → numpydoc entry (first line ``name : type`` — or the type alone in ``Returns`` —,
#: the description indented by four).
PARAMETERS: Mapping[str, str] = MappingProxyType({
    # a point of the link-level static balance (linklevel/equilibrium.py)
    "balance_point": "x : ndarray\n    (N, 2) roller positions [m].\nth : ndarray\n    (n,) "
                     "sprocket angles [rad].\nrest : float\n    Rest length of the links "
                     "[m].\nr0 : ndarray\n    The residual at (x, θ, ℓ₀) [N].",
    "drive": "drive : Drive\n    The design.",
    "params_drive": "Parameters\n----------\ndrive : Drive\n    The design.",
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
    "installed_link_level": "drive : Drive\n    The drive.\ngeometry : GeometryResult\n"
                            "    Its installed contour.\nmodel : LinkLevelModel\n"
                            "    The link-level model on it.\ntake_up : str or None\n"
                            "    The sprocket that took up the slack (None: none).",
    # the robust study (robust/): a state's model under S sets of modal factors, the drive
    # as drawn with its uncertainty model, the bootstrap of the Sobol indices, the batched
    # modal frequencies, a check's key and a sensitivity metric, the design file read
    "params_modal_factors": "Parameters\n----------\nstate : Analysis\n    The analysis of one "
                            "geometric state (factors 1, reference temperature).\ninertia : "
                            "ndarray\n    (S, n) factors on the sprockets' inertias [–].\nlink : "
                            "ndarray\n    (S,) factors on the link stiffness [–].\ntemperature : "
                            "ndarray\n    (S,) temperatures of the polymer parts [°C].",
    "params_nominal_wear": "Parameters\n----------\nnominal : Analysis\n    The analysis of the "
                           "drive as drawn.\nmodel : UncertaintyModel\n    Its model (allowable "
                           "elongation, take-up capacity).",
    "nominal_modal_returns": "Parameters\n----------\nnominal : Analysis\n    The analysis of "
                             "the drive as drawn.\nmodel : UncertaintyModel\n    Its uncertainty "
                             "model (its modal variables are sampled).\n\nReturns\n-------",
    "sobol_bootstrap_returns": "groups : int\n    G [–].\nconfidence : float\n    Level of the "
                               "intervals, c [–].\nseed : int\n    Seed of the resampling.\n"
                               "resamples : int\n    Bootstrap resamples [–].\n\nReturns\n"
                               "-------\ntuple",
    "params_system_inertia": "Parameters\n----------\nsystem : TorsionalSystem\n    The system "
                             "the variants share.\nnode_inertia : ndarray\n    (S, nodes) J of "
                             "every node [kg·m²]; a node of the system with J = 0 must keep it.",
    "elastic_frequencies_returns": "Returns\n-------\nndarray\n    (S, E) [Hz], E = massed "
                                   "coordinates − rigid-body motions.\n\nReferences\n"
                                   "----------\n[Guyan1965], [Rao2011, ch. 6]",
    "params_check_key_returns": "Parameters\n----------\nkey : str\n    The check's key "
                                "(:attr:`chaindrive.checks.Check.key`).\n\nReturns\n-------",
    "params_metric_returns": "Parameters\n----------\nmetric : str\n    A metric of the "
                             "result (a name of :data:`SENSITIVITY_METRICS`).\n\nReturns\n"
                             "-------",
    "params_design_path_returns": "Parameters\n----------\npath : str or pathlib.Path\n    "
                                  "The design file (TOML).\n\nReturns\n-------",
    # a worn chain on a sprocket (robust/wear.py)
    "worn_pitch_teeth_returns": "Parameters\n----------\npitch : array_like\n    Nominal chain "
                                "pitch p [m].\nteeth : array_like\n    Teeth z [–].\n"
                                "elongation : array_like\n    Wear elongation ε [–].\n\n"
                                "Returns\n-------\nndarray",
    # the model and the tooth frequency a start-up's step is chosen from
    # (dynamics/transient/drive_startup.py)
    "params_model_tooth_frequency": "Parameters\n----------\nmodel : DriveModel\n    The "
                                    "model.\ntooth_frequency_hz : float\n    f_z [Hz].",
    # the match of a spectrum's peak to the model's lines (identification/spectrum.py)
    "tolerance_resolution_returns": "tolerance : float\n    Relative tolerance of the model's "
                                    "frequencies [-].\nresolution : float\n    One frequency "
                                    "bin [Hz].\n\nReturns\n-------",
    "params_samples_rate": "Parameters\n----------\nvalues : ndarray\n    The samples [signal "
                           "unit].\nsample_rate : float\n    f_s [Hz].",
    # the last parameters and the Returns heading of a span's hinge-friction energies
    # (dynamics/damping.py)
    "amplitude_tension_fit_returns": "relative_amplitude : array_like\n    ȳ_0 [-].\ntension : "
                                     "array_like\n    Static span tension F_0 [N].\n"
                                     "coefficients : HingeFrictionCoefficients\n    The chain's "
                                     "F_max fit (default: the paper's ПР-12,7-1820-1).\n\n"
                                     "Returns\n-------",
    "field_path": "path : str\n    A ``sprockets[2].x``-style path.",
    "geometry_the_contour": "geometry : GeometryResult\n    The contour.",
    "centres_signed_radii": "Parameters\n----------\ncentres : numpy.ndarray\n"
                            "    (n, 2) sprocket centres [m].\nradii : numpy.ndarray\n"
                            "    (n,) signed pitch radii [m] (negative on the inside of the "
                            "contour).",
    # the inputs of a contour's layout, and of the two-sprocket closed forms (geometry/contour.py)
    "layout_inputs": "centres : numpy.ndarray\n    (n, 2) sprocket centres [m].\n"
                     "radii_abs : numpy.ndarray\n    (n,) pitch radii R [m].\n"
                     "inside : numpy.ndarray\n    (n,) True for a sprocket on the inside of "
                     "the contour.\nteeth : numpy.ndarray\n    (n,) numbers of teeth z [-].\n"
                     "pitch : float\n    Chain pitch p [m].",
    "two_sprocket_links": "center_distance : float\n    Centre distance a [m].\npitch : float\n"
                          "    Chain pitch p [m].\nz1, z2 : int\n    Teeth of the two sprockets "
                          "[-].\n\nReturns\n-------\nfloat\n    L_p [pitches] (not rounded).",
    "two_sprocket_center_distance": "links : float\n    Chain length L_p [pitches].\n"
                                    "pitch : float\n    Chain pitch p [m].\nz1, z2 : int\n"
                                    "    Teeth of the two sprockets [-].\n\nReturns\n-------\n"
                                    "float\n    Centre distance a [m].\n\nRaises\n------\n"
                                    "GeometryError\n    On ``chain.links`` when the links are "
                                    "too few for the sprockets.",
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
    # the Parameters section and the Returns type of a diameter by the tooth form
    "tooth_form_diameter_returns": "Parameters\n----------\npitch : float or array_like\n"
                                   "    Chain pitch p [m].\nteeth : int or array_like\n"
                                   "    Number of teeth z [-].\nroller_diameter : float or "
                                   "array_like\n    Roller diameter d1 [m].\nform : {\"ISO 606\", "
                                   "\"GOST 591\"}\n    The tooth form.\n\nReturns\n-------\n"
                                   "float or numpy.ndarray",
    # the whole Parameters section and the Returns type of a speed of the chain (kinematics.py)
    "pitch_teeth_speed_returns": f"Parameters\n----------\n{_PITCH_TEETH_SPEED}\n\nReturns\n"
                                 "-------\nfloat or numpy.ndarray",
    "pitch_teeth_speed_phase": _PITCH_TEETH_SPEED_PHASE,
    "pitch_teeth_speed_phase_returns": f"Parameters\n----------\n{_PITCH_TEETH_SPEED_PHASE}\n\n"
                                       "Returns\n-------\nfloat or numpy.ndarray",
    # the whole Parameters section and the Returns type of a GOST 591 diameter
    "pitch_t_teeth_roller_returns": "Parameters\n----------\npitch : float or array_like\n"
                                    "    Chain pitch t [m].\nteeth : int or array_like\n"
                                    "    Number of teeth z [-].\nroller_diameter : float or "
                                    "array_like\n    Roller diameter d1 [m].\n\nReturns\n"
                                    "-------\nfloat or numpy.ndarray",
    "roller_diameter_array": "roller_diameter : float or array_like\n"
                             "    Roller diameter d1 [m].",
    "ax": "ax : Axes or None\n    Axes to draw into (None: a new figure).",
    "units": _UNITS,
    "units_force": 'units : {"SI", "US"}\n    Unit system of the forces: N (SI) or lbf (US)\n'
                   '    (:data:`chaindrive.display.QUANTITIES`, kind ``"force"``).',
    "ax_returns_figure": "ax : Axes or None\n    Axes to draw into (None: a new figure).\n\n"
                         "Returns\n-------\nFigure\n    The figure drawn into.",
    "campbell": "campbell : CampbellData\n    The model's Campbell data.",
    # the drawing of a link-level state (plotting/linklevel.py)
    "magnify_units": "magnify : float\n    Scale of the transverse deviations of the free rollers "
                     "[-].\nunits : {\"SI\", \"US\"}\n    Unit system: positions in m (SI) or ft "
                     "(US), link tensions in N (SI) or lbf (US)\n    (:data:`chaindrive.display."
                     "QUANTITIES`, kinds ``\"distance\"`` and ``\"force\"``).",
    "units_force_figure": 'units : {"SI", "US"}\n    Unit system of the forces: N (SI) or lbf '
                          '(US)\n    (:data:`chaindrive.display.QUANTITIES`, kind ``"force"``).'
                          "\n\nReturns\n-------\nFigure\n    The figure drawn into.",
    "returns_figure": "Figure\n    The figure drawn into.",
    "inp": "inp : ReportInput\n    The analysis and the report's settings.",
    "params_inp": "Parameters\n----------\ninp : ReportInput\n"
                  "    The analysis and the report's settings.",
    # the whole Parameters and Returns sections of a report section's builder
    "section": "Parameters\n----------\ninp : ReportInput\n"
               "    The analysis and the report's settings.\n\nReturns\n-------\n"
               "list of Block | None\n    The section's blocks (None: the section does not apply).",
    "section_blocks": "Parameters\n----------\ninp : ReportInput\n"
                      "    The analysis and the report's settings.\n\nReturns\n-------\n"
                      "list of Block\n    The section's blocks.",
    # presenters (app/, cli/, report/, display.py)
    "document": _DOCUMENT,
    "returns_rows": _ROWS,
    # the Parameters section of a table's rows from the document (app/views.py), and with
    # its Returns section
    "params_document_units": f"Parameters\n----------\n{_DOCUMENT}\n{_UNITS}",
    "rows_document_units": f"Parameters\n----------\n{_DOCUMENT}\n{_UNITS}\n\n"
                           f"Returns\n-------\n{_ROWS}",
    # the Parameters section of a page's screen of the design
    "params_design_catalogs": "Parameters\n----------\ndesign : dict\n"
                              "    The design mapping (what a TOML design file loads to).\n"
                              "catalogs : dict of str to Path | None\n    The catalogues "
                              "uploaded in the session (name → file), the only files\n"
                              "    ``chain.catalog`` may name "
                              "(:func:`chaindrive.io.design.drive_from_mapping`).",
    # the Parameters section of a tab of the page (app/tabs.py)
    "params_screen": f"Parameters\n----------\n{_SCREEN}",
    "params_screen_design": f"Parameters\n----------\n{_SCREEN}\ndesign : dict\n"
                            "    The design mapping of the form (what the TOML download "
                            "writes).",
    # the Parameters section of a bounded run of the page's screens (app/runs.py)
    "params_form_catalogs": "Parameters\n----------\ndesign : dict\n"
                            "    The design mapping of the form.\n"
                            "catalogs : dict of str to Path | None\n"
                            "    The session's uploaded catalogues.",
    # the report's renderers and builders (report/)
    "params_report": "Parameters\n----------\nreport : Report\n    The built report.",
    "report_options": "source : str | Path | None\n    The design file (echoed at the end, its "
                      "SHA-256 in the header).\ndpi : int\n    Resolution of the figures "
                      "[1/in].\nprogress : callable | None\n    Called with each section's "
                      "title before it is built (e.g. a progress bar).\nsynthesis : "
                      "SynthesisResult | None\n    The optimisation that chose this design "
                      "(its Pareto set and front).\nunits : str\n    Output unit system, "
                      '"SI" or "US" (:mod:`chaindrive.display`).',
    # the whole Parameters and Returns sections of a plot of the static loads
    "loads_figure": "Parameters\n----------\nanalysis : Analysis\n    The analysis (its loads)."
                    "\nax : Axes or None\n    Axes to draw into (None: a new figure).\n"
                    'units : {"SI", "US"}\n    Unit system of the forces: N (SI) or lbf (US)\n'
                    '    (:data:`chaindrive.display.QUANTITIES`, kind ``"force"``).\n\n'
                    "Returns\n-------\nFigure\n    The figure drawn into.",
    # the Parameters section of a name checked against the valid ones (errors.py)
    "params_name_choices": "Parameters\n----------\nname : str\n    What the user wrote.\n"
                           "choices : iterable of str\n    The valid names.",
    # the Parameters section of a bundled design's accessor (examples/)
    "params_example": "Parameters\n----------\nname : str\n    One of :func:`names`.",
    # the Parameters section of a plausibility check of a design (io/plausible.py)
    "params_drive_read": "Parameters\n----------\ndrive : Drive\n    The design as read.",
    # the span curves of a plot of the dynamic response (plotting/)
    "span_names": "names : sequence of str or None\n    Labels of the spans (None: numbered).",
    "span_curves": "names : sequence of str or None\n    Labels of the spans (None: numbered).\n"
                   "max_lines : int\n    Spans drawn at most (those of the largest peaks) [-].",
    # the Parameters sections of the drawing's documents and pages (drawing.py)
    "params_drawing_analysis": "Parameters\n----------\nanalysis : Analysis\n"
                               "    The analysis of the design (geometry, sprocket profiles).",
    "params_dxf_page": "Parameters\n----------\ndoc : ezdxf.document.Drawing\n"
                       "    A DXF document.\npage_width_mm : float\n"
                       "    Width of the page of a document of several sheets [mm].",
    # the Returns section of the measured frequencies a command reads (cli/measure.py)
    "measured_modes_assumed": "Returns\n-------\nmeasured : list of MeasuredMode\n"
                              "assumed : list of str\n    What rests on an assumed value.",
    # the Parameters section of a progress indicator of the command line (cli/progress.py)
    "params_progress": "Parameters\n----------\ndescription : str\n    What runs.\n"
                       "quiet : bool\n    True in ``--json`` mode (nothing is drawn).",
    # the design file of chaindrive.load
    "design_path": "path : str or pathlib.Path\n    The design file.",
    # the whole Parameters and Returns sections of the page's full analysis (app/runs.py)
    "drive_analysis": "Parameters\n----------\ndrive : Drive\n    The design.\n\nReturns\n"
                      "-------\nAnalysis",
    # the Parameters section of a reader of one cell of the page's form (app/state.py)
    "params_cell": "Parameters\n----------\nvalue : object\n    A cell of the form.",
    # the Parameters section of an uploaded file's reader (app/uploads.py)
    "params_upload": "Parameters\n----------\nname : str\n    The file's name as uploaded.\n"
                     "data : bytes\n    Its content.",
    # the Returns sections of the readers of a record and of a TOML text (io/)
    "returns_record": "Returns\n-------\nRecord\n    The record, sampled evenly.",
    "returns_toml": "Returns\n-------\ndict\n    The mapping the TOML text loads to.",
    # the unit system of display.py, and the Parameters section of a presenter of one check
    "system": _SYSTEM,
    "params_check": f"Parameters\n----------\n{_CHECK}",
    "params_check_system": f"Parameters\n----------\n{_CHECK}\n{_SYSTEM}",
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
