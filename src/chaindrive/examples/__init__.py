"""Ready drives for the docs, the tests and the web page: design files shipped with the
package (``examples/`` in the source tree points here).

::

    from chaindrive import examples
    examples.names()                         # ('eight_sprocket', ...)
    drive = examples.load("seed_three_sprocket")
"""

from __future__ import annotations

from importlib import resources
from importlib.abc import Traversable

from chaindrive._docstrings import shared_parameters
from chaindrive.errors import DesignError, did_you_mean
from chaindrive.io.design import drive_from_mapping, parse_toml
from chaindrive.model import Drive

__all__ = ["load", "names", "text"]


def _files() -> dict[str, Traversable]:
    root = resources.files(__name__)
    return {f.name.removesuffix(".toml"): f for f in root.iterdir()
            if f.name.endswith(".toml")}


def names() -> tuple[str, ...]:
    """The names of the bundled designs.

    Returns
    -------
    tuple of str
        File names without ``.toml``, sorted.
    """
    return tuple(sorted(_files()))


@shared_parameters
def text(name: str) -> str:
    """The TOML text of a bundled design.

    %(params_example)s

    Returns
    -------
    str
        The design file's text.

    Raises
    ------
    DesignError
        On the field ``example`` for an unknown name, suggesting the closest.
    """
    files = _files()
    if name not in files:
        raise DesignError("example", f"no bundled design {name!r}" + did_you_mean(name, files)
                          + f" (known: {', '.join(sorted(files))})")
    return files[name].read_text(encoding="utf-8")


@shared_parameters
def load(name: str) -> Drive:
    """The validated drive of a bundled design.

    %(params_example)s

    Returns
    -------
    Drive
        The design, validated as :func:`chaindrive.load` validates a file.
    """
    return drive_from_mapping(parse_toml(text(name), f"{name}.toml"))
