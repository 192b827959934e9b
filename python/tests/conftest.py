import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs the volspline command line the build made (VOLSPLINE_CLI, set by ctest)."""
    path = os.environ.get("VOLSPLINE_CLI")
    if not path:
        pytest.skip("VOLSPLINE_CLI is not set (run through ctest)")

    def run(*args):
        result = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        return result.returncode, result.stdout, result.stderr

    return run
