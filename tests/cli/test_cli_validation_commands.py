"""Bad options of the commands: one line naming the option, the value and what is allowed,
exit status 2, nothing on stdout, never a traceback (catalog, robust, app, simulate,
schema)."""

from __future__ import annotations

import json
import re
import resource
import subprocess
import sys

import pytest

from chaindrive.cli import run
from chaindrive.io.design import SECTIONS
from chaindrive.linklevel import DURATION
from chaindrive.units import parse_quantity
from tests.conftest import EXAMPLES

JINDAL = str(EXAMPLES / "two_sprocket_jindal.toml")


def cli(capsys: pytest.CaptureFixture[str], *args: str) -> tuple[int, str, str]:
    """Run one command line in this process: (exit status, stdout, stderr)."""
    status = run(list(args))
    out, err = capsys.readouterr()
    return status, out, err


def assert_user_error(status: int, out: str, err: str, *parts: str) -> None:
    """Exit 2, nothing on stdout, one line on stderr holding every one of ``parts``."""
    assert status == 2, err
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("error: "), err
    assert "internal error" not in err and "Traceback" not in err
    for part in parts:
        assert part in err, (part, err)


# --------------------------------------------------------------------------- catalog
@pytest.mark.parametrize("args", [("catalog", ""), ("catalog", "  "), ("catalog", "", "--json"),
                                  ("catalog", "--materials", "")])
def test_catalog_empty_name_is_refused(capsys: pytest.CaptureFixture[str],
                                       args: tuple[str, ...]) -> None:
    status, out, err = cli(capsys, *args)
    assert_user_error(status, out, err, "got '")


@pytest.mark.parametrize("extra", [(), ("--json",)])
def test_catalog_unknown_standard_names_the_allowed_ones(capsys: pytest.CaptureFixture[str],
                                                         extra: tuple[str, ...]) -> None:
    status, out, err = cli(capsys, "catalog", "--standard", "bogus", *extra)
    assert_user_error(status, out, err, "--standard:", "'bogus'", "'ISO 606'", "'ANSI'",
                      "'GOST 13568'", "'polymer'")


def test_catalog_standard_filters_by_the_standard(capsys: pytest.CaptureFixture[str]) -> None:
    for given, standard in (("iso", "ISO 606"), ("GOST 13568", "GOST 13568"),
                            ("Polymer", "polymer")):
        status, out, err = cli(capsys, "catalog", "--standard", given, "--json")
        assert status == 0, err
        chains = json.loads(out)["chains"]
        assert chains and {c["standard"] for c in chains} == {standard}
    status, out, _ = cli(capsys, "catalog", "--standard", "ANSI", "--json")
    chains = json.loads(out)["chains"]
    assert status == 0 and chains and all(c["ansi"] for c in chains)


def test_catalog_standard_does_not_apply_to_materials(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = cli(capsys, "catalog", "--materials", "--standard", "ISO 606")
    assert_user_error(status, out, err, "--standard:", "--materials")


def test_catalog_standard_must_agree_with_the_chain_named(
        capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = cli(capsys, "catalog", "ISO 606 16B-1", "--standard", "GOST")
    assert_user_error(status, out, err, "--standard:", "ISO 606 16B-1", "GOST 13568")
    status, out, _ = cli(capsys, "catalog", "ISO 606 16B-1", "--standard", "ISO", "--json")
    assert status == 0 and json.loads(out)["chains"][0]["designation"] == "ISO 606 16B-1"


# --------------------------------------------------------------------------- robust
@pytest.mark.parametrize("seed", ["-1", "2147483648"])
def test_robust_seed_has_the_bounds_of_the_file_field(capsys: pytest.CaptureFixture[str],
                                                      seed: str) -> None:
    status, out, err = cli(capsys, "robust", JINDAL, "--modal", "--seed", seed)
    assert_user_error(status, out, err, "--seed:", f"got {seed}", "from 0 to 2147483647")


@pytest.mark.parametrize("samples", ["0", "-5", "7"])
def test_robust_samples_has_the_bounds_of_the_file_field(capsys: pytest.CaptureFixture[str],
                                                         samples: str) -> None:
    status, out, err = cli(capsys, "robust", JINDAL, "--modal", "--samples", samples)
    assert_user_error(status, out, err, "--samples:", f"got {samples}", "from 8 to 1048576")


def _limit_memory() -> None:
    """In the child: at most 8 GB of address space, so that a regression fails with a
    MemoryError instead of exhausting the machine."""
    resource.setrlimit(resource.RLIMIT_AS, (8 << 30, 8 << 30))


@pytest.mark.concurrency  # a subprocess with a memory limit (the unchecked option took > 20 GB)
def test_robust_samples_above_the_file_limit_is_refused_before_any_work() -> None:
    proc = subprocess.run([sys.executable, "-m", "chaindrive", "robust", JINDAL, "--modal",
                           "--samples", "100000000"], capture_output=True, text=True,
                          check=False, timeout=300, preexec_fn=_limit_memory)
    assert_user_error(proc.returncode, proc.stdout, proc.stderr, "--samples:",
                      "got 100000000", "from 8 to 1048576")


@pytest.mark.parametrize("workers", ["0", "-2"])
def test_robust_workers_must_be_at_least_one(capsys: pytest.CaptureFixture[str],
                                             workers: str) -> None:
    status, out, err = cli(capsys, "robust", JINDAL, "--modal", "--workers", workers)
    assert_user_error(status, out, err, "--workers", workers, "1<=x<=256")


def test_robust_wear_is_named_as_the_option(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = cli(capsys, "robust", JINDAL, "--modal", "--wear", "bogus")
    assert_user_error(status, out, err, "--wear:", "'bogus'", '"life"')


# --------------------------------------------------------------------------- app
@pytest.mark.concurrency  # a subprocess: on a mistake the web server must never start
@pytest.mark.parametrize("port", ["99999", "-1", "0", "65536"])
def test_app_port_out_of_range(port: str) -> None:
    proc = subprocess.run([sys.executable, "-m", "chaindrive", "app", "--port", port],
                          capture_output=True, text=True, check=False, timeout=120)
    assert_user_error(proc.returncode, proc.stdout, proc.stderr, "--port", port, "65535")


# --------------------------------------------------------------------------- examples, limits
def test_simulate_duration_example_lies_within_its_range(
        capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = cli(capsys, "simulate", JINDAL, "--model", "links", "--duration", "5")
    assert_user_error(status, out, err, "--duration:", "missing unit")
    example = re.search(r'write it like "([^"]+)"', err)
    assert example is not None, err
    assert DURATION.contains(parse_quantity(example.group(1), "time", "example"))


def test_schema_prints_whole_numbers_in_full(capsys: pytest.CaptureFixture[str]) -> None:
    status, out, err = cli(capsys, "schema", "--json")
    assert status == 0, err
    doc = json.loads(out)
    assert set(doc) == set(SECTIONS)
    whole = [f for fields in doc.values() for f in fields if f["kind"] in ("int", "links")]
    assert whole and not [f["allowed"] for f in whole if re.search(r"\de[+-]?\d", f["allowed"])]
    allowed = {f["field"]: f["allowed"] for f in doc["uncertainty"]}
    assert allowed["samples"] == "a whole number from 8 to 1048576"
    assert allowed["seed"] == "a whole number from 0 to 2147483647"
    ramp = next(f for f in doc["motor"] if f["field"] == "ramp_time")
    assert ramp["example"] != "2400 h" and "2400 h" not in ramp["allowed"]
    status, out, err = cli(capsys, "schema")
    assert status == 0 and "1.04858e+06" not in out and "2.14748e+09" not in out
