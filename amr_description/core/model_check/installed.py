# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""The installed copy of a source file (the stale-install lesson)."""

import filecmp
import os

from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import INFO
from amr_description.core.model_check.findings import WARNING


def compare_installed(source_path, installed_path):
    """
    Compare a source file with its installed copy (the stale-install lesson).

    :param source_path: the file in the source tree.
    :param installed_path: the file under ``share/<pkg>/...``, or None when not installed.
    :returns: a :class:`Finding`: ok when it is the same file (symlink install) or has the
        same bytes, warning when not installed, error when the contents differ.
    """
    element = f'installed {os.path.basename(source_path)}'
    if installed_path is None or not os.path.exists(installed_path):
        return Finding(WARNING, element, 'not installed; run colcon build', installed_path or
                       'share/amr_description/...', 'nothing')
    if os.path.samefile(source_path, installed_path):
        return Finding(INFO, element, f'{installed_path} is the source file (symlink install)')
    if filecmp.cmp(source_path, installed_path, shallow=False):
        return Finding(INFO, element, f'{installed_path} equals the source file')
    return Finding(ERROR, element,
                   'installed copy differs from the source: rebuild (colcon build) or nodes '
                   'load a stale model', source_path, installed_path)


def installed_counterpart(source_path, package='amr_description'):
    """
    Return the installed path of a source-tree file of ``package``, or None.

    Only files of the package's own source tree (``<src>/package.xml`` names ``package`` and
    the file is under ``<src>/urdf`` or ``<src>/config``) have a counterpart.

    :returns: ``<share>/<package>/<folder>/<name>`` through the ament index, or None.
    """
    folder_path = os.path.dirname(os.path.abspath(source_path))
    folder = os.path.basename(folder_path)
    package_xml = os.path.join(os.path.dirname(folder_path), 'package.xml')
    if folder not in ('urdf', 'config') or not os.path.isfile(package_xml):
        return None
    try:
        with open(package_xml) as f:
            if f'<name>{package}</name>' not in f.read():
                return None
        from ament_index_python.packages import get_package_share_directory
        share = get_package_share_directory(package)
    except Exception:  # not installed, or ament_index unavailable
        return os.path.join('share', package, folder, os.path.basename(source_path))
    return os.path.join(share, folder, os.path.basename(source_path))
