"""Fixtures of the Python tests: the CLI they compare with and the data they share.

ctest (python/CMakeLists.txt) sets PYTHONPATH to the build tree's package, CROPSIGHT_CLI to the
built CLI and CROPSIGHT_SHARED_DATA_DIR to ../shared/data.
"""
import json
import os
import subprocess

import pytest

import cropsight as cs


def cli_path():
    path = os.environ.get("CROPSIGHT_CLI", "")
    if not path or not os.path.isfile(path):
        pytest.skip("CROPSIGHT_CLI is not set to the built cropsight CLI (ctest sets it)")
    return path


def run_cli(*args):
    """Runs the CLI; returns its stdout. A failure shows its stderr."""
    done = subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def run_cli_json(*args):
    return json.loads(run_cli(*args, "--json").strip().splitlines()[-1])


def shared_data(*parts):
    root = os.environ.get("CROPSIGHT_SHARED_DATA_DIR", "")
    path = os.path.join(root, *parts)
    if not root or not os.path.exists(path):
        pytest.skip(f"shared data {os.path.join(*parts)} not present (../shared/data)")
    return path


@pytest.fixture(scope="session")
def broccoli_pass(tmp_path_factory):
    """A short simulated broccoli pass (written by the library's simulator from Python)."""
    out = tmp_path_factory.mktemp("broccoli") / "seq"
    cs.simulate.broccoli(str(out), variety="uk", frames=6, seed=7)
    return str(out)
