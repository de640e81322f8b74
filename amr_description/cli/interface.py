# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
``ros2 interface show|list|packages|package`` (output of ros2interface, jazzy).

``show`` prints the ``.msg``/``.srv``/``.action`` file found under ``share/PKG/<kind>/`` of
the ament index. Every field of a non-primitive type is followed by that type's definition,
indented one tab deeper; nested definitions are shown without comments and blank lines
unless ``--all-comments``; ``--no-comments`` drops them at the top level too.
"""

import os

from amr_description.cli.common import fail
from amr_description.cli.extension import Command
from amr_description.cli.extension import Verb
from amr_description.core.message_yaml.utilities import INTERFACE_KINDS


def interface_path(identifier):
    """
    Return the definition file of ``pkg/kind/Type`` (or ``pkg/Type``, any kind).

    :param identifier: interface type name.
    :returns: path of the ``.msg``/``.srv``/``.action`` file.
    :raises ValueError: on a malformed name.
    :raises LookupError: when the package or the file does not exist.
    """
    from ament_index_python.packages import get_package_share_directory
    from ament_index_python.packages import PackageNotFoundError
    parts = identifier.split('/')
    if len(parts) not in (2, 3) or not all(parts) or (
            len(parts) == 3 and parts[1] not in INTERFACE_KINDS):
        raise ValueError(
            f"Invalid name '{identifier}'. Expected three parts separated by '/'")
    try:
        share = get_package_share_directory(parts[0])
    except PackageNotFoundError:
        raise LookupError(f"Unknown package '{parts[0]}'") from None
    kinds = [parts[1]] if len(parts) == 3 else list(INTERFACE_KINDS)
    for kind in kinds:
        path = os.path.join(share, kind, f'{parts[-1]}.{kind}')
        if os.path.isfile(path):
            return path
    raise LookupError(f"Could not find the interface '{identifier}'")


def _parse_line(package, line):
    """Return ``(is_comment_or_blank, nested_type, text_without_trailing_comment)``."""
    from rosidl_adapter.parser import parse_message_string
    stripped = line.strip()
    if not stripped or stripped.startswith('#'):
        return True, None, line
    if stripped in ('---',):
        return False, None, line
    try:
        spec = parse_message_string(package, 'Line', line)
    except Exception:  # not a field line: print it as is
        return False, None, line
    text = line.split('#', 1)[0].rstrip() if '#' in line else line
    if not spec.fields:
        return False, None, text
    field_type = spec.fields[0].type
    if field_type.is_primitive_type():
        return False, None, text
    return False, f'{field_type.pkg_name}/msg/{field_type.type}', text


def show_lines(identifier, comments=True, nested_comments=False, indent=0):
    """
    Return the lines ``ros2 interface show`` prints for ``identifier``.

    :param identifier: interface type name.
    :param comments: keep comments and blank lines at this level.
    :param nested_comments: keep them in nested definitions too.
    :param indent: tab depth of this level.
    :returns: list of str.
    :raises ValueError: on a malformed name.
    :raises LookupError: on an unknown interface.
    """
    package = identifier.split('/')[0]
    with open(interface_path(identifier)) as f:
        raw = f.read().splitlines()
    lines = []
    for line in raw:
        line = line.rstrip()
        skip, nested, text = _parse_line(package, line)
        if skip and not comments:
            continue
        shown = line if comments else text.rstrip()
        lines.append(('\t' * indent + shown) if shown else '')
        if nested:
            lines.extend(show_lines(nested, nested_comments, nested_comments, indent + 1))
    return lines


def _show(args):
    try:
        lines = show_lines(args.type, comments=args.all_comments or not args.no_comments,
                           nested_comments=args.all_comments)
    except (ValueError, LookupError) as exc:
        return fail(str(exc))
    for line in lines:
        print(line)
    return 0


def _list(args):
    from ament_index_python.packages import get_packages_with_prefixes
    found = {kind: [] for kind in INTERFACE_KINDS}
    for package, prefix in sorted(get_packages_with_prefixes().items()):
        for kind in INTERFACE_KINDS:
            folder = os.path.join(prefix, 'share', package, kind)
            if os.path.isdir(folder):
                found[kind].extend(
                    f'{package}/{kind}/{name[:-len(kind) - 1]}'
                    for name in sorted(os.listdir(folder)) if name.endswith('.' + kind))
    titles = {'msg': 'Messages', 'srv': 'Services', 'action': 'Actions'}
    for kind in INTERFACE_KINDS:
        if getattr(args, f'only_{kind}') or not any(
                getattr(args, f'only_{k}') for k in INTERFACE_KINDS):
            print(f'{titles[kind]}:')
            for name in found[kind]:
                print(f'    {name}')
    return 0


def interface_packages():
    """
    Return the packages registering interfaces in the ament index (``rosidl_interfaces``).

    :returns: dict package name -> install prefix.
    """
    from ament_index_python import get_resources
    return get_resources('rosidl_interfaces')


def package_interfaces(package):
    """
    Return the interfaces of ``package`` as ``pkg/kind/Type``, sorted (ros2interface).

    :param package: package name.
    :returns: list of str.
    :raises LookupError: ``Unknown package 'p'`` when it registers no interfaces.
    """
    from ament_index_python import get_resource
    try:
        content, _ = get_resource('rosidl_interfaces', package)
    except LookupError:
        raise LookupError(f"Unknown package '{package}'") from None
    names = set()
    for line in content.splitlines():
        kind, _, filename = line.strip().partition('/')
        base, _, ext = filename.rpartition('.')
        if kind in INTERFACE_KINDS and ext == 'idl' and base:
            names.add(f'{package}/{kind}/{base}')
    return sorted(names)


def _packages(args):
    kinds = [k for k, flag in (('msg', args.only_msgs), ('srv', args.only_srvs),
                               ('action', args.only_actions)) if flag]
    for name in sorted(interface_packages()):
        if kinds and not any(i.split('/')[1] in kinds for i in package_interfaces(name)):
            continue
        print(name)
    return 0


def _package(args):
    try:
        names = package_interfaces(args.package_name)
    except LookupError as exc:
        return fail(str(exc))
    for name in names:
        print(name)
    return 0


def _arguments_show(p):
    """Add the arguments of ``ros2 interface show``."""
    group = p.add_mutually_exclusive_group()
    group.add_argument('--all-comments', action='store_true',
                       help='Show all comments, including for nested interface definitions')
    group.add_argument('--no-comments', action='store_true',
                       help='Show no comments or whitespace')
    p.add_argument('type', help="Show an interface definition (e.g. 'std_msgs/msg/String')")


VERB_SHOW = Verb('Output the interface definition', _show, _arguments_show)
"""``ros2 interface show``."""


def _arguments_list(p):
    """Add the arguments of ``ros2 interface list``."""
    p.add_argument('-m', '--only-msgs', dest='only_msg', action='store_true',
                   help='Print out only the message types')
    p.add_argument('-s', '--only-srvs', dest='only_srv', action='store_true',
                   help='Print out only the service types')
    p.add_argument('-a', '--only-actions', dest='only_action', action='store_true',
                   help='Print out only the action types')


VERB_LIST = Verb('List all interface types available', _list, _arguments_list)
"""``ros2 interface list``."""


def _arguments_packages(p):
    """Add the arguments of ``ros2 interface packages``."""
    p.add_argument('-m', '--only-msgs', action='store_true',
                   help='Only list packages that generate messages')
    p.add_argument('-s', '--only-srvs', action='store_true',
                   help='Only list packages that generate services')
    p.add_argument('-a', '--only-actions', action='store_true',
                   help='Only list packages that generate actions')


VERB_PACKAGES = Verb(
    'Output a list of packages that provide interfaces',
    _packages, _arguments_packages)
"""``ros2 interface packages``."""


def _arguments_package(p):
    """Add the arguments of ``ros2 interface package``."""
    p.add_argument('package_name', help="Name of the ROS package (e.g. 'example_interfaces')")


VERB_PACKAGE = Verb(
    'Output a list of available interface types within one package',
    _package, _arguments_package)
"""``ros2 interface package``."""


COMMAND = Command('Show information about ROS interfaces')
"""``ros2 interface``: its verbs are registered in ``amr_description.interface.verb``."""
