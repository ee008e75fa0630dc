"""Every bad input of issue 2 gives one line naming the field, exit status 2, no traceback,
and nothing on stdout (nothing written half-way)."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.conftest import EXAMPLES, cli_in_process

GOOD = (EXAMPLES / "seed_three_sprocket.toml").read_text(encoding="utf-8")


#: The command run in this process: what these tests assert (what it prints and writes, its
#: exit status) is the command's, not the process's.
run_cli = cli_in_process


def sprocket(name: str, teeth: object = 17, x: str = '"0 mm"', y: str = '"0 mm"',
             extra: str = "") -> str:
    return (f'\n[[sprockets]]\nname = "{name}"\nteeth = {teeth}\nx = {x}\ny = {y}\n{extra}\n')


HEAD = '[drive]\nname = "t"\n\n[chain]\ndesignation = "ISO 606 08B-1"\n'
TWO = (HEAD + sprocket("A", extra='role = "driver"\nspeed = "100 rpm"')
       + sprocket("B", x='"500 mm"'))

CASES: dict[str, tuple[str, str]] = {
    "toml syntax": ("[drive\nname = 1", "line 1"),
    "unknown field": (TWO.replace('teeth = 17\nx = "500 mm"', 'teeht = 17\nx = "500 mm"'),
                      "sprockets[1].teeht: unknown field; did you mean 'teeth'?"),
    "unknown section": (TWO + "\n[chian]\n", "chian: unknown section; did you mean 'chain'?"),
    "missing unit": (TWO.replace('x = "500 mm"', 'x = "500"'), "sprockets[1].x: missing unit"),
    "number without unit": (TWO.replace('x = "500 mm"', "x = 500"),
                            "sprockets[1].x: must be a string with a unit"),
    "unknown unit": (TWO.replace('x = "500 mm"', 'x = "500 furlongz"'),
                     "sprockets[1].x: unknown unit"),
    "wrong kind of unit": (TWO.replace('"100 rpm"', '"300 kg"'),
                           "sprockets[0].speed: '300 kg' is not a speed"),
    "fractional teeth": (TWO.replace("teeth = 17\nx = \"500 mm\"", "teeth = 3.5\nx = \"500 mm\""),
                         "sprockets[1].teeth: must be a whole number from 6 to 150, got 3.5"),
    "zero speed": (TWO.replace('"100 rpm"', '"0 rpm"'), "sprockets[0].speed: must be"),
    "negative inertia": (TWO.replace('x = "500 mm"', 'x = "500 mm"\ninertia = "-0.1 kg*m^2"'),
                         "sprockets[1].inertia: must be"),
    "zero teeth": (TWO.replace("teeth = 17\nx = \"500 mm\"", "teeth = 0\nx = \"500 mm\""),
                   "sprockets[1].teeth: must be a whole number from 6 to 150, got 0"),
    "speed on a driven sprocket": (TWO.replace('x = "500 mm"', 'x = "500 mm"\nspeed = "50 rpm"'),
                                   "sprockets[1].speed: give the speed on the driver only"),
    "negative power": (TWO.replace('name = "t"', 'name = "t"\npower = "-1 kW"'),
                       "drive.power: must be"),
    "no driver": (TWO.replace('role = "driver"\nspeed = "100 rpm"', ""),
                  "sprockets.role: the driver is missing"),
    "two drivers": (TWO.replace('x = "500 mm"\ny = "0 mm"\n', 'x = "500 mm"\ny = "0 mm"\n'
                                'role = "driver"\n'),
                    "sprockets.role: exactly one sprocket must be the driver, got 2"),
    "one sprocket": (HEAD + sprocket("A", extra='role = "driver"\nspeed = "1 rpm"'),
                     "sprockets: a contour needs 2 to 24 sprockets, got 1"),
    "25 sprockets": (HEAD + "".join(sprocket(f"S{i}", x=f'"{i * 200} mm"') for i in range(25)),
                     "sprockets: a contour needs 2 to 24 sprockets, got 25"),
    "duplicate names": (TWO.replace('name = "B"', 'name = "A"'),
                        "sprockets[1].name: duplicate name 'A'"),
    "unknown chain": (TWO.replace("ISO 606 08B-1", "ISO 606 08X-1"),
                      "chain.designation: "),
    "overlap": (TWO.replace('x = "500 mm"', 'x = "30 mm"'), "overlap"),
    "cannot close": (HEAD + sprocket("A", extra='role = "driver"\nspeed = "100 rpm"')
                     + sprocket("B", x='"1000 mm"', y='"1000 mm"')
                     + sprocket("C", x='"1000 mm"') + sprocket("D", y='"1000 mm"'),
                     "cannot close"),
    "bad role": (TWO.replace('role = "driver"', 'role = "drivr"'),
                 "sprockets[0].role: must be one of \"driver\", \"driven\", \"idler\", got 'drivr';"
                 " did you mean 'driver'?"),
    "bad driver duty": (TWO.replace('name = "t"', 'name = "t"\ndriver = "bumpy"'),
                        'drive.driver: must be one of "smooth", "slight shock", "moderate '
                        "shock\", got 'bumpy'"),
    "bad driven duty": (TWO.replace('name = "t"', 'name = "t"\ndriven = "slight shock"'),
                        'drive.driven: must be one of "smooth", "moderate shock", "heavy '
                        "shock\", got 'slight shock'"),
    "bad rotation": (TWO.replace('name = "t"', 'name = "t"\nrotation = "left"'),
                     "drive.rotation: must be one of \"cw\", \"ccw\", got 'left'"),
    "negative required life": (TWO.replace('name = "t"', 'name = "t"\nrequired_life = "-5 h"'),
                               "drive.required_life: must be a time"),
    "required life not a time": (TWO.replace('name = "t"', 'name = "t"\nrequired_life = "5 kg"'),
                                 "drive.required_life: '5 kg' is not a time"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_input_is_one_line_and_exit_2(case: str, tmp_path: Path) -> None:
    text, expected = CASES[case]
    design = tmp_path / "bad.toml"
    design.write_text(text, encoding="utf-8")
    proc = run_cli("analyze", str(design), "--json")
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1, proc.stderr
    assert "Traceback" not in proc.stderr
    assert expected in lines[0]


def test_missing_file(tmp_path: Path) -> None:
    proc = run_cli("analyze", str(tmp_path / "nope.toml"))
    assert proc.returncode == 2
    assert proc.stderr.strip().endswith("no such design file")


def test_unknown_chain_suggests_the_nearest(tmp_path: Path) -> None:
    design = tmp_path / "bad.toml"
    design.write_text(TWO.replace("ISO 606 08B-1", "ISO 606 08B-l"), encoding="utf-8")
    proc = run_cli("analyze", str(design))
    assert proc.returncode == 2
    assert "did you mean 'ISO 606 08B-" in proc.stderr


def test_good_file_still_passes() -> None:
    proc = run_cli("analyze", str(EXAMPLES / "seed_three_sprocket.toml"), "--json")
    assert proc.returncode == 0, proc.stderr
    assert GOOD  # the example file exists and is read
