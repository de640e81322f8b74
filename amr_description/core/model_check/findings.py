# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""A finding of a model check, its severities, and the tolerances of the checks."""

from dataclasses import dataclass

import numpy as np


ERROR = 'error'
WARNING = 'warning'
INFO = 'ok'
DIFF_DRIVE_TYPE = 'diff_drive_controller/DiffDriveController'
HARDWARE_GROUP = 'amr_description.hardware'
GEOMETRY_TOLERANCE = 1e-3  # m, wheel_separation and wheel_radius against the URDF
INERTIA_TOLERANCE = 0.1  # relative Frobenius distance tolerated from the geometric inertia


@dataclass
class Finding:
    """
    One result of a check.

    :param severity: ``'error'``, ``'warning'`` or ``'ok'`` (a passed check worth reporting).
    :param element: what it is about, e.g. ``"link 'base_link'"`` or ``"joint 'j'"``.
    :param message: what is wrong (or right), one line.
    :param expected: the expected value, as text ('' when not applicable).
    :param found: the value found, as text ('' when not applicable).
    """

    severity: str
    element: str
    message: str
    expected: str = ''
    found: str = ''

    def __str__(self):
        """Return the one-line report form of the finding."""
        text = f'{self.severity.upper():7} {self.element}: {self.message}'
        if self.expected or self.found:
            text += f' (expected {self.expected}, found {self.found})'
        return text


def vec(v, digits=4):
    """Format a vector compactly, e.g. ``(0, 1, 0)``."""
    return '(' + ', '.join(f'{round(float(x), digits) + 0.0:g}' for x in v) + ')'


def origin_matrix(origin):
    """Return a 4x4 matrix for a yourdfpy origin (None = identity)."""
    return np.eye(4) if origin is None else np.asarray(origin, dtype=float)
