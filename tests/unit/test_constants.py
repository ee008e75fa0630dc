"""One definition of each unit constant: 2π and the rpm and degree factors live in
``chaindrive.units`` only, and the presenters write no conversion factor of their own.

The source is parsed (:mod:`ast`, nothing imported). The tests fail on

(a) an assignment anywhere in ``src/chaindrive`` outside ``units.py`` whose value is 2π
    (``2 * math.pi``, ``2.0 * np.pi``, ``math.tau``, …), 30/π or π/30 (the rpm factors) or
    180/π or π/180 (the degree factors), written with any of ``math``/``np``/``numpy``;
(b) π (``math.pi``, ``np.pi``, ``math.tau``) written in a presenter (``cli``, ``report``,
    ``app``, ``plotting``, ``drawing``, ``display``): a presenter converts with the factors
    of :mod:`chaindrive.units` / :mod:`chaindrive.display`.
"""

from __future__ import annotations

import ast
import math
from pathlib import Path

import pytest

from chaindrive import units

PACKAGE = Path(__file__).resolve().parents[2] / "src" / "chaindrive"
PRESENTERS = ("cli", "report", "app", "plotting", "drawing.py", "display.py")
_PI_NAMES = {("math", "pi"), ("np", "pi"), ("numpy", "pi")}
_TAU_NAMES = {("math", "tau"), ("np", "tau"), ("numpy", "tau")}


def _attr(node: ast.AST) -> tuple[str, str] | None:
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
        return node.value.id, node.attr
    return None


def _number(node: ast.AST) -> float | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) \
            and not isinstance(node.value, bool):
        return float(node.value)
    return None


def _is_pi(node: ast.AST) -> bool:
    return _attr(node) in _PI_NAMES


def unit_constant(node: ast.AST) -> str | None:
    """The name of the unit constant ``node`` computes, or None."""
    if _attr(node) in _TAU_NAMES:
        return "2π"
    if not isinstance(node, ast.BinOp):
        return None
    left, right = node.left, node.right
    if isinstance(node.op, ast.Mult):
        for a, b in ((left, right), (right, left)):
            if _number(a) == 2.0 and _is_pi(b):
                return "2π"
    if isinstance(node.op, ast.Div):
        if _is_pi(right) and _number(left) in (30.0, 180.0):
            return f"{_number(left):g}/π"
        if _is_pi(left) and _number(right) in (30.0, 180.0):
            return f"π/{_number(right):g}"
    return None


def _sources() -> list[Path]:
    return sorted(p for p in PACKAGE.rglob("*.py") if p != PACKAGE / "units.py")


def definitions(tree: ast.AST) -> list[tuple[int, str]]:
    """(line, constant) of every assignment of a unit constant in ``tree``."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, (ast.Assign, ast.AnnAssign)) and node.value is not None:
            what = unit_constant(node.value)
            if what is not None:
                out.append((node.lineno, what))
    return out


def test_the_scan_finds_each_spelling() -> None:
    # the rule is only as good as its pattern: each spelling it is meant to refuse is refused
    for text, what in (("TWO_PI = 2.0 * math.pi", "2π"), ("w = 2 * np.pi", "2π"),
                       ("T: float = math.tau", "2π"), ("RPM = 30.0 / math.pi", "30/π"),
                       ("rpm = math.pi / 30", "π/30"), ("d = 180 / numpy.pi", "180/π")):
        assert definitions(ast.parse(text)) == [(1, what)], text
    assert definitions(ast.parse("x = 2 * math.pi * k / 6")) == []  # an expression, no constant


def test_units_holds_the_constants() -> None:
    assert 2.0 * math.pi == units.TWO_PI
    assert pytest.approx(1.0, rel=1e-15) == units.RPM_PER_RAD_S * units.RAD_S_PER_RPM
    assert pytest.approx(10 * math.pi, rel=1e-15) == 300 * units.RAD_S_PER_RPM  # 300 rpm
    assert pytest.approx(1.0, rel=1e-15) == units.DEG_PER_RAD * units.RAD_PER_DEG


def test_no_unit_constant_defined_outside_units() -> None:
    found = [f"{p.relative_to(PACKAGE)}:{line}: {what}" for p in _sources()
             for line, what in definitions(ast.parse(p.read_text(encoding="utf-8")))]
    assert not found, "define these in chaindrive.units and import them:\n" + "\n".join(found)


def _presenter_files() -> list[Path]:
    out: list[Path] = []
    for name in PRESENTERS:
        path = PACKAGE / name
        out.extend(sorted(path.rglob("*.py")) if path.is_dir() else [path])
    return out


def test_presenters_write_no_conversion_factor() -> None:
    found = []
    for p in _presenter_files():
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if _attr(node) in _PI_NAMES | _TAU_NAMES:
                found.append(f"{p.relative_to(PACKAGE)}:{node.lineno}")  # type: ignore[attr-defined]
    assert not found, "a presenter converts with chaindrive.units/display:\n" + "\n".join(found)
