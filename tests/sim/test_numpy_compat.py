# SPDX-License-Identifier: GPL-3.0-or-later
"""The engine's direct ufunc calls find numpy's ufuncs on numpy 1.26 and 2.x, also once
something (Blender does) has imported numpy._core, which numpy 1.26 has without umath."""

import subprocess
import sys

from tests.paths import ROOT


def test_the_clip_ufunc_is_found_after_numpy_core_was_imported():
    code = (
        "import numpy._core, numpy as np\n"
        "from sim.core.frames import clip\n"
        "assert clip(np.array([1.0, 5.0]), 2.0, 3.0).tolist() == [2.0, 3.0]\n"
    )
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
