# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""mrepair.html_report(): the self-contained HTML report, the same page as
`mrepair repair IN OUT --html report.html` writes."""

import json
import os

import numpy as np

from . import _mrepair
from ._studio_assets import (DEFAULT_FACE_BUDGET, PLACEHOLDER, TEMPLATE, find_studio_assets, json_default,
                             overlay_json, payload_mesh, triangles)


def report_payload(V_before, F_before, V_after, F_after, report, settings=None, *, title="mesh",
                   face_budget=DEFAULT_FACE_BUDGET, max_elements=100000, **inspect_options):
    """the payload dict of the report page (doc/studio.md), JSON-ready."""
    def side(V, F):
        V = np.asarray(V, dtype=np.float64)
        overlay = _mrepair.defect_overlay(V, triangles(F), max_elements=max_elements, **inspect_options)
        return payload_mesh(V, F, face_budget), overlay_json(overlay)

    mb, db = side(V_before, F_before)
    ma, da = side(V_after, F_after)
    return {"version": 1, "title": str(title), "meshes": {"before": mb, "after": ma},
            "defects": {"before": db, "after": da}, "report": report or {}, "settings": settings or {}}


def html_report(path, V_before, F_before, V_after, F_after, report, settings=None, *, title=None,
                face_budget=DEFAULT_FACE_BUDGET, max_elements=100000, **inspect_options):
    """writes one self-contained HTML file (no network needed to open it) with the before
    and after meshes, their defects drawn in colour with their counts, the report tables and
    the settings: the page of `mrepair repair IN OUT --html path`.

    report: the report dict of the job (e.g. the third value of mrepair.repair); settings: a
    dict of the options used (shown as they are). Meshes above `face_budget` faces are shown as
    a decimated preview (said on the page); at most `max_elements` elements per defect kind are
    drawn (the counts are always the full ones). inspect_options (spike_angle, small_hole,
    small_component, t_junction_tolerance, self_intersections) are those of mrepair.inspect.

    The template comes from the studio's built assets (MREPAIR_STUDIO_ASSETS, the build
    folder, the install folder); FileNotFoundError says how to build it when it is missing."""
    folder = find_studio_assets(TEMPLATE)
    with open(os.path.join(folder, TEMPLATE), encoding="utf-8") as f:
        template = f.read()
    if template.count(PLACEHOLDER) != 1:
        raise ValueError("%s: not a report template (expected one %s)" % (folder, PLACEHOLDER))
    if title is None:
        title = os.path.basename(os.fspath(path))
    payload = report_payload(V_before, F_before, V_after, F_after, report, settings, title=title,
                             face_budget=face_budget, max_elements=max_elements, **inspect_options)
    # every "<" as \u003c (as the CLI writes it): no string can end the <script> element early
    text = json.dumps(payload, default=json_default, separators=(",", ":")).replace("<", "\\u003c")
    html = template.replace(PLACEHOLDER, text, 1)
    with open(path, "w", encoding="utf-8") as f:
        f.write(html)
