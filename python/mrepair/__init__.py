# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""mrepair: mesh repair and remeshing on CGAL, from NumPy arrays.

Every call takes vertices V (a float64 N x 3 array) and faces F (an integer
M x 3 array, or a list of index lists for polygons), copies them (the
caller's arrays are never changed) and returns new arrays and the report of
the matching ``mrepair`` command as a dict::

    import mrepair
    V, F = mrepair.read("part.stl")
    V, F, report = mrepair.repair(V, F)
    print(report["face_accounting"], report["after"]["defects"])

The computation runs without the GIL. ``progress`` takes a callable
``progress(phase, fraction)`` (see ``progress_bar`` for tqdm); returning
False cancels the call (``Cancelled``, a KeyboardInterrupt), and so does
Ctrl-C (KeyboardInterrupt). Bad input raises ValueError with the library's
reason.
"""

from ._mrepair import (  # noqa: F401
    Cancelled,
    GapClosingSequence,
    clean,
    close_gaps,
    compare_to_reference,
    defect_overlay,
    inspect,
    locate_defects,
    preview_mesh,
    read,
    remesh,
    repair,
    soup_to_manifold,
    write,
)
from ._html_report import html_report  # noqa: F401

#: the kinds of ``locate_defects`` / ``defect_overlay``, in drawing order, and
#: the key of the inspection report's ``defects`` section each one counts
#: (doc/studio.md)
DEFECT_REPORT_KEYS = {
    "boundary_loops": "boundary_loops",
    "small_holes": "small_holes",
    "non_manifold_edges": "non_manifold_edges",
    "non_manifold_vertices": "non_manifold_vertices",
    "spikes": "spiked_vertices",
    "near_degenerate_faces": "near_degenerate_faces",
    "small_components": "small_components",
    "crossing_pairs": "self_intersecting_pairs",
    "t_junctions": "t_junctions",
}

__all__ = [
    "Cancelled",
    "DEFECT_REPORT_KEYS",
    "GapClosingSequence",
    "clean",
    "close_gaps",
    "compare_to_reference",
    "defect_overlay",
    "html_report",
    "inspect",
    "locate_defects",
    "preview_mesh",
    "progress_bar",
    "read",
    "remesh",
    "repair",
    "soup_to_manifold",
    "write",
]
__version__ = "0.1.0"


def progress_bar(bar):
    """returns a ``progress`` callable that drives a tqdm bar (or anything with
    ``total``, ``n``, ``set_description`` and ``refresh``): the description is
    the running phase, the bar its fraction done::

        with tqdm(total=100) as bar:
            V, F, report = mrepair.repair(V, F, progress=mrepair.progress_bar(bar))
    """
    total = bar.total or 100

    def progress(phase, fraction):
        bar.set_description(phase, refresh=False)
        bar.n = round(max(0.0, min(1.0, fraction)) * total)
        bar.refresh()

    return progress
