# SPDX-License-Identifier: GPL-3.0-or-later
"""Images as numpy arrays (layer 1): the bounded PNG reader and writer (``png``), the numpy
filters of binary and grey images (``filters``: Gaussian, Otsu, erosion, dilation, the median,
thinning, the perimeter, distances), the morphology of the picture reader (``morph``:
labels, distance transforms, resizing), and the exports of issue 29 (the ink matte ``matte``,
prints at a size and DPI ``prints`` with ``resample`` and the ``tiff`` writer, the outline as
SVG ``svg`` from ``contours``).

May import: ``core``."""
