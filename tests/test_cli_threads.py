"""The command's linear algebra libraries run one thread each unless the user says otherwise.

``report`` forks one worker per core; each worker's BLAS pool would start as many threads
again, and they competed with the other worker for the cores. The variables only take effect
if they are set before NumPy is first imported: the command line sets them in its entry
point, which must not import NumPy itself.
"""

from __future__ import annotations

import subprocess
import sys

from wheeled_dyn.cli import main as cli


def test_unset_thread_counts_become_one_and_a_users_count_is_kept():
    environ = {"OMP_NUM_THREADS": "4"}
    cli.one_thread_each(environ)
    assert environ["OMP_NUM_THREADS"] == "4"
    assert all(environ[name] == "1" for name in cli.THREAD_VARIABLES if name != "OMP_NUM_THREADS")


def test_the_entry_point_is_reached_before_numpy_is_imported():
    code = "import sys, wheeled_dyn.cli.main; print('numpy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "False"
