# SPDX-License-Identifier: GPL-3.0-or-later
"""What the exports of issue 29.4 read: the engine's paper as the paper image shows it (the
sample it shows, simulated to there when the playback is elsewhere), and their poll."""

from __future__ import annotations

from ..blender import checks, images, playback


def can_export(cls, context) -> bool:
    st = checks.settings(context.scene)
    if st.recording is None or st.paper_image is None:
        cls.poll_message_set("Nothing written yet: write, paint or import a recording first")
        return False
    return True


def shown_paper(scene):
    """The sim.paper.Paper the paper image shows (UserError when there is none)."""
    st = checks.settings(scene)
    img = st.paper_image
    if st.recording is None or img is None:
        raise checks.UserError("Nothing written yet: write, paint or import a recording first")
    return playback.show(scene, int(img.get(images.SHOWN_TAG, 0))).paper
