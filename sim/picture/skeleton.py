# SPDX-License-Identifier: GPL-3.0-or-later
"""The skeleton of a picture's ink as a graph (numpy only): the ink's skeleton (Zhang-Suen, its
staircase corners thinned) cut at its junctions into chains, each from one end to the other,
and the junctions as nodes (see ``strokes``, which reads the strokes off it). Coordinates are
image pixels (x right, y down), as floats."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..image import morph as M
from ..image.filters import _gaussian, skeleton


@dataclass
class Chain:
    """Skeleton pixels from one end to the other; ``ends`` are node ids (-1: a free end)."""

    pts: np.ndarray  # (K, 2) x, y
    ends: list


@dataclass
class Node:
    centre: np.ndarray  # (2,) x, y
    radius: float  # the ink's half-width at the junction
    chains: list = field(default_factory=list)  # (chain id, which end: 0 first, 1 last)


def _neighbour_count(s: np.ndarray) -> np.ndarray:
    c = np.zeros(s.shape, dtype=np.int8)
    for dy, dx in M.NEIGHBOURS_8:
        c += M._shift(s, dy, dx, False)
    return c


def _simple(s: np.ndarray, y: int, x: int) -> bool:
    """The pixel's set neighbours are one 8-connected piece and two or three: taking it away
    disconnects nothing and ends no line."""
    h, w = s.shape
    nb = [
        (dy, dx)
        for dy, dx in M.NEIGHBOURS_8
        if 0 <= y + dy < h and 0 <= x + dx < w and s[y + dy, x + dx]
    ]
    if not 2 <= len(nb) <= 3:
        return False
    seen, todo = {nb[0]}, [nb[0]]
    while todo:
        a = todo.pop()
        for b in nb:
            if b not in seen and max(abs(a[0] - b[0]), abs(a[1] - b[1])) <= 1:
                seen.add(b)
                todo.append(b)
    return len(seen) == len(nb)


def _thin_corners(s: np.ndarray) -> np.ndarray:
    """Remove the redundant corner pixels of 4-connected staircases one at a time (a simple
    point, ``_simple``), so that a one-pixel-wide skeleton has no false junctions."""
    s = s.copy()
    for y, x in np.argwhere(s & (_neighbour_count(s) >= 2)):
        if _simple(s, int(y), int(x)):
            s[y, x] = False
    return s


def _walk(start, members: set) -> list:
    """Pixels of a chain from ``start``, each next one an unvisited 8-neighbour (4-neighbours
    first)."""
    path, seen = [start], {start}
    cur = start
    while True:
        y, x = cur
        nxt = None
        for dy, dx in ((-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (-1, 1), (1, -1), (1, 1)):
            q = (y + dy, x + dx)
            if q in members and q not in seen:
                nxt = q
                break
        if nxt is None:
            return path
        path.append(nxt)
        seen.add(nxt)
        cur = nxt


def _node_of(y: int, x: int, jlab: np.ndarray) -> int:
    h, w = jlab.shape
    for dy, dx in M.NEIGHBOURS_8:
        yy, xx = y + dy, x + dx
        if 0 <= yy < h and 0 <= xx < w and jlab[yy, xx]:
            return int(jlab[yy, xx]) - 1
    return -1


def skeleton_graph(mask: np.ndarray, dist: np.ndarray) -> tuple[list, list]:
    """The skeleton of the ink as chains and junction nodes."""
    n = mask.shape[0]
    smooth = _gaussian(mask.astype(np.float64), max(1.5 * n / 512, 0.7)) > 0.5
    s = _thin_corners(skeleton(smooth))
    count = _neighbour_count(s)
    junction = s & (count >= 3)
    jlab, k = M.label(junction)
    nodes = []
    for i in range(k):
        ys, xs = np.nonzero(jlab == i + 1)
        nodes.append(Node(np.array([xs.mean(), ys.mean()]), float(dist[ys, xs].max())))
    clab, kc = M.label(s & ~junction)
    chains = []
    ys, xs = np.nonzero(clab)
    order = np.argsort(clab[ys, xs], kind="stable")
    bounds = np.searchsorted(clab[ys, xs][order], np.arange(1, kc + 2))
    for i in range(kc):
        idx = order[bounds[i] : bounds[i + 1]]
        members = {(int(ys[j]), int(xs[j])) for j in idx}
        ends = [p for p in members if _chain_degree(p, members) <= 1] or [min(members)]
        path = _walk(ends[0], members)
        a, b = path[0], path[-1]
        pts = np.array([[p[1], p[0]] for p in path], dtype=np.float64)
        na = _node_of(*a, jlab) if count[a] != 1 else -1
        nb = _node_of(*b, jlab) if count[b] != 1 else -1
        if len(path) == 1:
            nb = _other_node(a, jlab, na)
        chains.append(Chain(pts, [na, nb]))
    _link(chains, nodes)
    return chains, nodes


def _chain_degree(p, members: set) -> int:
    y, x = p
    return sum((y + dy, x + dx) in members for dy, dx in M.NEIGHBOURS_8)


def _other_node(p, jlab, first: int) -> int:
    h, w = jlab.shape
    for dy, dx in M.NEIGHBOURS_8:
        yy, xx = p[0] + dy, p[1] + dx
        if 0 <= yy < h and 0 <= xx < w and jlab[yy, xx] and jlab[yy, xx] - 1 != first:
            return int(jlab[yy, xx]) - 1
    return -1


def _link(chains: list, nodes: list) -> None:
    for node in nodes:
        node.chains = []
    for ci, c in enumerate(chains):
        for end in (0, 1):
            if c.ends[end] >= 0:
                nodes[c.ends[end]].chains.append((ci, end))


def _length(pts: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum()) if len(pts) > 1 else 0.0


def _outward(c: Chain, end: int) -> np.ndarray:
    """The chain's points running away from the given end."""
    return c.pts if end == 0 else c.pts[::-1]
