# SPDX-License-Identifier: GPL-3.0-or-later
"""The command line, ``python -m sim`` (layer 9): the parser and dispatch (``main``), one module
per command group (``render``, ``write``, ``imitate``, ``fit``, the iou command's evaluation
``evaluate``) and the speed benchmark (``bench``).

May import: every package of ``sim``."""
