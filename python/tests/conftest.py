"""The command line the package is compared with, and cases to compare on."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any

import pytest

import microslip

REPOSITORY = Path(__file__).resolve().parents[2]

#: Compliances of every family without a table, each admissible on every cycle below.
COMPLIANCES = [
    "persson:gamma=1,sigma=1",
    "power:c=1,beta=-0.5",
    "hertz:r=1,estar=1",
    "rational:a=0.5,b=1,c=0.1",
    "exp:a=1,c=1,d=0.2",
    "2*persson:gamma=1,sigma=1+const:c=0.5",
]

#: The first W of the project's README.
FIRST = {
    "p0": "1",
    "p1": "0.4",
    "q1": "0.5",
    "phi": "0.4pi",
    "friction": "1",
    "lambda": "1",
    "compliance": "persson:gamma=1,sigma=1",
}

#: The fields of a case in the order of a batch CSV header.
FIELDS = ["p0", "p1", "q0", "q1", "phi", "friction", "lambda", "compliance"]


def cli_path() -> Path:
    """`microslip` built by `cargo build --release` at the repository's root (or
    $MICROSLIP_CLI)."""
    path = Path(os.environ.get("MICROSLIP_CLI", REPOSITORY / "target" / "release" / "microslip"))
    if not path.is_file():
        pytest.fail(f"{path} is missing: build it with `cargo build --release` first")
    return path


def run_cli(*arguments: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [str(cli_path()), *arguments], capture_output=True, text=True, timeout=600, check=False
    )


def case_flags(case: dict[str, str]) -> list[str]:
    flags = []
    for name, value in case.items():
        flags += [f"--{name}", value]
    return flags


def cli_json(command: str, case: dict[str, str], *more: str) -> dict[str, Any]:
    done = run_cli(command, *case_flags(case), *more, "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def case_of(text: dict[str, str]) -> microslip.Case:
    """The Case of a dict keyed as the command line's flags."""
    keyword = {("lam" if name == "lambda" else name): value for name, value in text.items()}
    return microslip.Case(**keyword)
