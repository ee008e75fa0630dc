"""Ahead-of-time build of the start-up kernel: ``python -m chaindrive.dynamics.transient.kernel_build``.

The nonlinear start-up (:mod:`chaindrive.dynamics.transient.startup`) steps in the numba kernel
:func:`chaindrive.dynamics.transient.kernel.run_kernel_flat`. Compiled just in time, it costs
every new process about 0.7 s before the first step (importing numba 0.25 s, its typing and
lowering registries, loading the cached machine code; measured with ``python -X importtime``
and cProfile) — most of a command-line ``analyze``. This module compiles the same Python
source once, ahead of time, with numba's ``numba.pycc`` into the extension module
``chaindrive.dynamics.transient._startup_aot``, which imports in milliseconds and without numba (numba
documents that such modules do not need numba at run time).

The module also exports ``source_digest()``: a digest of ``kernel.py`` and
``kernel_codes.py`` as they were at the build, and of the processor it was built on.
:func:`compiled_kernel` uses the module only while the digest still matches the sources and
the processor, so an edited kernel is never run from a stale build (it falls back to
numba's just-in-time compilation until rebuilt).

The build targets the processor it runs on (``target_cpu = "host"``: its vector
instructions, as numba's just-in-time compilation does), not numba.pycc's default generic
x86-64 (two-lane SSE2): the dense products of the step ran 1.4× slower in the generic build
(docs/performance.md). Such a module may not run on another processor (an instruction it
lacks), hence the processor in the digest: built on one machine and moved to another, the
module is not used.

``make`` runs the build after installing; it needs a C compiler (numba.pycc links with the
platform compiler). Without one the build reports why and the package works as before.
"""

from __future__ import annotations

import hashlib
import importlib
import sys
import warnings
from functools import cache
from pathlib import Path
from typing import Any, cast

__all__ = ["MODULE", "build", "compiled_kernel", "processor", "source_digest"]

MODULE = "_startup_aot"
_HERE = Path(__file__).resolve().parent
_SOURCES = ("kernel.py", "kernel_codes.py")


def processor() -> str:
    """The processor's model and instruction-set extensions as the system reports them (the
    first ``model name`` and ``flags`` of /proc/cpuinfo on Linux, after the machine type;
    elsewhere the machine type alone).

    Returns
    -------
    str
        A description that differs between processors whose code may differ.
    """
    import platform  # platform.machine() is os.uname(); platform.processor() would run uname

    found: dict[str, str] = {}
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as f:
            for line in f:
                key, _, value = line.partition(":")
                key = key.strip()
                if key in ("model name", "flags") and key not in found:
                    found[key] = value.strip()
                    if len(found) == 2:
                        break
    except OSError:
        pass
    return "|".join([platform.machine(), found.get("model name", ""), found.get("flags", "")])


def source_digest() -> int:
    """The fingerprint of the kernel's sources and of the processor (:func:`processor`): the
    first 7 bytes of their SHA-256, as a non-negative int64.

    Returns
    -------
    int
        The digest; a compiled module built from other sources or on another processor
        carries another one.
    """
    h = hashlib.sha256()
    for name in _SOURCES:
        h.update((_HERE / name).read_bytes())
    h.update(processor().encode())
    return int.from_bytes(h.digest()[:7], "big")


@cache
def compiled_kernel() -> Any:  # a function of a generated extension module: no stubs
    """``run_kernel_flat`` of the ahead-of-time module, or None when it is not built or was
    built from other sources (decided once per process)."""
    try:
        # imported by name: the extension module exists only once built
        _startup_aot = importlib.import_module("chaindrive.dynamics.transient._startup_aot")
    except ImportError:
        return None
    if _startup_aot.source_digest() != source_digest():
        return None
    return _startup_aot.run_kernel_flat


def build(output_dir: Path | None = None) -> Path:
    """Compile the kernel ahead of time (numba.pycc) into an extension module.

    Parameters
    ----------
    output_dir : Path or None
        Where to write the module (None: this package's folder).

    Returns
    -------
    Path
        The path of the extension module written.
    """
    from numba.core.errors import NumbaPendingDeprecationWarning

    with warnings.catch_warnings():  # numba.pycc is "pending deprecation" since numba 0.57
        warnings.simplefilter("ignore", NumbaPendingDeprecationWarning)
        from numba.pycc import CC

    # lazy: the kernel module imports numba (≈0.25 s); only a build needs it
    from chaindrive.dynamics.transient.kernel import FLAT_SIGNATURE, run_kernel_flat

    digest = source_digest()
    cc = CC(MODULE)
    cc.output_dir = str(output_dir or _HERE)
    cc.verbose = False
    cc.target_cpu = "host"  # this processor's vector instructions (module docstring)

    @cc.export("source_digest", "i8()")
    def _digest() -> int:
        return digest

    # the numba dispatcher behind the typed decorator keeps the Python function as .py_func
    cc.export("run_kernel_flat", FLAT_SIGNATURE)(cast(Any, run_kernel_flat).py_func)
    cc.compile()
    built = sorted(Path(cc.output_dir).glob(MODULE + ".*"), key=lambda p: p.stat().st_mtime)
    return built[-1]


def main() -> int:
    """Command-line entry: build, or explain in one line why not (exit 0 either way: the
    ahead-of-time module is an optimisation, the package works without it)."""
    try:
        path = build()
    except Exception as exc:  # no compiler, no numba, …: the just-in-time path remains
        print(f"start-up kernel not compiled ahead of time ({type(exc).__name__}: {exc}); "
              "numba will compile it on first use", file=sys.stderr)
        return 0
    print(f"start-up kernel compiled ahead of time: {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
