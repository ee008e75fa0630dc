"""Why the link-level static solve creeps on a drive (docs/linklevel.md §1, "Why the
minimisation creeps there"). Run:
.venv/bin/python benchmarks/bench_linklevel_static_conditioning.py [example] [steps]
(default: twenty_four_sprocket, 400 steps).

Runs the first minimisation of the solve (the trust-region Newton method in its
Levenberg–Marquardt form, as ``equilibrium._minimum`` does it, from the placement at the pull
T̄ = T₀) for ``steps`` steps, printing every 50th step's ‖∇Φ‖₂, largest component, shift μ and
ratio; then at the state reached: the spread of the Hessian ∇²Φ (its eigenvalues, dense) and
where its six softest eigenvectors sit (rollers on a sprocket or in a free span), the largest
forces left with the contact of each roller (penetration δ and the region of the tooth gap),
and four steps of Newton's method with a backtracking line search on Φ from there (the step
length taken and ‖∇Φ‖₂ after it). CPU time by ``time.process_time``, one BLAS thread.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.sparse import csc_matrix, diags
from threadpoolctl import threadpool_limits

from chaindrive.geometry.contour import contour_geometry
from chaindrive.io.design import load_drive
from chaindrive.linklevel import build_model
from chaindrive.linklevel import equilibrium as eqm
from chaindrive.linklevel.assembly import assemble_chain
from chaindrive.linklevel.kernel import penetration

EXAMPLES = Path(__file__).resolve().parents[1] / "src" / "chaindrive" / "examples"


def _energy(name: str) -> tuple[eqm._Tensioned, object]:
    """Φ of the example's first minimisation, and its model."""
    drive = load_drive(EXAMPLES / f"{name}.toml")
    geometry, _ = eqm.installed_geometry(drive, contour_geometry(drive))
    model = build_model(drive, geometry)
    asm = assemble_chain(geometry, drive.driver_index, hang=bool(model.gravity[1] != 0.0))
    span = next((k for k, sp in enumerate(geometry.spans) if sp.start == drive.driver_index), 0)
    n = model.centres.shape[0]
    free = np.array([i for i in range(n) if i != model.driver], dtype=np.int64)
    x = asm.positions.copy()
    ref = int(eqm.span_probes(geometry, x)[span])
    tables = eqm.kernel_tables(model)
    bal = eqm.Balance(model, tables, free, x.shape[0], ref)
    rest = model.pitch - model.pretension / model.link_stiffness
    return eqm._Tensioned(model, tables, bal, x, asm.angles.copy(), rest), model


def _lm_steps(phi: eqm._Tensioned, steps: int) -> tuple[np.ndarray, float]:
    """``steps`` steps of the minimisation (``equilibrium._minimum``, no tolerance), the
    gradient left and the shifts printed; the unknowns and the shift reached."""
    mus: list[float] = []
    z, taken = eqm._minimum(phi, 0.0, steps, mus)
    g, mu = phi.gradient(z), (mus[-1] if mus else math.nan)
    print(f"{taken} steps: |grad| {np.linalg.norm(g):.3e} N, largest "
          f"{np.abs(g[:-1]).max():.3e} N, mu {mu:.3e} N/m", flush=True)
    if mus:
        print("mu over the steps, 5/50/95 %:", np.percentile(mus, [5, 50, 95]))
    return z, mu


def _contacts(phi: eqm._Tensioned, model: object, z: np.ndarray) -> np.ndarray:
    """Penetration δ [m] of every roller in the reach of a sprocket (nan: none)."""
    x, th, _ = phi.state(z)
    on = phi.bal._sprocket_of(x)
    spr = phi.tables.spr
    out = np.full(phi.N, np.nan)
    for i in np.flatnonzero(on >= 0):
        s = int(on[i])
        rel = x[i] - model.centres[s]  # type: ignore[attr-defined]
        out[i] = penetration(float(rel[0]), float(rel[1]), float(th[s]), *spr[2:8, s])[0]
    return out


def _refusal(phi: eqm._Tensioned, model: object, z: np.ndarray, mu: float) -> None:
    """The step at a quarter of the shift reached: its ratio and the contacts it opens or
    closes."""
    g, H = phi.gradient(z), phi.hessian(z)
    p = eqm._definite_solve(csc_matrix(H + diags(np.full(z.size, 0.25 * mu))), g)
    if p is None:
        print("  not positive definite at mu/4")
        return
    predicted = -float(g @ p + 0.5 * p @ (H @ p))
    ratio = (phi.value(z) - phi.value(z + p)) / predicted
    before, after = _contacts(phi, model, z), _contacts(phi, model, z + p)
    flips = np.flatnonzero((before > 0) != (after > 0))
    print(f"  step at mu/4 = {0.25 * mu:.3g} N/m: largest move {np.abs(p).max():.2e} m, ratio "
          f"{ratio:.3f}; contacts it opens or closes: "
          + ", ".join(f"roller {i} (delta {before[i]:.2e} -> {after[i]:.2e} m)"
                      for i in flips))


def _spread(phi: eqm._Tensioned, z: np.ndarray) -> None:
    """The Hessian's eigenvalues and where its softest modes sit."""
    w, V = np.linalg.eigh(phi.hessian(z).toarray())
    print(f"Hessian eigenvalues {w[0]:.3g} … {w[-1]:.3g} N/m (condition {w[-1] / w[0]:.2g});"
          f" six lowest {np.array2string(w[:6], precision=3)}")
    x, _, _ = phi.state(z)
    on = phi.bal._sprocket_of(x)
    for j in range(6):
        rollers = np.abs(V[: 2 * phi.N, j]).reshape(phi.N, 2).sum(axis=1)
        top = np.argsort(-rollers)[:6]
        print(f"  mode {j}: rollers {sorted(top.tolist())}, on sprockets "
              f"{sorted(set(on[top].tolist()))} (-1: free span), weight on the sprockets' "
              f"turns {np.abs(V[2 * phi.N:-1, j]).sum():.2e}")


def _left(phi: eqm._Tensioned, model: object, z: np.ndarray) -> None:
    """The largest forces left and the contact of each roller."""
    g = phi.gradient(z)
    x, th, _ = phi.state(z)
    on = phi.bal._sprocket_of(x)
    spr = phi.tables.spr
    for b in np.argsort(-np.abs(g[:-1]))[:8]:
        if b >= 2 * phi.N:
            print(f"  sprocket {phi.bal.free[b - 2 * phi.N]}: torque/R {g[b]:+.3e} N")
            continue
        i, s = int(b // 2), int(on[b // 2])
        where = "free span"
        if s >= 0:
            rel = x[i] - model.centres[s]  # type: ignore[attr-defined]
            d = penetration(float(rel[0]), float(rel[1]), float(th[s]), *spr[2:8, s])[0]
            where = f"sprocket {s}, delta {d:.3e} m (k_c delta {spr[8, s] * max(d, 0):.3g} N)"
        print(f"  roller {i}: {-g[b]:+.3e} N, {where}")


def _newton(phi: eqm._Tensioned, z: np.ndarray, steps: int = 4) -> None:
    """Newton's method with a backtracking (Armijo) line search on Φ from ``z``."""
    f, g = phi.value(z), phi.gradient(z)
    for k in range(steps):
        H, mu = phi.hessian(z), 0.0
        while (p := eqm._definite_solve(csc_matrix(H + diags(np.full(z.size, mu))), g)) \
                is None:
            mu = max(4.0 * mu, 1e-10 * float(np.abs(H.diagonal()).max()))
        a, slope = 1.0, float(g @ p)
        while a > 1e-12 and (fn := phi.value(z + a * p)) > f + 1e-4 * a * slope:
            a *= 0.5
        z, f, g = z + a * p, fn, phi.gradient(z + a * p)
        print(f"  Newton {k}: full step {np.abs(p).max():.2e} m, length taken {a:.3g}, "
              f"|grad| after {np.linalg.norm(g):.3e} N")


def main(name: str, steps: int) -> None:
    phi, model = _energy(name)
    print(f"{name}: {phi.N} rollers, T0 {model.pretension:.2f} N")  # type: ignore[attr-defined]
    t = time.process_time()
    with threadpool_limits(limits=1):
        z, mu = _lm_steps(phi, steps)
        print(f"{steps} steps: {time.process_time() - t:.1f} s CPU")
        _spread(phi, z)
        print("largest forces left:")
        _left(phi, model, z)
        print("why the shift stays up:")
        _refusal(phi, model, z, mu)
        print("Newton with a line search on Phi from there:")
        _newton(phi, z)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "twenty_four_sprocket",
         int(sys.argv[2]) if len(sys.argv) > 2 else 400)
