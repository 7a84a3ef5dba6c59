# SPDX-License-Identifier: GPL-3.0-or-later
"""A pytest plugin (``-p tests.collect`` in pyproject.toml): the repository's root is the
add-on, whose ``__init__.py`` is no test package. pytest would import it as one before the
first test (``Package.setup``): as the package named after the checkout's folder, which fails
for a folder whose name is no Python name (``virtual-hairy-brush``, ``artist-b``). The root is
collected as a plain folder instead, whatever its name."""

import pytest


@pytest.hookimpl(tryfirst=True)
def pytest_collect_directory(path, parent):
    if path == parent.config.rootpath:
        return pytest.Dir.from_parent(parent, path=path)
    return None
