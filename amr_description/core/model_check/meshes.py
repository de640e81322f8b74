# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Mesh files of a robot, read as the simulator reads them (reads the files)."""

import os

from amr_description.core.description.files import resolve_uri
from amr_description.core.description.meshes import usable_mesh
from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import WARNING


def check_meshes(model):
    """
    Check every ``<mesh>`` of every link's visuals and collisions.

    The file is resolved and prepared by
    :func:`amr_description.core.description.meshes.usable_mesh`, as the simulator does: what
    it cannot use is an error (the simulator leaves that shape out), what it changes
    (decimated, thickened, triangles left out) a warning.

    :param model: :class:`~amr_description.core.description.urdf_model.RobotModel`.
    :returns: list of :class:`~amr_description.core.model_check.findings.Finding`, one per
        problem, naming the link, the element and the file.
    """
    findings = []
    for name, link in model.links.items():
        for kind, elements in (('collision', link.collisions), ('visual', link.visuals)):
            for index, element in enumerate(elements):
                mesh = getattr(element.geometry, 'mesh', None)
                if mesh is None:
                    continue
                where = f"link '{name}' {kind} {index}"
                findings += _check_mesh(where, mesh.filename, mesh.scale)
    return findings


def _check_mesh(where, filename, scale):
    """Return the findings of one mesh."""
    try:
        path = resolve_uri(filename)
    except ValueError as exc:
        return [Finding(ERROR, where, f'{exc}: the simulator leaves this mesh out')]
    if not os.path.isfile(path):
        return [Finding(ERROR, where, f'mesh {filename!r}: no file {path!r}: the simulator '
                        'leaves it out')]
    try:
        prepared = usable_mesh(path, scale)
    except ValueError as exc:
        return [Finding(ERROR, where, f'{exc}: the simulator leaves this mesh out')]
    return [Finding(WARNING, where, note) for note in prepared.notes]
