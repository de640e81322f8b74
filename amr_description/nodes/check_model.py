# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""``check_model``: check a URDF beyond ``check_urdf`` and print the findings."""

import argparse
import sys

from amr_description.core.description.urdf_model import parse_urdf_file
from amr_description.core.description.urdf_model import URDFError
from amr_description.core.model_check import check_model
from amr_description.core.model_check.controllers_yaml import load_controllers
from amr_description.core.model_check.findings import ERROR
from amr_description.core.model_check.findings import Finding
from amr_description.core.model_check.findings import INFO
from amr_description.core.model_check.findings import WARNING
from amr_description.core.model_check.installed import compare_installed
from amr_description.core.model_check.installed import installed_counterpart
from amr_description.core.model_check.meshes import check_meshes


def _controllers_of(root):
    """
    Return ``(controllers dict, last path)`` of the YAML files a description names, or Nones.

    Several gz_ros2_control ``<parameters>`` files are merged per node section, a later file
    overriding an earlier one (rcl's ``--params-file`` rule).

    :param root: the parsed ``<robot>`` element (``RobotModel.element``).
    :raises ValueError: one line naming a file that cannot be read.
    """
    from amr_description.core.description.files import resolve_uri
    from amr_description.core.description.mujoco_block import parse_mujoco_block
    from amr_description.core.gazebo.tags import parse_control_plugin
    try:  # the same choice as RobotDescription.parameters_files; the checks report errors
        block, plugin = parse_mujoco_block(root), parse_control_plugin(root)
    except ValueError:
        return None, None
    uris = [block.parameters] if block.parameters else (plugin.parameters if plugin else [])
    paths = [resolve_uri(p) for p in uris]
    merged = None
    for path in paths:
        data = load_controllers(path)
        merged = merged or {}
        for section, values in data.items():
            target = merged.setdefault(section, {})
            for key, value in (values or {}).items():
                if isinstance(value, dict) and isinstance(target.get(key), dict):
                    target[key] = {**target[key], **value}
                else:
                    target[key] = value
    return merged, (paths[-1] if paths else None)


def main(argv=None):
    """
    Check a URDF (and optionally its controllers.yaml); print findings.

    ``ros2 run amr_description check_model [--controllers YAML] [--quiet] URDF``

    :param argv: arguments without the program name (default: ``sys.argv[1:]``).
    :returns: 0 when no errors, 1 when a check failed (including a rule of the URDF loader,
        reported as an error naming the element), 2 when a file cannot be read or is not a
        URDF document at all (malformed XML, no ``<robot>``).
    """
    parser = argparse.ArgumentParser(
        prog='check_model', description='Check a URDF beyond check_urdf: inertia, wheels, '
        'ros2_control block and controllers.yaml.')
    parser.add_argument('urdf', help='URDF file')
    parser.add_argument('--controllers', metavar='YAML',
                        help='controllers.yaml (ros2_control format) to check against the URDF '
                        '(default: the file the description names, <mujoco><ros2_control '
                        'parameters> or the <parameters> of gz_ros2_control)')
    parser.add_argument('-q', '--quiet', action='store_true', help='print errors and warnings '
                        'only')
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    model = None
    try:
        try:
            urdf_xml, model = parse_urdf_file(args.urdf)
        except URDFError as exc:
            if not exc.element:
                raise
            findings = [Finding(ERROR, exc.element, exc.problem)]
        controllers = load_controllers(args.controllers) if args.controllers else None
        if controllers is None and model is not None:
            controllers, args.controllers = _controllers_of(model.element)
    except ValueError as exc:
        print(f'check_model: {exc}', file=sys.stderr)
        return 2
    if model is not None:
        findings = check_model(model, urdf_xml, controllers) + check_meshes(model)
    for path in (args.urdf, args.controllers):
        installed = installed_counterpart(path) if path else None
        if installed is not None:
            findings.append(compare_installed(path, installed))
    for finding in findings:
        if not (args.quiet and finding.severity == INFO):
            print(finding)
    errors = sum(f.severity == ERROR for f in findings)
    warnings = sum(f.severity == WARNING for f in findings)
    if model is None:
        print(f'{args.urdf}: refused by the URDF loader: {errors} error(s), '
              f'{warnings} warning(s)')
    else:
        print(f'{args.urdf}: robot {model.name!r}, {len(model.links)} links, '
              f'{len(model.joints)} joints: {errors} error(s), {warnings} warning(s)')
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main())
