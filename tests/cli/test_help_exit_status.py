"""`chaindrive --help` states the exit statuses the safety net returns (chaindrive.cli.safety)."""

from __future__ import annotations

import re

from typer.testing import CliRunner

from chaindrive.cli import app
from chaindrive.cli.safety import EXIT_INTERNAL, EXIT_USER_ERROR


def test_help_lists_every_exit_status_the_commands_return() -> None:
    out = CliRunner().invoke(app, ["--help"]).output
    assert "Exit status:" in out
    listed = {int(m) for m in re.findall(r"^\s+(\d+)\s", out.split("Exit status:")[1], re.M)}
    assert listed == {0, EXIT_USER_ERROR, EXIT_INTERNAL}
    assert "128+N" in out
