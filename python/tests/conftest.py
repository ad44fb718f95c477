"""Shared fixtures: the command-line program the package is compared against."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli():
    """A function running ``friction-lab ARGS`` (the workspace's build, made if missing;
    ``FRICTION_LAB_BIN`` names another) that returns the completed process."""
    binary = os.environ.get("FRICTION_LAB_BIN")
    if binary is None:
        subprocess.run(["cargo", "build", "--quiet", "--bin", "friction-lab"], cwd=ROOT,
                       check=True)
        binary = str(ROOT / "target" / "debug" / "friction-lab")

    def run(*args):
        return subprocess.run([binary, *map(str, args)], capture_output=True, text=True)

    return run
