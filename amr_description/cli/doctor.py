# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

r"""
``ros2 doctor [-r|-rf] [-iw]``: check the ROS 2 set-up, in the format of ros2doctor (jazzy).

Checks (category: what fails it) run in order; a problem is printed as a Python warning line
``<file>: <line>: UserWarning: <text>`` on stderr, as upstream's ``doctor_warn``; then
``All N checks passed`` or ``N/M check(s) failed`` and ``Failed modules: ...`` (blank lines
around, as upstream). Errors fail a check, warnings only with ``--include-warnings``.

* ``platform``: ``ROS_DISTRO`` unset (error) or not ``jazzy`` (warning); ``ROS_VERSION`` not 2.
* ``network``: no loopback interface (error); a network-wide discovery range with no
  multicast-capable interface (warning).
* ``middleware``: ``RMW_IMPLEMENTATION`` names an rmw that rclpy cannot load (error).
* ``environment``: ``ROS_DOMAIN_ID`` not an integer 0..232 (error; Fast DDS refuses more),
  ``ROS_AUTOMATIC_DISCOVERY_RANGE`` not one of ``SUBNET``, ``LOCALHOST``, ``OFF``,
  ``SYSTEM_DEFAULT`` (error).
* ``topic``: a publisher without subscriber or a subscriber without publisher (warnings, as
  upstream's TopicCheck).
* ``stack``: with the simulator running (node ``/mujoco_sim``), each of ``/clock``,
  ``/joint_states``, ``/odom``, ``/tf`` must have a publisher (error).

``-r`` prints every report: ``\n   NAME`` then ``item<pad>: value`` lines, padded to the
longest item name + 4, as upstream's ``format_print``; ``-rf`` only those of failed checks.
The exit code is 0 whatever the checks found, as upstream.
"""

import os
import platform
import socket
import sys
import warnings

from amr_description.cli.common import cli_node
from amr_description.cli.common import default_node_name
from amr_description.cli.common import wait_for_graph
from amr_description.cli.extension import Command

STACK_TOPICS = ('/clock', '/joint_states', '/odom', '/tf')
DISCOVERY_RANGES = ('SUBNET', 'LOCALHOST', 'OFF', 'SYSTEM_DEFAULT')
_IFF_UP, _IFF_LOOPBACK, _IFF_MULTICAST = 0x1, 0x8, 0x1000


def _warning_format(message, category, filename, lineno, file=None, line=None):
    return f'{filename}: {lineno}: {category.__name__}: {message}\n'


class Result:
    """Errors and warnings of one check; each is printed as a warning when added."""

    def __init__(self):
        """Start with no error and no warning."""
        self.error = 0
        self.warning = 0

    def add_error(self, message):
        """Count and print an error."""
        warnings.warn(message, stacklevel=2)
        self.error += 1

    def add_warning(self, message):
        """Count and print a warning."""
        warnings.warn(message, stacklevel=2)
        self.warning += 1


def network_interfaces():
    """
    Describe the network interfaces from ``/sys/class/net`` and ``socket``.

    :returns: list of dicts with ``device``, ``flags`` (int), ``mtu``, ``ether`` and ``inet``
        (IPv4 address or None).
    """
    import fcntl
    import struct
    found = []
    for _, name in socket.if_nameindex():
        base = os.path.join('/sys/class/net', name)

        def read(item, default=''):
            try:
                with open(os.path.join(base, item)) as f:
                    return f.read().strip()
            except OSError:
                return default
        inet = None
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sock:
            try:
                packed = fcntl.ioctl(sock.fileno(), 0x8915,  # SIOCGIFADDR
                                     struct.pack('256s', name.encode()[:15]))
                inet = socket.inet_ntoa(packed[20:24])
            except OSError:
                pass
        found.append({'device': name, 'flags': int(read('flags', '0x0'), 16),
                      'mtu': read('mtu'), 'ether': read('address'), 'inet': inet})
    return found


def _check_platform(env):
    result = Result()
    distro = env.get('ROS_DISTRO')
    if not distro:
        result.add_error('ROS_DISTRO is not set.')
    elif distro != 'jazzy':
        result.add_warning(f"ROS_DISTRO is '{distro}'; this installation is jazzy.")
    if env.get('ROS_VERSION', '2') != '2':
        result.add_error(f"ROS_VERSION is '{env.get('ROS_VERSION')}'; expected 2.")
    return result


def _check_network(env):
    result = Result()
    interfaces = network_interfaces()
    if not any(i['flags'] & _IFF_LOOPBACK and i['flags'] & _IFF_UP for i in interfaces):
        result.add_error('No loopback IP address is found.')
    if env.get('ROS_AUTOMATIC_DISCOVERY_RANGE', 'SUBNET') != 'LOCALHOST' and not any(
            i['flags'] & _IFF_MULTICAST and not i['flags'] & _IFF_LOOPBACK
            for i in interfaces):
        result.add_warning('No multicast-capable network interface: discovery beyond this '
                           'machine will not work.')
    return result


def _check_middleware(env):
    result = Result()
    try:
        from rclpy.utilities import get_rmw_implementation_identifier
        get_rmw_implementation_identifier()
    except Exception as exc:  # noqa: B902 - any load failure of the rmw is the finding
        result.add_error('Unable to load the RMW implementation '
                         f"'{env.get('RMW_IMPLEMENTATION', 'default')}': {exc}")
    return result


def _check_environment(env):
    result = Result()
    domain = env.get('ROS_DOMAIN_ID', '0') or '0'
    if not domain.isdigit() or int(domain) > 232:
        result.add_error(f"ROS_DOMAIN_ID '{domain}' is not an integer from 0 to 232.")
    discovery = env.get('ROS_AUTOMATIC_DISCOVERY_RANGE')
    if discovery is not None and discovery not in DISCOVERY_RANGES:
        result.add_error(f"ROS_AUTOMATIC_DISCOVERY_RANGE '{discovery}' is not one of "
                         f"{', '.join(DISCOVERY_RANGES)}.")
    return result


def _check_topic(graph):
    result = Result()
    for name, _, pubs, subs in graph['topics']:
        if name in ('/parameter_events', '/rosout'):
            continue
        if pubs and not subs:
            result.add_warning(f'Publisher without subscriber detected on {name}.')
        elif subs and not pubs:
            result.add_warning(f'Subscriber without publisher detected on {name}.')
    return result


def _check_stack(graph):
    result = Result()
    if '/mujoco_sim' not in graph['nodes']:
        return result
    counts = {name: pubs for name, _, pubs, _ in graph['topics']}
    for topic in STACK_TOPICS:
        if not counts.get(topic):
            result.add_error(f'The simulator runs but nothing publishes {topic}.')
    return result


def _graph(spin_time):
    with cli_node(default_node_name()) as node:
        topics = wait_for_graph(node, lambda n: n.get_topic_names_and_types(),
                                settle=spin_time, minimum=spin_time, maximum=spin_time)
        own = node.get_fully_qualified_name()
        nodes = {f'{ns.rstrip("/")}/{nm}' for nm, ns in node.get_node_names_and_namespaces()}
        info = []
        for name, types in topics:
            pubs = [i for i in node.get_publishers_info_by_topic(name)
                    if f'{i.node_namespace.rstrip("/")}/{i.node_name}' != own]
            subs = [i for i in node.get_subscriptions_info_by_topic(name)
                    if f'{i.node_namespace.rstrip("/")}/{i.node_name}' != own]
            if pubs or subs:
                info.append((name, types, len(pubs), len(subs)))
    return {'topics': info, 'nodes': nodes - {own}}


def _reports(env, graph):
    import rclpy.utilities
    reports = []
    items = []
    for i in network_interfaces():
        items += [('device', i['device']), ('flags', hex(i['flags'])), ('mtu', i['mtu'])]
        if i['inet']:
            items.append(('inet', i['inet']))
        if i['ether']:
            items.append(('ether', i['ether']))
    reports.append(('network', 'NETWORK CONFIGURATION', items))
    uname = platform.uname()
    reports.append(('platform', 'PLATFORM INFORMATION', [
        ('system', uname.system), ('platform info', platform.platform()),
        ('release', uname.release), ('processor', uname.machine)]))
    try:
        rmw = rclpy.utilities.get_rmw_implementation_identifier()
    except Exception as exc:  # noqa: B902 - reported, not raised
        rmw = f'unavailable ({exc})'
    reports.append(('middleware', 'RMW MIDDLEWARE', [('middleware name', rmw)]))
    reports.append(('platform', 'ROS 2 INFORMATION', [
        ('distribution name', env.get('ROS_DISTRO', '')),
        ('distribution type', 'ros2'), ('distribution status', 'active'),
        ('python version', platform.python_version())]))
    reports.append(('environment', 'ROS ENVIRONMENT', [
        ('ROS_DOMAIN_ID', env.get('ROS_DOMAIN_ID', '0 (unset)')),
        ('ROS_AUTOMATIC_DISCOVERY_RANGE',
         env.get('ROS_AUTOMATIC_DISCOVERY_RANGE', 'SUBNET (unset)')),
        ('RMW_IMPLEMENTATION', env.get('RMW_IMPLEMENTATION', '(unset)'))]))
    items = []
    for name, _, pubs, subs in graph['topics']:
        items += [('topic', name), ('publisher count', pubs), ('subscriber count', subs)]
    reports.append(('topic', 'TOPIC LIST', items or [
        ('topic', 'none'), ('publisher count', 0), ('subscriber count', 0)]))
    return reports


def format_report(name, items):
    r"""
    Return one report as upstream's ``format_print`` prints it.

    :param name: report title, e.g. ``'RMW MIDDLEWARE'``.
    :param items: ``[(item name, value), ...]``.
    :returns: ``'\n   NAME\n'`` then ``'<item padded to longest + 4>: value'`` lines.
    """
    pad = max((len(k) for k, _ in items), default=0) + 4
    return f'\n   {name}\n' + ''.join(f'{k:{pad}}: {v}\n' for k, v in items)


def _main(args):
    env = dict(os.environ)
    warnings.formatwarning = _warning_format
    warnings.simplefilter('always', UserWarning)
    try:
        graph = _graph(args.spin_time)
    except Exception as exc:  # noqa: B902 - e.g. an invalid domain id: the checks say why
        graph = {'topics': [], 'nodes': set()}
        warnings.warn(f'Cannot join the ROS graph: {" ".join(str(exc).split())}')
    if args.report:
        for _, name, items in _reports(env, graph):
            sys.stdout.write(format_report(name, items))
        return 0
    checks = [('platform', lambda: _check_platform(env)),
              ('network', lambda: _check_network(env)),
              ('middleware', lambda: _check_middleware(env)),
              ('environment', lambda: _check_environment(env)),
              ('topic', lambda: _check_topic(graph)),
              ('stack', lambda: _check_stack(graph))]
    failed = []
    for category, check in checks:
        result = check()
        sys.stderr.flush()
        if result.error or (args.include_warnings and result.warning):
            failed.append(category)
    if failed:
        print(f'\n{len(failed)}/{len(checks)} check(s) failed\n')
        print('Failed modules:', *failed)
        if args.report_failed:
            for category, name, items in _reports(env, graph):
                if category in failed:
                    sys.stdout.write(format_report(name, items))
        return 0  # upstream exits 0 whatever the checks found
    print(f'\nAll {len(checks)} checks passed\n')
    return 0


def _arguments(parser):
    """Add the arguments of ``ros2 doctor`` (and ``ros2 wtf``)."""
    group = parser.add_mutually_exclusive_group(required=False)
    group.add_argument('--report', '-r', action='store_true', help='Print all reports.')
    group.add_argument('--report-failed', '-rf', action='store_true',
                       help='Print reports of failed checks only.')
    parser.add_argument('--include-warnings', '-iw', action='store_true',
                        help='Include warnings as failed checks. Warnings are ignored by '
                             'default.')
    parser.add_argument('--spin-time', type=float, default=2.0, metavar='SECONDS',
                        help='Spin time in seconds to wait for discovery (default: 2.0)')


COMMAND = Command('Check ROS setup and other potential issues', _arguments, _main)
"""``ros2 doctor``, registered also as ``ros2 wtf`` (as ros2doctor)."""
