# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""SDF worlds: the reader (core/gazebo/sdf_world.py) and the MuJoCo world built from it."""

import math
import os

from amr_description.core.gazebo.sdf_resources import fuel_model_name
from amr_description.core.gazebo.sdf_world import load_world
from amr_description.core.gazebo.sdf_world import read_world
from amr_description.core.gazebo.sdf_world import WorldError
import mujoco
import numpy as np
import pytest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
DATA = os.path.join(ROOT, 'test', 'data', 'worlds')
COURSE = os.path.join(DATA, 'course_world.sdf')
CASTER_BOT = os.path.join(ROOT, 'test', 'data', 'gz_diff_drive', 'robot.urdf.xacro')
# ground (0), world visuals (2: a collision with the same visual is drawn as one) and
# collisions (3)
GEOMS = np.array([1, 0, 1, 1, 0, 0], dtype=np.uint8)


@pytest.fixture
def models_path(monkeypatch):
    monkeypatch.setenv('GZ_SIM_RESOURCE_PATH', os.path.join(DATA, 'models'))


def _ray(world, start, direction):
    """Return the distance (m) from ``start`` along ``direction`` to the first collision geom."""
    geom = np.array([-1], dtype=np.int32)
    distance = mujoco.mj_ray(world.model, world.data, np.asarray(start, dtype=float),
                             np.asarray(direction, dtype=float), GEOMS, 1, -1, geom)
    return distance, world.model.geom(geom[0]).name


def test_a_course_world_loads_its_primitives_and_one_line_per_missing_model(models_path):
    world = read_world(COURSE)
    assert (world.name, world.physics_step, world.real_time_factor) == ('course', 0.002, 1.0)
    assert [m.name for m in world.models] == ['ground_plane', 'box', 'cylinder', 'sphere',
                                              'capsule', 'ellipsoid', 'crate_a']
    assert world.messages == [
        'model://cardboard_box not found in GZ_SIM_RESOURCE_PATH ('
        f'{os.path.join(DATA, "models")}): the world loads without it',
        'https://fuel.gazebosim.org/1.0/OpenRobotics/models/Warehouse: Fuel models are not '
        'downloaded here (put the model in a folder of GZ_SIM_RESOURCE_PATH): the world '
        'loads without it']
    assert world.not_simulated == ['gui', 'light', 'plugin', 'scene']
    assert world.gravity == (0.0, 0.0, -9.8)  # SDF's default
    crate = world.model('crate_a')  # <include><name>, model.config's newest <sdf>
    assert crate.static and crate.links[0].visuals[0].kind == 'mesh'
    assert crate.links[0].visuals[0].path.endswith(os.path.join('crate', 'meshes', 'cube.stl'))


def test_every_geometry_is_where_the_closed_form_puts_it(models_path):
    from amr_description.sim.world import World
    description = read_world(COURSE)
    world = World(description.physics_step, description)
    assert world.name == 'course' and world.physics_step == 0.002
    assert list(world.model.opt.gravity) == [0.0, 0.0, -9.8]
    cases = [
        ((0, 0, 0.5), (1, 0, 0), 2.5, 'box::box_link::box_collision'),   # face at x = 3 - 0.5
        # the cylinder's pose comes from the saved <state>: y -4, not -3
        ((0, 0, 0.5), (0, -1, 0), 3.5, 'cylinder::cylinder_link::c'),
        ((0, 0, 0.5), (0, 1, 0), 2.5, 'sphere::l::c'),
        # capsule: relative_to the sphere (0, 3, 0.5) + (0, 2, 0); radius 0.2, half 0.3
        ((1, 5, 0.5), (-1, 0, 0), 0.8, 'capsule::l::c'),
        ((0, 5, 2.0), (0, 0, -1), 2.0 - (0.5 + 0.3 + 0.2), 'capsule::l::c'),
        # ellipsoid radii (0.2, 0.4, 0.6) turned 90 deg about z by its <frame>
        ((0, 0, 1), (-1, 0, 0), 3.0 - 0.4, 'ellipsoid::l::c'),
        ((-3, -2, 1), (0, 1, 0), 2.0 - 0.2, 'ellipsoid::l::c'),
        ((-3, 0, 3), (0, 0, -1), 2.0 - 0.6, 'ellipsoid::l::c'),
        ((6, 6, 2), (0, 0, -1), 1.5, 'crate_a::body::'),      # include pose + link
        ((10, 10, 1), (0, 0, -1), 1.0, 'ground_plane'),
    ]
    for start, direction, expected, name in cases:
        distance, hit = _ray(world, start, direction)
        assert hit.startswith(name) and distance == pytest.approx(expected, abs=1e-9), \
            (start, direction, hit, distance)
    # the ground of gz-sim's empty.sdf: mu 100/50 is rougher than MuJoCo's default 1
    ground = world.model.geom('ground_plane')
    assert list(ground.friction) == [1.0, 0.005, 0.0001] and ground.priority == 0
    # the box is free (it has an inertial): 1 kg, and it falls onto the ground
    body = world.model.body('box::box_link')
    assert body.mass[0] == pytest.approx(1.0) and world.model.body_jntnum[body.id] == 1
    # its visual is its collision box: one geom, drawn in the visual's red
    box = world.model.geom('box::box_link::box_collision')
    assert box.group[0] == 2 and list(box.rgba) == [1, 0, 0, 1] and box.contype[0] == 1
    assert [world.model.geom(i).name for i in range(world.model.ngeom)].count(
        'box::box_link::visual::box_visual') == 0


def test_the_shipped_empty_world_is_the_empty_world():
    from amr_description.core.description.files import read_description
    from amr_description.sim.urdf_to_mjcf import urdf_to_spec
    from amr_description.sim.world import World
    urdf = read_description(os.path.join(ROOT, 'urdf', 'amr.urdf'))
    description = load_world('empty')
    assert (description.name, description.physics_step, description.gravity) == \
        ('empty', 0.001, (0.0, 0.0, -9.81))
    qpos = []
    for world in (World(0.001), World(0.001, description)):
        assert world.name == 'empty'
        world.spawn(urdf_to_spec(urdf, name='amr', pose=(0, 0, 0.2, 0, 0, 0)), 'amr')
        world.data.ctrl[:] = 3.0
        world.step(1000)
        qpos.append(world.data.qpos.copy())
    assert np.array_equal(qpos[0], qpos[1])


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def _world(body, version='1.9'):
    return (f'<?xml version="1.0"?>\n<sdf version="{version}"><world name="w">{body}'
            '</world></sdf>')


def _box_model(name, size='1 1 1', extra=''):
    return (f'<model name="{name}"><static>true</static><link name="l"><collision name="c">'
            f'<geometry><box><size>{size}</size></box></geometry></collision></link>{extra}'
            '</model>')


def test_bad_parts_are_one_line_each_and_the_rest_loads(tmp_path, models_path):
    body = (_box_model('flat', '1 0 1') + _box_model('good') +
            '<model name="arm"><link name="a"/><link name="b"/><joint name="j" type="revolute">'
            '<parent>a</parent><child>b</child></joint></model>'
            '<model name="m"><static>true</static><link name="l"><visual name="v"><geometry>'
            '<mesh><uri>meshes/none.stl</uri></mesh></geometry></visual></link></model>'
            '<include><uri>model://loop</uri></include>'
            '<model name="cone"><static>true</static><link name="l"><collision name="c">'
            '<geometry><cone><radius>1</radius><length>1</length></cone></geometry>'
            '</collision></link></model>')
    path = _write(tmp_path, 'w.sdf', _world(body, version='1.12'))
    world = read_world(path)
    assert [m.name for m in world.models] == ['flat', 'good', 'm', 'cone']
    messages = world.messages
    assert messages[0] == f'{path}: <sdf version="1.12"> is newer than 1.11; read as 1.11'
    assert messages[1] == ("model 'flat' link 'l' collision 'c': <box> sizes must be > 0 and "
                           'at most 100000, found 1 0 1: skipped')
    assert messages[2] == ("model 'arm' has joints: articulated SDF models are not simulated "
                           'yet: the world loads without it')
    assert messages[3].startswith("model 'm' link 'l' visual 'v': mesh 'meshes/none.stl' not "
                                  'found (') and messages[3].endswith('none.stl): skipped')
    assert messages[4].startswith('model://loop: an include cycle (') and \
        messages[4].endswith(': the world loads without it')
    assert messages[5] == ("model 'cone' link 'l' collision 'c': <cone> geometry is not "
                           'simulated: skipped')
    assert len(messages) == 6 and all('\n' not in m for m in messages)


@pytest.mark.parametrize('text, message', [
    ('<sdf version="1.9"><world name="w"><model name="x"></world></sdf>',
     ':1: malformed XML (Opening and ending tag mismatch: model line 1 and world, column 60)'),
    ('<robot name="r"><link name="base"/></robot>',
     ': this is a URDF (<robot>), not an SDF world; spawn it with create -file'),
    ('<sdf version="1.9"><model name="m"/></sdf>', ': no <world> in this SDF file'),
    (_world('<physics name="p"><max_step_size>0</max_step_size></physics>'),
     ': <physics><max_step_size> must be > 0 s, found 0'),
    (_world('<gravity>0 0</gravity>'),
     ": <world><gravity>: expected 3 finite numbers, found '0 0'"),
])
def test_a_world_that_cannot_be_read_is_one_line_naming_the_file(tmp_path, text, message):
    path = _write(tmp_path, 'bad.sdf', text)
    with pytest.raises(WorldError) as refused:
        read_world(path)
    assert str(refused.value) == path + message


def test_a_world_name_or_file_that_does_not_exist():
    with pytest.raises(WorldError, match=r"^world 'nowhere': no such file and not a shipped "
                       r'world \(arena, empty, warehouse\)$'):
        load_world('nowhere')
    with pytest.raises(WorldError, match=r"^world '/no/such.sdf': no such file$"):
        load_world('/no/such.sdf')


def test_poses_in_degrees_and_quaternions(tmp_path):
    body = ('<model name="a"><static>true</static><pose degrees="true">1 0 0 0 0 90</pose>'
            '<link name="l"/></model>'
            '<model name="b"><static>true</static>'
            '<pose rotation_format="quat_xyzw">0 1 0 0 0 0.7071067811865476 '
            '0.7071067811865476</pose><link name="l"/></model>')
    world = read_world(_write(tmp_path, 'w.sdf', _world(body)))
    yaw = [math.atan2(m.pose[1, 0], m.pose[0, 0]) for m in world.models]
    assert yaw == [pytest.approx(math.pi / 2), pytest.approx(math.pi / 2)]


def _quat_yaw(yaw):
    return [0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)]


def _drive(sim, entity, linear, seconds):
    from geometry_msgs.msg import Twist
    diff_drive = entity.gz_systems.systems[0]
    twist = Twist()
    twist.linear.x = float(linear)
    diff_drive.on_command(twist)
    start = sim.step_count
    while sim.step_count - start < int(round(seconds / sim.physics_step)):
        sim.run_cycle()


def test_a_robot_driven_into_a_shelf_stops_and_a_pushed_box_moves():
    from amr_description.core.description.files import read_description
    from amr_description.sim.simulation import Simulation
    sim = Simulation(0.001, 0.0, world=load_world('warehouse'))
    urdf = read_description(CASTER_BOT)
    # facing +y at the origin: shelf_0_0 (x -2.5 .. 0.5) starts at y = 1 - 0.25 = 0.75
    wall = sim.spawn(urdf, name='wall', pose=[0, 0, 0.02] + _quat_yaw(math.pi / 2))
    _drive(sim, wall, 1.0, 4.0)  # 1 m/s (the robot's DiffDrive limits it to 1 m/s^2)
    y = sim.world.ground_truth('wall')[0][1]
    _drive(sim, wall, 1.0, 1.0)
    later = sim.world.ground_truth('wall')[0][1]
    # the front of the base (0.2 m ahead of its centre) rests against the shelf's face
    print(f'robot against the shelf: front at y = {y + 0.2:.4f} m (face at 0.75 m), '
          f'moved {later - y:.4f} m in the last second at 1 m/s')
    assert 0.5 < y + 0.2 < 0.78 and abs(later - y) < 0.01
    # box_0 (2 kg, 0.4 m) at (1, -1.2): a robot at (1, -0.4) facing -y pushes it
    pusher = sim.spawn(urdf, name='pusher', namespace='pusher',
                       pose=[1.0, -0.4, 0.02] + _quat_yaw(-math.pi / 2))
    box = sim.world.model.joint('box_0::link')
    start = sim.world.data.qpos[box.qposadr[0]:box.qposadr[0] + 3].copy()
    assert start == pytest.approx([1.0, -1.2, 0.2], abs=1e-3)
    _drive(sim, pusher, 0.3, 4.0)
    end = sim.world.data.qpos[box.qposadr[0]:box.qposadr[0] + 3].copy()
    print(f'box pushed from y {start[1]:.3f} to {end[1]:.3f} m')
    assert end[1] < start[1] - 0.3 and abs(end[0] - 1.0) < 0.2
    # the boxes nobody touched are asleep (out of the solver); the robots never sleep
    data, model = sim.world.data, sim.world.model
    assert not data.body_awake[model.body('box_2::link').id]
    assert data.body_awake[model.body('pusher/base_footprint').id]
    assert data.body_awake[model.body('wall/base_footprint').id]  # at rest against the shelf


def test_a_robot_spawned_into_a_pillar_is_one_warning_naming_it(caplog):
    from amr_description.core.description.files import read_description
    from amr_description.sim.simulation import Simulation
    sim = Simulation(0.001, 0.0, world=load_world('arena'))
    caplog.set_level('WARNING')
    sim.spawn(read_description(CASTER_BOT), pose=[1.0, 0.0, 0.05, 0, 0, 0, 1])
    lines = [r.getMessage() for r in caplog.records if 'overlapping' in r.getMessage()]
    assert lines == ["robot 'caster_bot' is spawned overlapping world model 'pillar_6'"]
    assert 'caster_bot' in sim.entities


def test_a_link_whose_visual_meshes_are_missing_shows_its_collision(tmp_path, models_path):
    from amr_description.core.gazebo.sdf_world import collapse_repeats
    from amr_description.sim.urdf_to_mjcf import COLLISION_GROUP
    from amr_description.sim.urdf_to_mjcf import VISUAL_GROUP
    from amr_description.sim.world import World
    visual = ('<visual name="v"><geometry><mesh><uri>model://brick/meshes/b.dae</uri></mesh>'
              '</geometry></visual>')
    body = (_box_model('wall_a', extra='').replace('</collision>', '</collision>' + visual) +
            _box_model('wall_b').replace('</collision>', '</collision>' + visual) +
            _box_model('hidden'))  # a collision alone stays invisible, as in Gazebo
    description = read_world(_write(tmp_path, 'w.sdf', _world(body)))
    assert collapse_repeats(description.messages) == [
        'model://brick/meshes/b.dae not found in GZ_SIM_RESOURCE_PATH '
        f'({os.path.join(DATA, "models")}): skipped (2 times)']
    model = World(description.physics_step, description).model
    assert model.geom('wall_a::l::c').group == VISUAL_GROUP  # drawn, and still collides
    assert model.geom('wall_a::l::c').contype == 1
    assert model.geom('hidden::l::c').group == COLLISION_GROUP


def test_shape_bounds_are_the_posed_corners_of_the_primitive():
    from amr_description.core.gazebo.sdf_elements import Shape
    from amr_description.core.gazebo.sdf_elements import shape_bounds
    turn = np.eye(4)
    turn[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]  # 90 deg about z
    turn[:3, 3] = [1.0, 2.0, 0.5]
    box = Shape('b', 'box', (4.0, 0.2, 1.0), np.eye(4))
    low, high = shape_bounds(box, turn)  # the 4 m side now lies along y
    np.testing.assert_allclose(low, [0.9, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(high, [1.1, 4.0, 1.0], atol=1e-12)
    lying = np.eye(4)
    lying[:3, :3] = [[1, 0, 0], [0, 0, -1], [0, 1, 0]]  # axis z onto y
    capsule = Shape('c', 'capsule', (0.1, 1.0), lying)
    low, high = shape_bounds(capsule, np.eye(4))
    np.testing.assert_allclose(high - low, [0.2, 1.2, 0.2], atol=1e-12)
    low, high = shape_bounds(Shape('s', 'sphere', (0.3,), np.eye(4)), turn)
    np.testing.assert_allclose(low, [0.7, 1.7, 0.2])
    assert shape_bounds(Shape('p', 'plane', (0, 0, 1, 10, 10), np.eye(4)), np.eye(4)) is None
    assert shape_bounds(Shape('m', 'mesh', (1, 1, 1), np.eye(4), 'x.stl'), np.eye(4)) is None


def test_the_walls_around_a_world_get_static_bodies_of_their_own(tmp_path):
    from amr_description.sim.sdf_to_mjcf import large_static_links
    from amr_description.sim.world import World
    walls = {f'walls::{side}' for side in ('north', 'south', 'east', 'west')}
    assert large_static_links(load_world('warehouse')) == walls  # 12.4 and 10 m of 12.4 x 10.2
    assert large_static_links(load_world('arena')) == walls  # 4.6 and 4.9 m of 4.6 x 5.1
    model = World(0.001, load_world('warehouse')).model
    north = model.geom('walls::north::collision_box')
    assert model.body(north.bodyid[0]).name == 'walls::north'
    assert model.body_weldid[north.bodyid[0]] == 0  # static: welded to the world
    shelf = model.geom('shelf_0_0::link::collision_plinth')
    assert shelf.bodyid[0] == 0 and model.geom('ground_plane').bodyid[0] == \
        model.body('ground_plane').id
    # a world without a ground has neither the ground's geom nor its body
    bare = World(0.001, read_world(_write(tmp_path, 'bare.sdf', _world(_box_model('b'))))).model
    with pytest.raises(KeyError):
        bare.body('ground_plane')
    with pytest.raises(KeyError):
        bare.geom('ground_plane')
    assert [bare.body(b).name for b in range(bare.nbody)] == ['world', 'b::l']  # all of it


def test_a_robot_with_a_ground_contact_pair_meets_a_shelf_with_its_wheels():
    """urdf/amr.urdf's wheels (explicit ground pairs) reach 0.3 m ahead, its base 0.25 m."""
    from amr_description.core.description.files import read_description
    from amr_description.sim.urdf_to_mjcf import urdf_to_spec
    from amr_description.sim.world import World
    world = World(0.001, load_world('warehouse'))
    urdf = read_description(os.path.join(ROOT, 'urdf', 'amr.urdf'))
    # facing +y at the origin: shelf_0_0's plinth (0.3 m high) has its face at y = 0.75
    world.spawn(urdf_to_spec(urdf, name='amr', pose=(0, 0, 0.0, 0, 0, math.pi / 2)), 'amr')
    model, data = world.model, world.data
    data.ctrl[:] = 5.0  # every wheel's PI velocity servo (both actuators) at 5 rad/s: 0.5 m/s
    touching = set()
    while not touching and world.time < 3.0:
        world.step(1)
        for contact in data.contact[:data.ncon]:
            names = {model.geom(contact.geom1).name, model.geom(contact.geom2).name}
            if 'shelf_0_0::link::collision_plinth' in names:
                touching |= {n.split('/')[1] for n in names if n.startswith('amr/')}
    y = world.ground_truth('amr')[0][1]
    print(f'first touch of the plinth with its centre at y = {y:.4f} m: {sorted(touching)}')
    assert touching == {'wheel_front_left', 'wheel_front_right'}
    assert y == pytest.approx(0.75 - 0.3, abs=0.005)


@pytest.mark.parametrize('name, robots', [('arena', 4), ('warehouse', 16)])
def test_the_fleet_grid_keeps_clear_of_every_world_model_wheels_included(name, robots):
    from amr_description.core.description.files import read_description
    from amr_description.launch.stacks import fleet_grid
    from amr_description.sim.urdf_to_mjcf import urdf_to_spec
    from amr_description.sim.world import World
    world = World(0.001, load_world(name))
    urdf = read_description(os.path.join(ROOT, 'urdf', 'amr.urdf'))
    for index, (x, y) in enumerate(fleet_grid(robots, 2.0)):  # the fleet stack's grid
        world.spawn(urdf_to_spec(urdf, name=f'r{index}', pose=(x, y, 0.0, 0, 0, 0)), f'r{index}')
    assert {r: world.overlapping_models(r) for r in world.robots} == \
        {r: [] for r in world.robots}


def test_gazebos_ground_plane_and_sun_are_shipped_and_fuels_names_find_them(tmp_path):
    world_file = tmp_path / 'everyday.sdf'
    world_file.write_text(
        '<sdf version="1.9"><world name="everyday">'
        '<include><uri>model://sun</uri></include>'
        '<include><uri>model://ground_plane</uri></include>'
        '<include><name>fuel_ground</name><pose>0 0 -1 0 0 0</pose>'
        '<uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Ground%20Plane/1</uri>'
        '</include>'
        '<include><uri>https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun</uri></include>'
        '</world></sdf>')
    world = load_world(str(world_file))
    assert world.messages == []
    assert [m.name for m in world.models] == ['ground_plane', 'fuel_ground']
    ground = world.model('ground_plane')
    plane = ground.links[0].collisions[0]
    assert ground.static and (plane.kind, plane.size) == ('plane', (0, 0, 1, 100, 100))
    assert world.model('fuel_ground').pose[2, 3] == -1.0
    assert world.not_simulated == ['light']  # the included suns


def test_fuel_model_names_are_read_from_the_uri():
    assert fuel_model_name('https://fuel.gazebosim.org/1.0/OpenRobotics/models/Sun') == 'Sun'
    assert fuel_model_name(
        'https://fuel.ignitionrobotics.org/1.0/openrobotics/models/ground plane/2') == \
        'ground plane'
    assert fuel_model_name('model://sun') is None
    assert fuel_model_name('https://example.com/a.sdf') is None
