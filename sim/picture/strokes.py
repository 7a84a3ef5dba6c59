# SPDX-License-Identifier: GPL-3.0-or-later
"""The strokes of a picture's ink (numpy only): the ink's skeleton as a graph of chains between
junctions and free ends (``skeleton``), short spurs pruned, the two junctions a thick crossing
thins into merged, and at every junction the chains that continue each other by direction
(nearly opposite ways out) joined across it, so that a horizontal runs on through the vertical
that crosses it; a chain that ends at a junction (the stem of a T) runs on to its centre. Each
stroke carries its width along it (twice the distance to the paper), read across a junction
from either side of it. Coordinates are image pixels (x right, y down), as floats."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..core import exact
from ..core.exact import matmul
from ..image import morph as M
from .skeleton import Chain, Node, _length, _link, _outward, skeleton_graph

CONTINUE_COS = -0.77  # two ways out of a junction continue each other within ~40 degrees
LOOSE_COS = -0.5  # ... and a short overhang continues a stroke within 60 degrees
SPUR = 2.0  # a chain from a free end into a junction shorter than this times its half-width
HOOK_COS = 0.0  # ... and a hook's two ways out lie within 90 degrees of each other (0.3, ~70:
# 鸟's foot in 鹤 and 雨's 横折钩 in gkai, ~80, were read as a leg ending at the junction and
# a hook of its own, the heel between them unwritten)
HOOK_SPUR = 1.5  # ... but the farthest of a junction's spurs this long (times its half-width)
OVERHANG_REACH = 1.3  # ... and a spur this long (times its half-width) straight on from a chain
HOOK_CLEAR = 1.2  # ... and this many times as long as the next is a hook's tip, kept
STAND_RISE = 0.3  # a standing stroke's way out of its foot rises by this share or more
HEEL_FLAT = 0.3  # ... and a spur off its foot within this share of level is its heel (_heel_foot)
TIP = 0.5  # a free end runs on to this times the stroke's half-width short of where the ink
# ends: where stroke data's medians end (hanzi-writer's, which the writer's reach to the tips
# and its lift at a stroke's end are made for: 0.46-0.51 of the half-width, median over the
# bundled and unseen characters); 0.1 overshot every free end by the brush's round tip
TIP_TURN = np.radians(75.0)  # a spur pruned at a junction is the tip of a stroke ending there
# when it runs on within this of the stroke's way into the junction (``_tips``)
TIP_STANDING = 0.25  # ... preferring a standing stroke by this much of the cosine: at a corner
# where a vertical and a horizontal start (口's top left) the vertical is written first, and
# its entry is the tip
TIP_MIN = (0.5, 1.0, 1.6)  # ... its skeleton reaches the second times the junction's
# half-width from its centre; or, pointing up (TIP_UP: the 露锋 entry of a standing stroke, at
# 口's top left), the first, and the ink along it the third (an L's square outer corner: 1.41;
# the skeleton stops a half-width or so short of a tip, blurred pictures' most: 品 at 150 px).
# A foot past the corner where strokes end keeps the skeleton's reach: the brush's lift there
# trails a thin tail past the foot (语's 口 at 300 px)
TIP_UP = 0.3  # ... the way out of the junction rises by this share of its length or more
DOT = (1.5, 0.7)  # a dot touching a stroke stands out this far past its edge and is this thick
# (times the stroke's half-width there; a bump a brush's entry or turn leaves: 0.4-1.0 out)
SPAN = 2.5  # a node merged from a thick crossing's junctions is at most this many of its
# ink's half-widths across (``_merge_close_nodes``)
ZONE = 1.3  # a junction's zone: this times the ink's half-width there, plus a pixel


@dataclass
class Stroke:
    """A stroke recovered from the picture: its centre line and half-width along it (pixels),
    and the nodes it passes through (``through``) or ends at (``touches``)."""

    pts: np.ndarray  # (K, 2) x, y
    radius: np.ndarray  # (K,)
    through: set = field(default_factory=set)
    touches: set = field(default_factory=set)
    joints: dict = field(default_factory=dict)  # node id -> its centre (x, y)


def _merge_close_nodes(chains: list, nodes: list) -> tuple[list, list]:
    """A thick crossing thins into two junctions joined by a short chain: one node. The
    shortest such chains merge first, and a merge that would make a node wider across than
    SPAN times its ink's half-width is not made: heavy writing's crossings along one stroke
    (里's vertical through 日's and 土's 横s, each about a half-width of counter apart) are
    crossings of their own, not one node (merged in a chain, 里's vertical and its five
    crossings became one node 160 px tall, and the strokes through it were paired at random)."""
    parent = list(range(len(nodes)))
    members = {i: [i] for i in range(len(nodes))}

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    def span(group) -> bool:
        centres = np.array([nodes[i].centre for i in group])
        far = np.linalg.norm(centres[:, None] - centres[None], axis=-1).max()
        return far <= SPAN * max(nodes[i].radius for i in group)

    def short(c) -> bool:
        a, b = c.ends
        return a >= 0 and b >= 0 and _length(c.pts) < ZONE * (nodes[a].radius + nodes[b].radius)

    for c in sorted((c for c in chains if short(c)), key=lambda c: _length(c.pts)):
        ra, rb = root(c.ends[0]), root(c.ends[1])
        if ra != rb and span(members[ra] + members[rb]):
            parent[rb] = ra
            members[ra] += members.pop(rb)
    group = [root(i) for i in range(len(nodes))]
    parent = list(range(len(nodes)))  # again in the chains' order: which chains the merges drop
    keep = []
    for c in chains:
        if short(c) and group[c.ends[0]] == group[c.ends[1]]:
            ra, rb = root(c.ends[0]), root(c.ends[1])
            if ra != rb:
                parent[rb] = ra
                continue
        keep.append(c)
    groups: dict = {}
    for i in range(len(nodes)):
        groups.setdefault(root(i), []).append(i)
    new_id, merged = {}, []
    for members in groups.values():
        for i in members:
            new_id[i] = len(merged)
        centre = np.mean([nodes[i].centre for i in members], axis=0)
        merged.append(Node(centre, max(nodes[i].radius for i in members)))
    for c in keep:
        c.ends = [new_id[e] if e >= 0 else -1 for e in c.ends]
    _link(keep, merged)
    return keep, merged


def _prune_spurs(chains: list, nodes: list, mask, dist) -> tuple[list, set, dict]:
    """Short chains from a free end into a junction of three or more: the bumps a brush's
    entry or turn leaves, not strokes. Where that leaves a junction with one chain, its
    farthest-reaching spur comes back when it reaches HOOK_SPUR of the junction's half-width
    and clearly farther than the others: the tip of a hook (宀's 横钩, whose shoulder is the
    other spur), which the stroke turns into; and a spur that runs straight on from one of
    the junction's chains comes back as that stroke's overhang (``_overhangs``). A dot that
    touches a stroke is kept (``_dot``). Returns the
    chains, the junctions whose
    spur came back (the stroke runs on through them) and the spurs still pruned, by junction
    (``_tips``)."""
    pruned: dict = {}
    for _ in range(3):
        drop = set()
        for ci, c in enumerate(chains):
            if (c.ends[0] < 0) == (c.ends[1] < 0):
                continue
            node = nodes[max(c.ends)]
            short = _length(c.pts) < SPUR * node.radius + 3
            if len(node.chains) >= 3 and short and not _dot(chains, c, node, mask, dist):
                drop.add(ci)
                pruned.setdefault(max(c.ends), []).append(c)
        if not drop:
            break
        chains = [c for ci, c in enumerate(chains) if ci not in drop]
        _link(chains, nodes)
    hooked, loose = set(), {}
    for ni, spurs in pruned.items():
        if not nodes[ni].chains:  # every chain of a piece of ink was a spur: a dot's blob
            back = _blob_stroke(spurs)
            chains += back
            _link(chains, nodes)
            if len(back) == 2:  # the stroke runs on through the junction
                hooked.add(ni)
            continue
        if len(nodes[ni].chains) != 1:
            back = _overhangs(chains, nodes[ni], spurs)
            for c in back:
                chains.append(c)
                _link(chains, nodes)
            loose[ni] = [c for c in spurs if not any(c is b for b in back)]
            continue
        reach = sorted((_length(c.pts), k) for k, c in enumerate(spurs))
        far, k = reach[-1]
        second = reach[-2][0] if len(reach) > 1 else 0.0
        foot = _heel_foot(chains, nodes[ni], spurs, spurs[k])
        if foot is not None:
            chains.append(foot)
            hooked.add(ni)
        elif far >= HOOK_SPUR * nodes[ni].radius and far >= HOOK_CLEAR * second:
            chains.append(spurs[k])
            hooked.add(ni)
    _link(chains, nodes)
    return chains, hooked, loose


def _heel_foot(chains: list, node: Node, spurs: list, far: Chain) -> Chain | None:
    """A standing stroke's foot, when its farthest spur runs sideways (within HEEL_FLAT of
    level) and another runs straight on (CONTINUE_COS): the sideways bump is the heel a pressed
    foot (顿) leaves, not a hook, whose tip rises (竖钩) or falls from a horizontal (横钩). The
    stroke runs on through the junction to the foot (東's vertical at a copybook's scale lost
    the 1/16 of its height past the heel, and box-normalised IoU fell to 0.50). Beyond the paper:
    its strokes come from stroke data, not from a picture."""
    ci, e = node.chains[0]
    up = _exit(chains[ci], e, node)[1]
    side = _exit(far, 0 if far.ends[0] >= 0 else 1, node)[1]
    if up[1] > -STAND_RISE or abs(float(side[1])) > HEEL_FLAT:
        return None
    for spur in spurs:
        way = _exit(spur, 0 if spur.ends[0] >= 0 else 1, node)[1]
        if spur is not far and float(matmul(way, up)) < CONTINUE_COS:
            return spur
    return None


def _blob_stroke(spurs: list) -> list:
    """The two of a junction's spurs whose free ends lie farthest apart, when pruning took every
    chain of a piece of ink: a heavy dot's skeleton is a small star of spurs round one junction,
    each shorter than SPUR times its half-width, and the piece must still be written (光's and
    并's dots in a scan of heavy kaishu were left out whole). The stroke runs from one free end
    through the junction to the other (``find_strokes`` pairs them there)."""
    if len(spurs) < 2:
        return list(spurs)
    free = [c.pts[0] if c.ends[0] < 0 else c.pts[-1] for c in spurs]
    _, a, b = max(
        (float(np.hypot(*(free[i] - free[j]))), i, j)
        for i in range(len(spurs))
        for j in range(i + 1, len(spurs))
    )
    return [spurs[a], spurs[b]]


def _dot(chains: list, c: Chain, node: Node, mask: np.ndarray, dist: np.ndarray) -> bool:
    """Whether a short chain from a free end into a junction is a dot touching the stroke
    there (宀's or 亠's dot sitting on its horizontal in a scan), not a bump: its ink stands
    out DOT[0] of the crossing stroke's half-width or more past the junction's edge (the chain,
    and the ink on along its way past the skeleton's end), and it is DOT[1] of that thick or
    more (a stroke's pointed tip reaching past a corner is thin), where a stroke runs on
    through the junction (two of its other chains leave it nearly opposite ways: at a corner
    where strokes start or end, a spur is a stroke's tip, ``_tips``). Beyond the paper, which
    reads no pictures: the scale is the crossing stroke's own half-width (``_crossing_radius``)
    where it is thinner than the junction - a heavy stroke's head pressed onto a thin one (丰's
    vertical in a heavy 害) makes the junction as wide as the head, and measured by it the head
    read as a bump and its stroke was left unwritten."""
    ways = [(i, e, _exit(chains[i], e, node)[1]) for i, e in node.chains if chains[i] is not c]
    through = [
        (a[:2], b[:2])
        for k, a in enumerate(ways)
        for b in ways[k + 1 :]
        if float(matmul(a[2], b[2])) < CONTINUE_COS
    ]
    if not through:
        return False
    r = min(node.radius, min(_crossing_radius(chains, node, pair, dist) for pair in through))
    end = 0 if c.ends[0] >= 0 else 1
    pts = _outward(c, end)
    run = len(_extend(pts, mask, node.radius, 0.0)[0])
    iy, ix = np.round(pts[len(pts) // 2 :, ::-1]).astype(int).T
    thick = float(dist[iy, ix].max())
    return _length(pts) + run - node.radius >= DOT[0] * r and thick >= DOT[1] * r


def _crossing_radius(chains: list, node: Node, pair: tuple, dist: np.ndarray) -> float:
    """The half-width of the stroke running on through a junction by the two chain ends
    ``pair``: the median of the ink's half-width along either chain just out of the junction's
    zone (as far again as the zone reaches); the junction's own where either chain ends inside
    the zone (a heavy dot's lobes, ``_blob_stroke``: no stroke runs through)."""
    rads = []
    for ci, e in pair:
        pts = _outward(chains[ci], e)
        if np.linalg.norm(pts[-1] - node.centre, axis=-1) <= ZONE * node.radius + 1.0:
            return node.radius
        k = _exit(chains[ci], e, node)[0]
        seg = pts[k : k + max(int(ZONE * node.radius), 3)]
        iy, ix = np.round(seg[:, ::-1]).astype(int).T
        rads.append(dist[iy, ix])
    return float(np.median(np.concatenate(rads)))


def _tips(chains: list, nodes: list, loose: dict, partner: dict, mask) -> None:
    """The pointed tips of strokes that start or end at a junction, in place: a spur pruned
    there (``_prune_spurs``) that runs on within TIP_TURN of the way a stroke comes into the
    junction, where that stroke ends (its chain end has no partner), is that stroke's tip - the
    point of a 露锋 entry reaching out past the corner of 口 where its vertical and its top
    start, or a foot reaching down past the corner where they end - and is joined to it, most
    nearly straight on first (a standing stroke before a lying one), one spur to a stroke's
    end. Without it the stroke starts at the
    corner's centre and the brush never reaches the tip, which is often the character's
    outermost ink. (A spur where a stroke runs through - the knob of a 折's shoulder, a bump
    at a crossing such as 木's, where its 撇 and 捺 start - is left off.)"""
    for ni, spurs in loose.items():
        node = nodes[ni]
        if any(ce in partner for ce in node.chains):  # a stroke runs through: a crossing's bump
            continue
        free = [ce for ce in node.chains if ce not in partner]
        cand = []
        for spur in spurs:
            end = 0 if spur.ends[0] == ni else 1
            tip = _outward(spur, end)[-1] - node.centre
            if np.linalg.norm(tip, axis=-1) < TIP_MIN[0] * node.radius:
                continue
            way = tip / float(np.linalg.norm(tip, axis=-1))
            run = len(_extend(np.array([node.centre, node.centre + tip]), mask, node.radius, 0)[0])
            entry = (
                way[1] < -TIP_UP and np.linalg.norm(tip, axis=-1) + run >= TIP_MIN[2] * node.radius
            )
            if np.linalg.norm(tip, axis=-1) < TIP_MIN[1] * node.radius and not entry:
                continue
            for ce in free:
                out = _exit(chains[ce[0]], ce[1], node)[1]
                cos = float(matmul(out, way))
                if cos < -exact.cos(TIP_TURN):  # a standing stroke first (口's vertical)
                    cand.append(
                        (cos - TIP_STANDING * (abs(out[1]) > abs(out[0])), id(spur), ce, spur, end)
                    )
        taken = set()
        for _, sid, ce, spur, end in sorted(cand, key=lambda c: c[0]):
            if sid in taken or ce in partner:
                continue
            taken.add(sid)
            chains.append(spur)
            partner[ce], partner[(len(chains) - 1, end)] = (len(chains) - 1, end), ce
    _link(chains, nodes)


def _overhangs(chains: list, node: Node, spurs: list) -> list:
    """The spurs pruned at a junction that run straight on from one of its chains beyond the
    ink of the others (OVERHANG_REACH of its half-width from its centre or more): the end of a
    stroke reaching past the stroke it meets, as 口's left side past its foot and its top, which
    the brush must reach."""
    out = []
    for spur in spurs:
        end = 0 if spur.ends[0] >= 0 else 1
        if _length(spur.pts) < OVERHANG_REACH * node.radius:
            continue
        way = _exit(spur, end, node)[1]
        for ci, e in node.chains:
            if float(matmul(_exit(chains[ci], e, node)[1], way)) < CONTINUE_COS:
                out.append(spur)
                break
    return out


def _exit(c: Chain, end: int, node: Node) -> tuple[int, np.ndarray]:
    """Where the chain leaves the node's zone (index along ``_outward``) and its way out."""
    pts = _outward(c, end)
    zone = ZONE * node.radius + 1.0
    far = np.flatnonzero(np.linalg.norm(pts - node.centre, axis=1) > zone)
    k = int(far[0]) if far.size else len(pts) - 1
    j = min(k + max(int(2 * node.radius), 6), len(pts) - 1)
    d = pts[j] - pts[k] if j > k else pts[k] - node.centre
    return k, d / max(float(np.linalg.norm(d, axis=-1)), 1e-9)


def _pairs(chains: list, nodes: list) -> dict:
    """At every junction, the chain ends that continue each other: the most nearly opposite
    ways out first; and a horizontal that turns down at its end (a 横折) at a corner of two."""
    partner = {}
    for node in nodes:
        ways = {ce: _exit(chains[ce[0]], ce[1], node)[1] for ce in node.chains}
        cand = sorted(
            (float(matmul(ways[a], ways[b])), a, b)
            for i, a in enumerate(node.chains)
            for b in node.chains[i + 1 :]
            if a[0] != b[0]
        )
        for cos, a, b in cand:
            if a in partner or b in partner:
                continue
            corner = len(node.chains) == 2 and (
                _is_corner(ways[a], ways[b]) or _is_open_l(chains, a, b, ways)
            )
            if cos < CONTINUE_COS or corner:
                partner[a], partner[b] = b, a
        for cos, a, b in cand:  # a stroke's overhang at a corner of three continues it
            if a in partner or b in partner or cos >= LOOSE_COS or len(node.chains) < 3:
                continue
            if min(_length(chains[a[0]].pts), _length(chains[b[0]].pts)) < 3 * node.radius:
                partner[a], partner[b] = b, a
    return partner


def _is_corner(u: np.ndarray, v: np.ndarray) -> bool:
    """Two ways out of a corner that one stroke makes: a horizontal turning down (one way goes
    left, the other down: 横折, 横撇) or a hook (both go up, close together: the stroke came
    down and flicks back up at its foot, 竖钩, 斜钩)."""
    left, down = np.array([-1.0, 0.0]), np.array([0.0, 1.0])
    turn_down = (matmul(u, left) > 0.8 and matmul(v, down) > 0.6) or (
        matmul(v, left) > 0.8 and matmul(u, down) > 0.6
    )
    hook = u[1] < -0.3 and v[1] < -0.3 and float(matmul(u, v)) > HOOK_COS
    return bool(turn_down or hook)


def _is_open_l(chains: list, a, b, ways: dict) -> bool:
    """A vertical turning right at its foot into a horizontal, not closing a box: one stroke,
    竖折 (the ㄴ of 亡 or 区, whose horizontal ends free; 山's and 出's 凵, whose horizontal
    runs on into the strokes standing on it). Where the corner closes a box (the foot of 口,
    日, 田: the vertical's top and the horizontal's end are joined by other strokes) the two
    are separate strokes."""
    up, right = np.array([0.0, -1.0]), np.array([1.0, 0.0])
    for v, h in ((a, b), (b, a)):
        if matmul(ways[v], up) > 0.8 and matmul(ways[h], right) > 0.8:
            far_v, far_h = chains[v[0]].ends[1 - v[1]], chains[h[0]].ends[1 - h[1]]
            corner = chains[v[0]].ends[v[1]]
            return far_h < 0 or not _joined(chains, far_v, far_h, {v[0], h[0]}, corner)
    return False


def _joined(chains: list, start: int, goal: int, without: set, avoid: int) -> bool:
    """Whether junctions ``start`` and ``goal`` are joined by chains other than ``without``,
    not through junction ``avoid`` (a free end, -1, is joined to nothing)."""
    if start < 0 or goal < 0:
        return False
    seen, todo = {start, avoid}, [start]
    while todo:
        node = todo.pop()
        if node == goal:
            return True
        for ci, c in enumerate(chains):
            if ci in without or node not in c.ends:
                continue
            for other in c.ends:
                if other >= 0 and other not in seen:
                    seen.add(other)
                    todo.append(other)
    return False


def _line(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    n = max(int(np.ceil(np.linalg.norm(b - a, axis=-1))), 1)
    t = np.linspace(0.0, 1.0, n + 1)[1:-1, None]
    return a + t * (b - a)


class _Trace:
    """Points of a stroke being traced, each with a known half-width or NaN (across a
    junction: read from either side later)."""

    def __init__(self):
        self.pts, self.rad = [], []
        self.through, self.touches = set(), set()
        self.free = [False, False]

    def add(self, pts, known: bool, dist) -> None:
        pts = np.asarray(pts, dtype=np.float64).reshape(-1, 2)
        if not len(pts):
            return
        self.pts.append(pts)
        if known:
            iy = np.clip(np.round(pts[:, 1]).astype(int), 0, dist.shape[0] - 1)
            ix = np.clip(np.round(pts[:, 0]).astype(int), 0, dist.shape[1] - 1)
            self.rad.append(dist[iy, ix])
        else:
            self.rad.append(np.full(len(pts), np.nan))


def _cut(c: Chain, end: int, nodes: list) -> np.ndarray:
    """The chain's points from ``end`` on, without those inside the zones of its nodes."""
    pts = _outward(c, end)
    a = _exit(c, end, nodes[c.ends[end]])[0] if c.ends[end] >= 0 else 0
    b = len(pts) - (_exit(c, 1 - end, nodes[c.ends[1 - end]])[0] if c.ends[1 - end] >= 0 else 0)
    if a >= b:
        mid = (a + b) // 2
        return pts[min(mid, len(pts) - 1) : min(mid, len(pts) - 1) + 1]
    return pts[a:b]


def _trace(ci: int, end: int, chains, nodes, partner, used, dist) -> _Trace:
    t = _Trace()
    n0 = chains[ci].ends[end]
    seg = _cut(chains[ci], end, nodes)
    if n0 < 0:
        t.free[0] = True
    elif (ci, end) not in partner:
        t.touches.add(n0)
        c0 = nodes[n0].centre
        t.add(np.vstack([c0, _line(c0, seg[0])]), False, dist)
    while True:
        used.add(ci)
        t.add(seg, True, dist)
        oe = 1 - end
        node = chains[ci].ends[oe]
        if node < 0:
            t.free[1] = True
            return t
        nxt = partner.get((ci, oe))
        if nxt is None or nxt[0] in used:
            t.touches.add(node)
            c1 = nodes[node].centre
            if nxt is None:
                t.add(np.vstack([_line(seg[-1], c1), c1]), False, dist)
            return t
        t.through.add(node)
        ci, end = nxt
        nseg = _cut(chains[ci], end, nodes)
        t.add(_line(seg[-1], nseg[0]), False, dist)
        seg = nseg


def _extend(pts: np.ndarray, mask: np.ndarray, r_end: float, short: float) -> tuple:
    """Points on from a free end (the last point) along its way until ``short`` px before the
    ink ends (the end's half-width ``r_end`` bounds the search): the skeleton stops short of a
    stroke's tip; and how far the end must come back instead when the skeleton already runs
    nearer the tip than ``short`` (into a 撇's point)."""
    if len(pts) < 2:
        return np.zeros((0, 2)), 0.0
    d = pts[-1] - pts[max(len(pts) - 10, 0)]
    d /= max(float(np.linalg.norm(d, axis=-1)), 1e-9)
    h, w = mask.shape
    last = 0
    for s in range(1, int(3 * r_end) + 6):
        x, y = np.round(pts[-1] + s * d).astype(int)
        if not (0 <= x < w and 0 <= y < h and mask[y, x]):
            break
        last = s
    reach = last - short
    if reach < 1:
        return np.zeros((0, 2)), max(-reach, 0.0)
    return pts[-1] + np.arange(1, int(reach) + 1)[:, None] * d, 0.0


def _cut_back(pts: np.ndarray, rad: np.ndarray, cut: float) -> tuple:
    """The line without its last ``cut`` px of arc (never below half its length)."""
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    t = max(s[-1] - cut, 0.5 * s[-1])
    k = int(np.searchsorted(s, t, side="right"))
    if cut <= 0 or k >= len(pts) or k < 1:
        return pts, rad
    end = np.array([np.interp(t, s, pts[:, 0]), np.interp(t, s, pts[:, 1])])
    return np.vstack([pts[:k], end]), np.concatenate([rad[:k], [np.interp(t, s, rad)]])


def _smooth_line(p: np.ndarray, k: int) -> np.ndarray:
    if len(p) < 3 or k <= 1:
        return p
    w = np.ones(k) / k
    pad = np.pad(p, ((k // 2, k - 1 - k // 2), (0, 0)), mode="edge")
    return np.stack([np.convolve(pad[:, i], w, mode="valid") for i in (0, 1)], axis=1)


def _finish(t: _Trace, mask, dist) -> Stroke:
    """The traced points as a stroke: free ends run on to the tips, junction half-widths read
    from either side, the line smoothed and resampled every 2 px."""
    pts, rad = np.concatenate(t.pts), np.concatenate(t.rad)
    known = np.isfinite(rad)
    if not known.any():
        iy, ix = np.clip(np.round(pts[:, ::-1]).astype(int), 0, mask.shape[0] - 1).T
        rad, known = dist[iy, ix], np.ones(len(pts), bool)
    idx = np.arange(len(pts))
    rad = np.interp(idx, idx[known], rad[known])
    short = TIP * float(np.median(rad))
    if t.free[1]:
        ext, cut = _extend(pts, mask, float(rad[-1]), short)
        pts, rad = np.vstack([pts, ext]), np.concatenate([rad, _radii(ext, dist, rad[-1])])
        pts, rad = _cut_back(pts, rad, cut)
    if t.free[0]:
        ext, cut = _extend(pts[::-1], mask, float(rad[0]), short)
        pts = np.vstack([ext[::-1], pts])
        rad = np.concatenate([_radii(ext[::-1], dist, rad[0]), rad])
        back, brad = _cut_back(pts[::-1], rad[::-1], cut)
        pts, rad = back[::-1], brad[::-1]
    pts = _smooth_line(pts, 5)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    n = max(int(s[-1] / 2.0), 1) + 1
    si = np.linspace(0.0, s[-1], n)
    out = np.stack([np.interp(si, s, pts[:, 0]), np.interp(si, s, pts[:, 1])], axis=1)
    return Stroke(out, np.interp(si, s, rad), t.through, t.touches)


def _radii(pts, dist, r_end: float) -> np.ndarray:
    if not len(pts):
        return np.zeros(0)
    iy = np.clip(np.round(pts[:, 1]).astype(int), 0, dist.shape[0] - 1)
    ix = np.clip(np.round(pts[:, 0]).astype(int), 0, dist.shape[1] - 1)
    return np.minimum(dist[iy, ix], r_end)


def find_strokes(mask: np.ndarray, dist: np.ndarray | None = None) -> list[Stroke]:
    """The strokes of an ink mask (top row first), unordered."""
    dist = M.edt(mask) if dist is None else dist
    chains, nodes = skeleton_graph(mask, dist)
    chains, nodes = _merge_close_nodes(chains, nodes)
    chains, hooked, loose = _prune_spurs(chains, nodes, mask, dist)
    partner = _pairs(chains, nodes)
    _tips(chains, nodes, loose, partner, mask)
    for ni in hooked:  # the stroke turns into its hook's tip
        a, b = nodes[ni].chains
        if a not in partner and b not in partner:
            partner[a], partner[b] = b, a
    used, out = set(), []
    starts = [(ci, e) for ci in range(len(chains)) for e in (0, 1) if (ci, e) not in partner]
    for ci, e in starts + [(ci, 0) for ci in range(len(chains))]:
        if ci not in used:
            s = _finish(_trace(ci, e, chains, nodes, partner, used, dist), mask, dist)
            s.joints = {i: nodes[i].centre for i in s.through | s.touches}
            out.append(s)
    return out
