# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""The mrepair studio: ``python3 -m mrepair.studio MESH [--port N] [--no-browser]``.

A local web page (served on 127.0.0.1 by the standard library's http.server)
that shows the mesh and its defects in WebGL, runs the repair or the cleaning
steps one by one, scrubs the progressive gap closing, remeshes, and exports
the mesh, a PNG of the view and the settings. The library does the work; the
page only shows and asks. See doc/studio.md."""

from .server import Session, make_server, main  # noqa: F401

__all__ = ["Session", "make_server", "main"]
