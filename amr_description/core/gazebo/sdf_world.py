# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
SDF worlds: the subset of SDFormat 1.6-1.11 that Gazebo worlds use, read into plain data.

No SDF library installs here (docs/worlds.md), so this module reads what worlds are made of:
``<world>`` with its ``<physics>`` (``max_step_size``, ``real_time_factor``) and ``<gravity>``;
``<model>`` (``<static>``, ``<pose>``, ``<link>``, ``<frame>``, nested ``<model>``);
``<include>`` (``<uri>``, ``<name>``, ``<pose>``, ``<static>``); ``<link>`` with
``<inertial>``, ``<collision>`` and ``<visual>``; the geometries ``box``, ``cylinder``,
``sphere``, ``capsule``, ``ellipsoid``, ``plane`` and ``mesh``; ``<surface><friction><ode>``
``<mu>``/``<mu2>``; ``<visual><material>`` ``<diffuse>``/``<ambient>``; and the ``<state>`` block
of a world saved from the Gazebo GUI (the initial poses of the models it names).

Poses follow SDFormat's frame semantics (sdformat.org, "Pose frame semantics", 1.7+): a
``<pose>`` is ``x y z roll pitch yaw`` (m, rad; ``degrees="true"``; ``rotation_format=
"quat_xyzw"`` gives 7 numbers) relative to ``relative_to`` when given, else to the parent
element's frame (a model's to the world, a link's to its model, a collision's or a visual's
to its link, a ``<frame>``'s to what it is ``attached_to``). Rotations are fixed-axis
roll-pitch-yaw (the URDF convention, :func:`~amr_description.core.kinematics.rpy_to_matrix`).

URIs: ``model://NAME/...`` resolves through ``GZ_SIM_RESOURCE_PATH`` (then the older
``IGN_GAZEBO_RESOURCE_PATH`` and ``SDF_PATH``) and the extra folders given (the package's own
``worlds/models``, with Gazebo's ``ground_plane`` and ``sun``: Fuel's "Ground Plane" and
"Sun" resolve to them, :data:`FUEL_SHIPPED`); a model folder's ``model.config`` names its SDF
file (``model.sdf`` when it has none). An included ``<light>`` (``model://sun``) is listed
with the world's elements that are not simulated. ``package://`` resolves through the ament
index; ``file://`` and relative paths against the file that names them. An ``http(s)`` (Fuel)
URI other than those two, a ``model://`` that is not found,
a bad included model, a model with joints (articulated models are not simulated yet): one line
each in :attr:`World.messages` and the world loads without that model, as gz-sim carries on
past a missing model. A world that cannot be read at all raises :class:`WorldError` (one line,
naming the file).
"""

import os

from amr_description.core.gazebo.sdf_elements import child_number
from amr_description.core.gazebo.sdf_elements import child_text
from amr_description.core.gazebo.sdf_elements import Link
from amr_description.core.gazebo.sdf_elements import Model
from amr_description.core.gazebo.sdf_elements import PartError
from amr_description.core.gazebo.sdf_elements import pose_matrix
from amr_description.core.gazebo.sdf_elements import read_geometry
from amr_description.core.gazebo.sdf_elements import sdf_bool
from amr_description.core.gazebo.sdf_elements import sdf_floats
from amr_description.core.gazebo.sdf_elements import Shape
from amr_description.core.gazebo.sdf_elements import World
from amr_description.core.gazebo.sdf_resources import find_world
from amr_description.core.gazebo.sdf_resources import fuel_model_name
from amr_description.core.gazebo.sdf_resources import FUEL_SHIPPED
from amr_description.core.gazebo.sdf_resources import RESOURCE_PATH_VARIABLES
from amr_description.core.gazebo.sdf_resources import shipped_worlds_folder
from amr_description.core.gazebo.sdf_resources import WorldError
from amr_description.core.geodesy import SphericalCoordinates
from amr_description.core.model_check.links import inertia_problems
from amr_description.core.xml_document import parse_file
from amr_description.core.xml_document import XMLError
import numpy as np

NEWEST_VERSION = (1, 11)
"""The newest SDFormat version read without a warning (sdformat 14, Gazebo Harmonic)."""

STEP_RANGE = (1e-5, 0.01)
"""Physics steps (s) that work with MuJoCo and a robot: a smaller one leaves sim time still,
a larger one lets a wheel sink through the ground; others are clamped with a warning."""

MAX_NESTING = 32
"""Nested ``<include>`` files, or nested ``<model>`` s, deeper than this leave the model out."""

SIMULATED_WORLD_ELEMENTS = ('physics', 'gravity', 'model', 'include', 'state', 'frame',
                            'spherical_coordinates')
"""``<world>`` children read; every other one is listed once as not simulated."""


def collapse_repeats(lines):
    """
    Return ``lines`` with each repeated line once, followed by ``(N times)`` (first order kept).

    A world that uses one missing mesh in sixteen models says so in one line.
    """
    counts = {}
    for line in lines:
        counts[line] = counts.get(line, 0) + 1
    return [line if n == 1 else f'{line} ({n} times)' for line, n in counts.items()]


def _version(root, source, messages):
    text = root.get('version', '')
    try:
        version = tuple(int(v) for v in text.split('.')[:2])
    except ValueError:
        version = ()
    if len(version) != 2:
        messages.append(f'{source}: <sdf version="{text}"> is not a version number (expected '
                        f'MAJOR.MINOR); read as {NEWEST_VERSION[0]}.{NEWEST_VERSION[1]}')
    elif version > NEWEST_VERSION:
        messages.append(f'{source}: <sdf version="{text}"> is newer than '
                        f'{NEWEST_VERSION[0]}.{NEWEST_VERSION[1]}; read as '
                        f'{NEWEST_VERSION[0]}.{NEWEST_VERSION[1]}')


def _parse_file(path, what):
    """Return the root element of an XML file; raise PartError with file and line."""
    try:
        return parse_file(path)
    except OSError as exc:
        raise PartError(f'{path}: cannot read {what}: {exc.strerror or exc}') from None
    except XMLError as exc:
        raise PartError(f'{path}:{exc.line}: malformed XML ({exc.reason}, '
                        f'column {exc.column})') from None


class _Reader:
    """The state of one world read: resource folders, include stack, messages."""

    def __init__(self, source, model_paths):
        self.source = source
        self.model_paths = list(model_paths)
        self.messages = []
        self.stack = [os.path.abspath(source)]
        self.included_tags = set()  # world elements that came through an <include>

    # ------------------------------------------------------------------ URIs
    def search_path(self):
        folders = []
        for variable in RESOURCE_PATH_VARIABLES:
            folders += [p for p in os.environ.get(variable, '').split(os.pathsep) if p]
        return folders + self.model_paths

    def resolve(self, uri, base):
        """Return the file or folder of ``uri`` named in file ``base``; raise PartError."""
        uri = uri.strip()
        shipped = FUEL_SHIPPED.get((fuel_model_name(uri) or '').lower())
        if shipped is not None:
            uri = f'model://{shipped}'
        if uri.startswith(('http://', 'https://')):
            raise PartError(f'{uri}: Fuel models are not downloaded here (put the model in a '
                            'folder of GZ_SIM_RESOURCE_PATH)')
        if uri.startswith('model://'):
            name, _, rest = uri[len('model://'):].partition('/')
            for folder in self.search_path():
                candidate = os.path.join(folder, name)
                if os.path.isdir(candidate):
                    return os.path.join(candidate, rest) if rest else candidate
            searched = ':'.join(self.search_path()) or 'empty'
            raise PartError(f'{uri} not found in GZ_SIM_RESOURCE_PATH ({searched})')
        if uri.startswith('package://'):
            from amr_description.core.description.files import resolve_uri
            return resolve_uri(uri)
        if uri.startswith('file://'):
            uri = uri[len('file://'):]
        return os.path.normpath(os.path.join(os.path.dirname(base), uri))

    @staticmethod
    def model_file(folder):
        """Return the SDF file of a model folder (``model.config``, else ``model.sdf``)."""
        if os.path.isfile(folder):
            return folder
        config = os.path.join(folder, 'model.config')
        if os.path.isfile(config):
            root = _parse_file(config, 'the model.config')
            files = [e for e in root.iter('sdf') if (e.text or '').strip()]
            if files:
                best = max(files, key=lambda e: tuple(
                    int(v) if v.isdigit() else 0 for v in e.get('version', '0').split('.')))
                return os.path.join(folder, best.text.strip())
        return os.path.join(folder, 'model.sdf')

    # ------------------------------------------------------------------ world
    def world(self, root):
        if root.tag == 'robot':
            raise WorldError(f'{self.source}: this is a URDF (<robot>), not an SDF world; '
                             'spawn it with create -file')
        if root.tag != 'sdf':
            raise WorldError(f'{self.source}: expected an <sdf> document, found <{root.tag}>')
        _version(root, self.source, self.messages)
        element = root.find('world')
        if element is None:
            raise WorldError(f'{self.source}: no <world> in this SDF file')
        world = World(name=element.get('name', 'default'), source=self.source)
        try:
            self._physics(element, world)
        except PartError as exc:
            raise WorldError(f'{self.source}: {exc}') from None
        models = []
        for child in element:
            try:
                if child.tag == 'model':
                    models.append((child, self.model(child, self.source, None)))
                elif child.tag == 'include':
                    model = self.include(child, self.source)
                    if model is not None:
                        models.append((child, model))
            except PartError as exc:
                self.messages.append(str(exc) + ': the world loads without it')
        names = {}
        for child, model in models:  # sdformat: names unique in a world; the first one kept
            if names.setdefault(model.name, child) is not child:
                self.messages.append(f'model {model.name!r}: a second model of that name: the '
                                     'world loads without it')
        models = [(child, model) for child, model in models if names[model.name] is child]
        self._place_models(element, models)
        world.models = [m for _, m in models]
        self._state(element, world)
        world.not_simulated = sorted({c.tag for c in element
                                      if c.tag not in SIMULATED_WORLD_ELEMENTS} |
                                     self.included_tags)
        world.messages = self.messages
        return world

    def _spherical(self, element, world):
        """Read ``<spherical_coordinates>`` (WGS84 and ENU only; else one line, unset)."""
        spherical = element.find('spherical_coordinates')
        if spherical is None:
            return
        where = '<spherical_coordinates>'
        model = child_text(spherical, 'surface_model', 'EARTH_WGS84')
        orientation = child_text(spherical, 'world_frame_orientation', 'ENU')
        if model != 'EARTH_WGS84' or orientation != 'ENU':
            self.messages.append(f'{where}: only surface_model EARTH_WGS84 with '
                                 f'world_frame_orientation ENU is simulated, found {model} '
                                 f'{orientation}: navsat sensors have no origin')
            return
        latitude = child_number(spherical, 'latitude_deg', 0.0, where)
        if not -90.0 <= latitude <= 90.0:
            self.messages.append(f'{where}<latitude_deg>: expected -90..90 deg, found '
                                 f'{latitude:g}: navsat sensors have no origin')
            return
        world.spherical_coordinates = SphericalCoordinates(
            latitude,
            child_number(spherical, 'longitude_deg', 0.0, where),
            child_number(spherical, 'elevation', 0.0, where),
            child_number(spherical, 'heading_deg', 0.0, where))

    def _physics(self, element, world):
        physics = element.findall('physics')
        chosen = next((p for p in physics if sdf_bool(p.get('default'))),
                      physics[0] if physics else None)
        if chosen is not None:
            world.physics_step = child_number(chosen, 'max_step_size', 0.001, '<physics>')
            world.real_time_factor = child_number(chosen, 'real_time_factor', 1.0, '<physics>')
            if not world.physics_step > 0:
                raise PartError(f'<physics><max_step_size> must be > 0 s, found '
                                f'{world.physics_step:g}')
            if not world.real_time_factor >= 0:
                raise PartError(f'<physics><real_time_factor> must be >= 0, found '
                                f'{world.real_time_factor:g}')
            step = min(max(world.physics_step, STEP_RANGE[0]), STEP_RANGE[1])
            if step != world.physics_step:  # sim time stands still, or robots fall through
                self.messages.append(f'<physics><max_step_size> {world.physics_step:g} s is out '
                                     f'of {STEP_RANGE[0]:g}..{STEP_RANGE[1]:g} s: {step:g} s used')
                world.physics_step = step
        self._spherical(element, world)
        gravity = child_text(element, 'gravity')
        if gravity is not None:
            world.gravity = sdf_floats(gravity, 3, '<world><gravity>')

    def _place_models(self, element, models):
        """Resolve each model's ``<pose relative_to>`` against world frames and models."""
        world_frames = {f.get('name'): f for f in element.findall('frame')}

        def frame_pose(name, seen):
            if name in ('', 'world'):
                return np.eye(4)
            if name in seen:
                raise PartError(f'<frame> {name!r}: a cycle of relative_to')
            seen = seen | {name}
            for _, model in models:
                if model.name == name:
                    return frame_pose(model.relative_to, seen) @ model.pose
            frame = world_frames.get(name)
            if frame is None:
                raise PartError(f'relative_to {name!r}: no such frame or model in the world')
            pose = frame.find('pose')
            base = (pose.get('relative_to') if pose is not None else None) or \
                frame.get('attached_to', '')
            return frame_pose(base, seen) @ pose_matrix(pose, f'<frame name="{name}">')

        placed = {}
        for entry in list(models):
            model = entry[1]
            if model.relative_to:
                try:
                    placed[model.name] = frame_pose(model.relative_to, {model.name}) @ \
                        model.pose
                except PartError as exc:
                    self.messages.append(f'model {model.name!r}: {exc}: the world loads '
                                         'without it')
                    models.remove(entry)
        for _, model in models:
            if model.name in placed:
                model.pose, model.relative_to = placed[model.name], ''

    def _state(self, element, world):
        """Apply a saved ``<state>``'s model poses (the first ``<state>`` block)."""
        state = element.find('state')
        if state is None:
            return
        for entry in state.findall('model'):
            model = world.model(entry.get('name', ''))
            if model is None or entry.find('pose') is None:
                continue
            try:
                model.pose = pose_matrix(entry.find('pose'), f'<state> model {model.name!r}')
            except PartError as exc:
                self.messages.append(str(exc))

    # ------------------------------------------------------------------ models
    def include(self, element, base):
        uri = child_text(element, 'uri')
        if not uri:
            raise PartError(f'{base}: <include> without <uri>')
        target = self.model_file(self.resolve(uri, base))
        if os.path.abspath(target) in self.stack:
            raise PartError(f'{uri}: an include cycle ({" -> ".join(self.stack + [target])})')
        if len(self.stack) > MAX_NESTING:  # a chain of files: an error, not a RecursionError
            raise PartError(f'{uri}: more than {MAX_NESTING} nested <include>s, from '
                            f'{self.stack[0]} to {target}')
        root = _parse_file(target, 'the model')
        inner = root.find('model')
        if inner is None and root.find('light') is not None:
            self.included_tags.add('light')  # a light (model://sun): not simulated
            return None
        if inner is None:
            raise PartError(f'{uri} ({target}): no <model> in it')
        self.stack.append(os.path.abspath(target))
        try:
            model = self.model(inner, target, element.get('name') or
                               child_text(element, 'name'))
        finally:
            self.stack.pop()
        if element.find('pose') is not None:
            model.pose = pose_matrix(element.find('pose'), f'<include> {uri}')
            model.relative_to = element.find('pose').get('relative_to', '')
        static = child_text(element, 'static')
        if static is not None:
            model.static = sdf_bool(static)
        return model

    def model(self, element, source, name=None):
        name = name or element.get('name', '')
        if not name:
            raise PartError(f'{source}: a <model> without a name')
        where = f'model {name!r}'
        if element.find('joint') is not None:
            raise PartError(f'{where} has joints: articulated SDF models are not simulated yet')
        pose_element = element.find('pose')
        model = Model(name=name, pose=pose_matrix(pose_element, where),
                      static=sdf_bool(child_text(element, 'static', 'false')))
        model.relative_to = pose_element.get('relative_to', '') \
            if pose_element is not None else ''
        model.links = self._links(element, source, where)
        return model

    def _links(self, element, source, where, prefix=''):
        """Return the links of a model (nested models flattened) posed in its frame."""
        if prefix.count('::') > MAX_NESTING:
            raise PartError(f'{where}: models nested more than {MAX_NESTING} deep')
        frames = {'__model__': np.eye(4), '': np.eye(4)}
        pending = [(e, 'link') for e in element.findall('link')] + \
            [(e, 'frame') for e in element.findall('frame')]
        declared = {e.get('name'): (e, kind) for e, kind in pending}

        def resolve(name, seen):
            if name in frames:
                return frames[name]
            if name in seen or name not in declared:
                raise PartError(f'{where}: relative_to {name!r} names no link or frame of it')
            found, kind = declared[name]
            pose = found.find('pose')
            base = pose.get('relative_to', '') if pose is not None else ''
            if kind == 'frame' and not base:
                base = found.get('attached_to', '')
            frames[name] = resolve(base, seen | {name}) @ pose_matrix(
                pose, f'{where} <{kind} name="{name}">')
            return frames[name]

        links = []
        for link_element, kind in pending:
            if kind != 'link':
                continue
            link_name = link_element.get('name', '')
            link = Link(name=prefix + link_name, pose=resolve(link_name, set()))
            self._inertial(link_element, link, f'{where} link {link_name!r}')
            for tag, shapes in (('collision', link.collisions), ('visual', link.visuals)):
                for index, shape_element in enumerate(link_element.findall(tag)):
                    shape_name = shape_element.get('name', f'{tag}_{index}')
                    try:
                        shape = self._shape(shape_element, source,
                                            f'{where} link {link_name!r} {tag} '
                                            f'{shape_name!r}', tag)
                    except PartError as exc:
                        self.messages.append(f'{exc}: skipped')
                        link.missing_visuals += tag == 'visual'
                        continue
                    if shape is not None:
                        shape.name = shape_name
                        shapes.append(shape)
            links.append(link)
        for nested in element.findall('model'):
            nested_name = nested.get('name', '')
            T = pose_matrix(nested.find('pose'), f'{where} model {nested_name!r}')
            for link in self._links(nested, source, f'{where}::{nested_name}',
                                    f'{prefix}{nested_name}::'):
                link.pose = T @ link.pose
                links.append(link)
        for nested in element.findall('include'):  # a nested model from a file
            model = self.include(nested, source)
            for link in model.links:
                link.name = f'{prefix}{model.name}::{link.name}'
                link.pose = model.pose @ link.pose
                links.append(link)
        return links

    @staticmethod
    def _inertial(element, link, where):
        inertial = element.find('inertial')
        if inertial is None:
            return
        link.mass = child_number(inertial, 'mass', 1.0, f'{where} <inertial>')
        if not link.mass > 0:
            raise PartError(f'{where} <inertial><mass> must be > 0 kg, found {link.mass:g}')
        link.inertial_pose = pose_matrix(inertial.find('pose'), f'{where} <inertial>')
        matrix = inertial.find('inertia')
        if matrix is not None:
            defaults = (1.0, 1.0, 1.0, 0.0, 0.0, 0.0)
            link.inertia = tuple(
                child_number(matrix, tag, default, f'{where} <inertia>')
                for tag, default in zip(('ixx', 'iyy', 'izz', 'ixy', 'ixz', 'iyz'), defaults))
            xx, yy, zz, xy, xz, yz = link.inertia
            for problem, expected, found in inertia_problems(
                    [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])[:1]:  # MuJoCo refuses it
                raise PartError(f'{where} <inertia>: {problem} (expected {expected}, found '
                                f'{found})')

    def _shape(self, element, source, where, tag):
        kind, size, path = read_geometry(element.find('geometry'), where,
                                         lambda uri: self.resolve(uri, source))
        pose = pose_matrix(element.find('pose'), where)
        shape = Shape(name='', kind=kind, size=tuple(size), pose=pose, path=path)
        if tag == 'visual':
            material = element.find('material')
            if material is not None:
                colour = child_text(material, 'diffuse') or child_text(material, 'ambient')
                if colour:
                    count = len(colour.split()) if len(colour.split()) in (3, 4) else 4
                    values = sdf_floats(colour, count, f'{where} <material>')
                    shape.rgba = tuple(values) + ((1.0,) if len(values) == 3 else ())
        else:
            ode = element.find('surface/friction/ode')
            if ode is not None:
                values = [child_number(ode, t, None, f'{where} <ode>') for t in ('mu', 'mu2')]
                values = [v for v in values if v is not None]
                if values:
                    shape.friction = max(0.0, min(values))
        return shape


def read_world(path, model_paths=()):
    """
    Read an SDF world file.

    :param path: the ``.sdf``/``.world`` file.
    :param model_paths: folders searched for ``model://`` after the environment's
        (:data:`RESOURCE_PATH_VARIABLES`).
    :returns: a :class:`World`; problems with parts of it are lines in ``messages``.
    :raises WorldError: one line naming the file when it cannot be read at all (missing,
        malformed XML with its line, not an SDF world, a URDF, bad ``<physics>``).
    """
    reader = _Reader(str(path), model_paths)
    try:
        root = _parse_file(str(path), 'the world')
    except PartError as exc:
        raise WorldError(str(exc)) from None
    return reader.world(root)


def load_world(value):
    """
    Find (:func:`find_world`) and read (:func:`read_world`) a world, with the shipped models.

    :raises WorldError: one line (see both).
    """
    return read_world(find_world(value), [os.path.join(shipped_worlds_folder(), 'models')])
