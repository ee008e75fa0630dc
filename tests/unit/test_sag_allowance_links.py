"""The installed centre distance shortened by a sag allowance Δa = k·a, and the "nearest"
even link count.

Sag allowance: textbooks install the chain with the centre distance shortened by
Δa = (0.002 … 0.004)·a so that the slack span sags [ChainDesignRU, §7], [Bhandari2010,
ex. 14.4]. In a two-sprocket drive the take-up moves along the line of centres, so the
installed centre distance is exactly a·(1 − k) of the tight one (closed form). Links: the
even count nearer to the tight length L_p (the one above on a tie) [ChainDesignRU, §6];
Jindal's ex. 30-2 rounds 80.21 pitches to 80 links [Jindal2010].
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

import chaindrive
from chaindrive.analysis import geometry_dict
from chaindrive.errors import DesignError
from chaindrive.geometry.contour import contour_geometry, round_links

EXAMPLE = Path(__file__).parents[2] / "src" / "chaindrive" / "examples" / "two_sprocket_jindal.toml"


def _with_chain(**fields: object) -> chaindrive.model.Drive:
    drive = chaindrive.load(EXAMPLE)
    return dataclasses.replace(drive, chain=dataclasses.replace(drive.chain, **fields))


@pytest.mark.parametrize("k", [0.002, 0.003, 0.004])
def test_two_sprocket_centre_distance_shortened_by_k_a(k: float) -> None:
    tight = contour_geometry(chaindrive.load(EXAMPLE))
    installed = contour_geometry(_with_chain(sag_allowance=k))
    assert tight.center_distance is not None and installed.center_distance is not None
    assert installed.center_distance == pytest.approx(tight.center_distance * (1 - k), rel=1e-9)
    assert installed.sag_allowance == pytest.approx(k * tight.center_distance, rel=1e-9)
    assert installed.links == tight.links and installed.slack > 0  # the chain now sags
    assert geometry_dict(installed)["sag_allowance_mm"] == pytest.approx(
        k * tight.center_distance * 1e3)
    assert geometry_dict(tight)["sag_allowance_mm"] == 0.0


def test_sag_allowance_is_checked(tmp_path: Path) -> None:
    with pytest.raises(DesignError, match="chain.sag_allowance"):
        _with_chain(sag_allowance=0.02)
    with pytest.raises(DesignError, match="not both"):
        _with_chain(sag_allowance=0.003, sag=0.02)
    text = EXAMPLE.read_text().replace('designation = "ISO 606 06B-1"',
                                       'designation = "ISO 606 06B-1"\nsag_allowance = 0')
    (tmp_path / "d.toml").write_text(text)
    with pytest.raises(DesignError, match=r"chain\.sag_allowance"):
        chaindrive.load(tmp_path / "d.toml")
    seed = chaindrive.load(EXAMPLE.with_name("seed_three_sprocket.toml"))  # fixed centres
    assert seed.adjustable_index is None
    seed = dataclasses.replace(seed, chain=dataclasses.replace(seed.chain, sag_allowance=0.003))
    with pytest.raises(DesignError, match="no sprocket is adjustable"):
        contour_geometry(seed)


@pytest.mark.parametrize(("tight", "nearest"), [(80.21, 80), (81.2, 82), (81.0, 82),
                                                (131.72, 132), (130.9, 130)])
def test_nearest_even_count(tight: float, nearest: int) -> None:
    assert round_links(tight, nearest=True) == nearest


def test_nearest_in_a_design(tmp_path: Path) -> None:
    text = EXAMPLE.read_text().replace('designation = "ISO 606 06B-1"',
                                       'designation = "ISO 606 06B-1"\nlinks = "nearest"')
    (tmp_path / "d.toml").write_text(text)
    a = chaindrive.analyze(chaindrive.load(tmp_path / "d.toml"), response=False)
    tight = a.length_choice.tight_pitches
    assert a.geometry.links == round_links(tight, nearest=True)
    assert a.length_choice.chosen in ("round down", "round up")
    (tmp_path / "e.toml").write_text(text.replace('"nearest"', '"nearst"'))
    with pytest.raises(DesignError, match="nearest"):
        chaindrive.load(tmp_path / "e.toml")
