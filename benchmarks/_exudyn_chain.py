"""The link-level chain built in exudyn (the peer of benchmarks/bench_linklevel.py).

Same bodies and forces as :mod:`chaindrive.linklevel` where exudyn has them natively:
rollers as 2D mass points (NodePoint2D + MassPoint2D) with gravity; links as
ConnectorSpringDamper (same k, c, rest lengths); sprockets as 2D rigid bodies held on their
centres by coordinate constraints, free to turn; roller–tooth contact by exudyn's
GeneralContact, spheres (circles in the plane) against the sprocket outline as a triangle
mesh extruded along z — the same gap (seating arc r_i over ±α, tangent flanks, tip circle),
the arc in straight pieces. GeneralContact's law is a linear spring–dashpot in series
between the two contact partners, so each side gets 2k_c and 2c_c. Hinge friction has no
native element: the comparison runs without it on both sides.
"""

from __future__ import annotations

import math
import time

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    CoordinateConstraint,
    LoadForceVector,
    LoadTorqueVector,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    MarkerNodePosition,
    MassPoint2D,
    NodePoint2D,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorSpringDamper,
    ObjectRigidBody2D,
    SensorNode,
    SensorObject,
)

GRAVITY = 9.80665


def tooth_outline(z: int, R: float, ri: float, alpha: float, Ra: float,
                  n_arc: int = 10, n_tip: int = 4, tangent: bool = False) -> np.ndarray:
    """Counter-clockwise outline (P, 2) [m] of a sprocket in its own frame: per gap the
    seating arc, the flanks along the arc's end tangents up to the tip circle, the tip arc
    to the next gap. The arc in n_arc − 1 chords: inscribed (vertices on the arc: a seated
    roller meets a chord up to r_i(1 − cos(Δθ/2)) early — with 10 points some 30 µm, 100
    times the static contact compression) or, ``tangent``, touching it at their midpoints
    (vertices at r_i/cos(Δθ/2): a roller meets them at most that much late)."""
    pts: list[np.ndarray] = []
    step = 2 * math.pi / z
    for j in range(z):
        ga = j * step
        er = np.array([math.cos(ga), math.sin(ga)])
        et = np.array([-math.sin(ga), math.cos(ga)])
        g = R * er

        def arc(th: float, g=g, er=er, et=et) -> np.ndarray:
            return g + ri * (math.cos(th) * (-er) + math.sin(th) * et)

        def flank_top(sg: float, g=g, er=er, et=et) -> np.ndarray:
            pe = arc(sg * alpha)
            n = math.cos(sg * alpha) * (-er) + math.sin(sg * alpha) * et
            u = np.array([-n[1], n[0]])
            if u @ er < 0:
                u = -u
            b, c = pe @ u, pe @ pe - Ra * Ra
            return pe + (-b + math.sqrt(b * b - c)) * u

        pts.append(flank_top(-1.0))
        if tangent:
            half = alpha / (n_arc - 1)  # half a chord's angle
            pts.extend(g + (arc(th) - g) / math.cos(half)
                       for th in np.linspace(-alpha - half, alpha + half, n_arc + 1))
        else:
            pts.extend(arc(th) for th in np.linspace(-alpha, alpha, n_arc))
        pts.append(flank_top(1.0))
        a0 = math.atan2(pts[-1][1], pts[-1][0])
        a1 = 2 * (ga + step / 2) - a0
        pts.extend(Ra * np.array([math.cos(a), math.sin(a)])
                   for a in np.linspace(a0, a1, n_tip + 2)[1:-1])
    return np.array(pts)


def extrude(outline: np.ndarray, half_width: float) -> tuple[list, list]:
    """Side faces of the outline extruded over ±half_width, normals outwards."""
    n = len(outline)
    points = [[x, y, -half_width] for x, y in outline] + [[x, y, half_width] for x, y in outline]
    triangles = []
    for i in range(n):
        j = (i + 1) % n
        triangles += [[i, j, n + j], [i, n + j, n + i]]
    return points, triangles


def build(model, state, dt: float, t_end: float, torques=None, probes=(), n_arc=10,
          tangent=False):
    """(SystemContainer, mbs, settings, sensor) of the chain of ``model`` from ``state``
    (:class:`chaindrive.linklevel.simulate.InitialState`), explicit steps of dt [s];
    ``torques`` (n,) constant torques on the sprockets [N·m] (counter-clockwise positive),
    ``probes`` link indices whose spring–damper force is recorded (sensor list appended)."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    ground_x = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    contact = mbs.AddGeneralContact()
    m = model.roller_mass
    x, v = state.positions, state.velocities
    markers = []
    for r in range(x.shape[0]):
        node = mbs.AddNode(NodePoint2D(referenceCoordinates=list(x[r]),
                                       initialVelocities=list(v[r])))
        mbs.AddObject(MassPoint2D(physicsMass=m, nodeNumber=node))
        marker = mbs.AddMarker(MarkerNodePosition(nodeNumber=node))
        markers.append(marker)
        mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=[0, -GRAVITY * m, 0]))
        contact.AddSphereWithMarker(marker, model.roller_radius, 2 * model.contact_stiffness[0],
                                    2 * model.contact_damping[0], 0)
    n_links = x.shape[0]
    links = []
    for i in range(n_links):
        links.append(mbs.AddObject(ObjectConnectorSpringDamper(
            markerNumbers=[markers[i], markers[(i + 1) % n_links]],
            stiffness=model.link_stiffness, damping=model.link_damping,
            referenceLength=float(state.rest_lengths[i]))))
    nodes = []
    for s in range(model.centres.shape[0]):
        cx, cy = model.centres[s]
        node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[cx, cy, float(state.angles[s])],
                                           initialVelocities=[0, 0, float(state.speeds[s])]))
        body = mbs.AddObject(ObjectRigidBody2D(physicsMass=1.0,
                                               physicsInertia=float(model.inertias[s]),
                                               nodeNumber=node))
        for c, offset in ((0, cx), (1, cy)):
            mc = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=c))
            mbs.AddObject(CoordinateConstraint(markerNumbers=[ground_x, mc], offset=offset))
        rigid = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[0, 0, 0]))
        if torques is not None and torques[s] != 0.0:
            mbs.AddLoad(LoadTorqueVector(markerNumber=rigid, loadVector=[0, 0, float(torques[s])]))
        outline = tooth_outline(int(model.teeth[s]), model.pitch_radii[s],
                                model.seating_radii[s], model.seating_half_angles[s],
                                model.tip_radii[s], n_arc=n_arc, tangent=tangent)
        points, triangles = extrude(outline, 0.01)
        contact.AddTrianglesRigidBodyBased(rigid, 2 * model.contact_stiffness[s],
                                           2 * model.contact_damping[s], 0, points, triangles)
        nodes.append(node)
    contact.SetFrictionPairings(np.zeros((1, 1)))
    lo, hi = x.min(axis=0) - 0.2, x.max(axis=0) + 0.2
    contact.SetSearchTreeBox([lo[0], lo[1], -0.1], [hi[0], hi[1], 0.1])
    contact.SetSearchTreeCellSize([40, 10, 1])
    sensor = mbs.AddSensor(SensorNode(nodeNumber=nodes[1], storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.AngularVelocity))
    if probes:
        sensor = [sensor] + [mbs.AddSensor(SensorObject(
            objectNumber=links[i], storeInternal=True,
            outputVariableType=exu.OutputVariableType.Force)) for i in probes]
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = round(t_end / dt)
    settings.timeIntegration.endTime = t_end
    settings.timeIntegration.verboseMode = 0
    settings.displayComputationTime = False
    settings.solutionSettings.writeSolutionToFile = False
    settings.solutionSettings.sensorsWritePeriod = 1e-4
    settings.timeIntegration.explicitIntegration.computeEndOfStepAccelerations = False
    settings.parallel.numberOfThreads = 1
    return SC, mbs, settings, sensor


def run(model, state, dt: float, t_end: float,
        solver=exu.DynamicSolverType.RK44) -> tuple[float, np.ndarray]:
    """(wall time of the solve [s], (T, 2) time [s] and driven sprocket speed [rad/s])."""
    _container, mbs, settings, sensor = build(model, state, dt, t_end)
    start = time.perf_counter()
    exu.SolveDynamic(mbs, settings, solverType=solver)
    wall = time.perf_counter() - start
    data = mbs.GetSensorStoredData(sensor)
    return wall, data[:, [0, 3]]


def run_loaded(model, state, dt: float, t_end: float, torques, probes, n_arc=200,
               solver=exu.DynamicSolverType.RK44) -> tuple[float, np.ndarray]:
    """(wall time of the solve [s], (T, 1 + len(probes)) time [s] and the probed links'
    force magnitudes [N] (exudyn records the connector's force vector)) of the chain under
    constant sprocket torques."""
    _container, mbs, settings, sensors = build(model, state, dt, t_end, torques, probes,
                                               n_arc, True)
    start = time.perf_counter()
    exu.SolveDynamic(mbs, settings, solverType=solver)
    wall = time.perf_counter() - start
    data = [mbs.GetSensorStoredData(s) for s in sensors[1:]]  # time, force vector (3)
    return wall, np.column_stack([data[0][:, 0]]
                                 + [np.linalg.norm(d[:, 1:4], axis=1) for d in data])
