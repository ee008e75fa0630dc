"""A package's public names imported from their submodules on first use (PEP 562), so that
importing the package does not import what only some of its names need (internal)."""

from __future__ import annotations

import importlib
import sys
from collections.abc import Mapping
from typing import Any

__all__ = ["lazy_attribute"]


def lazy_attribute(package: str, homes: Mapping[str, str], name: str) -> Any:
    """The public name ``name`` of ``package``, imported from its submodule and kept in the
    package's namespace (a package's module ``__getattr__`` returns it).

    Parameters
    ----------
    package : str
        The package's dotted name (its ``__name__``).
    homes : mapping of str to str
        Public name → the submodule that defines it, relative to ``package``.
    name : str
        The name asked for.

    Returns
    -------
    object
        What the submodule defines under ``name``.

    Raises
    ------
    AttributeError
        ``name`` is not one of ``homes``.
    """
    home = homes.get(name)
    if home is None:
        raise AttributeError(f"module {package!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{package}.{home}"), name)
    setattr(sys.modules[package], name, value)
    return value
