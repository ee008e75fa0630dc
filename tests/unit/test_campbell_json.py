"""The JSON of the Campbell data numbers the modes as the resonance table does (the rigid-body
mode 0, the first elastic mode 1) and names a parametric zone's span, as the report's figures
and tables do."""

from __future__ import annotations

from pathlib import Path

import chaindrive

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_campbell_crossings_number_modes_and_name_spans_as_the_tables() -> None:
    a = chaindrive.analyze(chaindrive.load(EXAMPLES / "eight_sprocket.toml"), response=False)
    doc = a.to_dict()["dynamics"]
    crossings = doc["campbell"]["crossings"]
    elastic = [c for c in crossings if c["mode"] is not None]
    parametric = [c for c in crossings if c["mode"] is None]
    assert elastic and parametric
    assert min(c["mode"] for c in elastic) >= 1  # 0 is the rigid-body mode
    frequencies = doc["natural_frequencies_hz"]
    natural = doc["campbell"]["natural_frequencies_hz"][0]
    for c in elastic:  # the mode number indexes the list of every mode, rigid first
        assert frequencies[c["mode"]] == natural[c["mode"] - 1]
    spans = {f"{s.start_name}→{s.end_name}" for s in a.geometry.spans}
    assert all(c["excitation"].removeprefix("parametric span ") in spans for c in parametric)
