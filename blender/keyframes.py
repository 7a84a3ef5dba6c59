# SPDX-License-Identifier: GPL-3.0-or-later
"""The brush empty keyframed along 6-DOF samples or world matrices, and its F-curves (legacy
and slotted actions)."""

from __future__ import annotations

import numpy as np

from . import transforms


def keyframe_samples(scene, st, samples, rate_hz: float, frame_start: float):
    """Keyframe the brush empty along 6-DOF samples (one key per sample, linear), so the
    writing plays, can be edited, and bakes back into the same samples."""
    paper_mw = st.paper_object.matrix_world
    mats = [transforms.matrix_from_sample(st, paper_mw, s) for s in samples]
    return keyframe_matrices(scene, st, mats, rate_hz, frame_start)


def keyframe_matrices(scene, st, mats, rate_hz: float, frame_start: float):
    """Keyframe the brush empty through world matrices, one a sample (linear); returns the
    last key's frame."""
    obj = st.brush_object
    obj.rotation_mode = "ZYX"
    frames = key_frames(scene, rate_hz, frame_start, np.arange(len(mats)))
    loc, rot = euler_channels(obj, mats)
    set_channels(obj, {path: (frames, values) for path, values in _paths(loc, rot)})
    return float(frames[-1])


CHANNELS = ("location", "rotation_euler")  # the brush empty's keyed paths, 3 indices each


def key_frames(scene, rate_hz: float, frame_start: float, index) -> np.ndarray:
    """The frames of the keys of samples ``index`` (one key a sample from ``frame_start``)."""
    fps = scene.render.fps / scene.render.fps_base
    return frame_start + np.asarray(index, dtype=float) * fps / rate_hz


def euler_channels(obj, mats, prev=None) -> tuple[np.ndarray, np.ndarray]:
    """(N, 3) locations and (N, 3) Euler ZYX rotations of the object's own basis (its parent
    taken out) for N world matrices, each rotation the one nearest the one before it (``prev``:
    the Euler before the first, e.g. the key before them)."""
    from mathutils import Euler, Matrix

    if obj.parent is not None:
        parent = np.array(obj.parent.matrix_world) @ np.array(obj.matrix_parent_inverse)
    else:
        parent = np.eye(4)
    inv_parent = np.linalg.inv(parent)
    loc = np.empty((len(mats), 3))
    rot = np.empty((len(mats), 3))
    prev = None if prev is None else Euler(tuple(prev), "ZYX")
    for i, m in enumerate(mats):
        basis = Matrix((inv_parent @ np.asarray(m)).tolist())
        t, q, _scale = basis.decompose()
        e = q.to_euler("ZYX", prev) if prev is not None else q.to_euler("ZYX")
        loc[i], rot[i], prev = t[:], e[:], e
    return loc, rot


def _paths(loc, rot):
    """((path, index), values) of the six channels."""
    for path, values in (("location", loc), ("rotation_euler", rot)):
        for k in range(3):
            yield (path, k), values[:, k]


def set_channels(obj, channels: dict):
    """The object's location and rotation F-curves made anew with these keys (``channels``:
    (path, index) -> (frames, values)), linear; its other animation stays."""
    remove_fcurves(obj, CHANNELS)
    for path, k in channels:
        obj.keyframe_insert(path, index=k, frame=float(channels[(path, k)][0][0]))
    curves = {(fc.data_path, fc.array_index): fc for fc in fcurves(obj.animation_data)}
    for key, (frames, values) in channels.items():
        fc = curves[key]
        kp = fc.keyframe_points
        kp.add(len(frames) - len(kp))
        co = np.stack([frames, values], axis=1).astype(np.float32)
        kp.foreach_set("co", co.ravel())
        for p in kp:
            p.interpolation = "LINEAR"
        fc.update()


def read_channels(obj) -> dict:
    """(path, index) -> (frames, values) of the object's location and rotation keys (empty
    arrays for a channel without keys)."""
    out = {key: (np.zeros(0), np.zeros(0)) for key, _ in _paths(np.zeros((0, 3)), np.zeros((0, 3)))}
    if obj.animation_data is None or obj.animation_data.action is None:
        return out
    for fc in fcurves(obj.animation_data):
        key = (fc.data_path, fc.array_index)
        if key in out:
            co = np.empty(2 * len(fc.keyframe_points), np.float32)
            fc.keyframe_points.foreach_get("co", co)
            co = co.reshape(-1, 2)
            out[key] = (co[:, 0].astype(float), co[:, 1].astype(float))
    return out


def splice_keyframes(scene, st, mats, rate_hz, frame_start, first, end, shift=0) -> float:
    """The brush empty's keys of samples [first, end) replaced by keys through ``mats`` (one a
    sample from sample ``first``, timed as keyframe_matrices times them from ``frame_start``):
    the keys of earlier samples stay as they are, those of later ones move by ``shift``
    samples (a cell written again that takes longer), their values kept. Returns the frame of
    the last new key."""
    obj = st.brush_object
    obj.rotation_mode = "ZYX"
    new_frames = key_frames(scene, rate_hz, frame_start, first + np.arange(len(mats)))
    per = float(key_frames(scene, rate_hz, 0.0, 1))
    old = read_channels(obj)
    prev = None
    keep = {}
    for key, (frames, values) in old.items():
        index = np.rint((frames - frame_start) / per)
        before, after = index < first, index >= end
        keep[key] = (frames[before], values[before], frames[after] + shift * per, values[after])
        if key[0] == "rotation_euler" and before.any():
            prev = (prev or [0.0, 0.0, 0.0])[:]
            prev[key[1]] = float(values[before][-1])
    loc, rot = euler_channels(obj, mats, prev)
    channels = {}
    for key, values in _paths(loc, rot):
        fb, vb, fa, va = keep[key]
        channels[key] = (np.r_[fb, new_frames, fa], np.r_[vb, values, va])
    set_channels(obj, channels)
    return float(new_frames[-1])


def remove_fcurves(obj, paths):
    """Delete the object's F-curves of these data paths (every index), keeping the rest."""
    ad = obj.animation_data
    if ad is None or ad.action is None:
        return
    action = ad.action
    if hasattr(action, "fcurves"):  # Blender < 5 (legacy actions)
        owners = [action.fcurves]
    else:
        slot = getattr(ad, "action_slot", None)
        owners = [
            bag.fcurves
            for layer in action.layers
            for strip in layer.strips
            if slot is not None and (bag := strip.channelbag(slot)) is not None
        ]
    for fcurves in owners:
        for fc in [fc for fc in fcurves if fc.data_path in paths]:
            fcurves.remove(fc)


def fcurves(ad):
    """The F-curves of an object's animation (legacy or slotted actions)."""
    action = ad.action
    if hasattr(action, "fcurves"):  # Blender < 5 (legacy actions)
        return list(action.fcurves)
    out = []
    slot = getattr(ad, "action_slot", None)
    for layer in action.layers:  # slotted actions (Blender 4.4+)
        for strip in layer.strips:
            bag = strip.channelbag(slot) if slot is not None else None
            if bag is not None:
                out.extend(bag.fcurves)
    return out
