# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``ros2 control view_controller_chains``: the controller/interface graph, as upstream draws it.

As ros2controlcli's ``view_controller_chains`` (jazzy), built with the ``graphviz`` Python
package (PyPI): a left-to-right directed graph ``g`` of record nodes with rounded corners,
one per controller (its name, then a column of the state interfaces it reads — ``(state)``
from the hardware, ``(exp state)`` from another controller — and of its exported references
``(exp ref)``, then a column of the command interfaces it writes ``(cmd)`` and its exported
states), plus ``hw state_interfaces`` and ``hw command_interfaces``; an edge per state
interface read and per command interface written. The diagram is saved as
``controller_diagram.gv`` (the DOT source) and ``controller_diagram.pdf`` in the current
directory; rendering the PDF needs Graphviz's ``dot`` program (Debian package ``graphviz``),
and without it the verb keeps the ``.gv`` and says which package to install.
"""

import os
import sys

DIAGRAM = 'controller_diagram'
DEBIAN_PACKAGE = 'graphviz'


def _field(port, text):
    # record labels treat these as syntax
    for ch in '{}|<>':
        text = text.replace(ch, '\\' + ch)
    return f'<{port}> {text}'


def _record(title, left, right):
    """Return a record label: title | {left fields} | {right fields} (empty sides skipped)."""
    columns = [' | '.join(_field(p, t) for p, t in side) for side in (left, right) if side]
    if not columns:
        return title
    return title + '|{' + '|'.join('{' + c + '}' for c in columns) + '}'


def build_graph(controllers, hardware):
    """
    Build the diagram of a ``ListControllers`` and a ``ListHardwareComponents`` response.

    :param controllers: ``controller_manager_msgs/srv/ListControllers`` response.
    :param hardware: ``controller_manager_msgs/srv/ListHardwareComponents`` response.
    :returns: a :class:`graphviz.Digraph` (not rendered).
    :raises ImportError: when the ``graphviz`` Python package is missing.
    """
    import graphviz
    hw_commands = sorted({i.name for c in hardware.component for i in c.command_interfaces})
    hw_states = sorted({i.name for c in hardware.component for i in c.state_interfaces})
    # full name of an interface a controller exports -> (owner, name as exported)
    refs, exported = {}, {}
    for ctrl in controllers.controller:
        for name in ctrl.reference_interfaces:
            refs[f'{ctrl.name}/{name}'] = (ctrl.name, name)
        for name in ctrl.exported_state_interfaces:
            exported[f'{ctrl.name}/{name}'] = (ctrl.name, name)
    graph = graphviz.Digraph('g', filename=DIAGRAM,
                             graph_attr={'rankdir': 'LR', 'ranksep': '2'},
                             node_attr={'shape': 'record', 'style': 'rounded'})
    for ctrl in sorted(controllers.controller, key=lambda c: c.name):
        states = sorted(set(ctrl.required_state_interfaces))
        commands = sorted(set(ctrl.required_command_interfaces))
        left = [(f'state_end_{i}', f'{i} (exp state)' if i in exported else f'{i} (state)')
                for i in sorted(states, key=lambda i: (i in exported, i))]
        left += [(f'controller_end_{i}', f'{i} (exp ref)')
                 for i in sorted(ctrl.reference_interfaces)]
        right = [(f'command_start_{i}', f'{i} (cmd)')
                 for i in sorted(commands, key=lambda i: (i in refs, i)) if i not in refs]
        right += [(f'controller_start_{i}', f'{i} (exp state)')
                  for i in sorted(ctrl.exported_state_interfaces)]
        right += [(f'command_start_{i}', f'{i} (cmd)') for i in commands if i in refs]
        graph.node(ctrl.name, _record(ctrl.name, left, right))
    graph.node('state_interfaces', _record(
        'hw state_interfaces', [(f'state_start_{i}', i) for i in hw_states], []))
    graph.node('command_interfaces', _record(
        'hw command_interfaces', [(f'command_end_{i}', i) for i in hw_commands], []))
    for ctrl in sorted(controllers.controller, key=lambda c: c.name):
        for i in sorted(set(ctrl.required_state_interfaces)):
            if i in exported:
                owner, name = exported[i]
                source = f'{owner}:controller_start_{name}'
            else:
                source = f'state_interfaces:state_start_{i}'
            graph.edge(source, f'{ctrl.name}:state_end_{i}')
        for i in sorted(set(ctrl.required_command_interfaces)):
            if i in refs:
                owner, name = refs[i]
                target = f'{owner}:controller_end_{name}'
            else:
                target = f'command_interfaces:command_end_{i}'
            graph.edge(f'{ctrl.name}:command_start_{i}', target)
    return graph


def write_diagram(controllers, hardware, view=False, directory=None):
    """
    Write ``controller_diagram.gv`` and render ``controller_diagram.pdf`` (see module doc).

    With ``view`` and a display, the PDF is opened in a viewer as upstream does; without a
    display the diagram is saved instead, with a note on stderr.

    :param controllers: ``ListControllers`` response.
    :param hardware: ``ListHardwareComponents`` response.
    :param view: open a viewer (upstream's default) rather than only saving.
    :param directory: where to write (default: the current directory).
    :returns: 0 when the PDF was written (or shown), 1 when only the ``.gv`` could be
        (one line naming the Debian package to install), or an error string.
    """
    try:
        import graphviz
    except ImportError:
        return ("view_controller_chains needs the Python package 'graphviz' "
                '(pip install graphviz)')
    directory = os.path.abspath(directory or os.curdir)
    graph = build_graph(controllers, hardware)
    source = os.path.join(directory, f'{DIAGRAM}.gv')
    with open(source, 'w') as f:
        f.write(graph.source)
    if view and not (os.environ.get('DISPLAY') or os.environ.get('WAYLAND_DISPLAY')):
        print('No display detected, saving the diagram instead of opening a viewer.',
              file=sys.stderr)
        view = False
    try:
        path = graph.render(outfile=os.path.join(directory, f'{DIAGRAM}.pdf'), format='pdf',
                            view=view, cleanup=False)
    except graphviz.ExecutableNotFound:
        print(f'Saved controller diagram source to {source}')
        return (f"Could not render {DIAGRAM}.pdf: Graphviz's 'dot' program was not found; "
                f'install the Debian package {DEBIAN_PACKAGE} (apt-get install '
                f'{DEBIAN_PACKAGE})')
    except Exception as exc:  # noqa: B902 - e.g. no viewer for the format
        print(f'Could not open a viewer ({exc}), saving the diagram instead.', file=sys.stderr)
        path = graph.render(outfile=os.path.join(directory, f'{DIAGRAM}.pdf'), format='pdf',
                            view=False, cleanup=False)
    print(f'Saved controller diagram to {os.path.abspath(path)}')
    return 0
