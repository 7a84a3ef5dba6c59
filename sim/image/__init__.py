# SPDX-License-Identifier: GPL-3.0-or-later
"""Images as numpy arrays (layer 1): the bounded PNG reader and writer (``png``), the numpy
filters of binary and grey images (``filters``: Gaussian, Otsu, erosion, dilation, the median,
thinning, the perimeter, distances) and the morphology of the picture reader (``morph``:
labels, distance transforms, resizing).

May import: ``core``."""
