# SPDX-License-Identifier: GPL-3.0-or-later
"""Configuring the brush automatically (layer 8; Sec. 7.2): training samples (``samples``), the
target function Eq. 28 (``target``), the search - grid, steepest descent, the shrinking cube -
with the fit's settings and their defaults, declared once here (``search``: FitSettings), the
texture statistics of real writing the Qp2 stage also compares against (``texture``), and the
evaluations on a Dask cluster (``cluster``).

May import: every package below it (``core``, ``image``, ``brush``, ``paper``, ``surface``,
``engine``, ``writing``, ``picture``)."""
