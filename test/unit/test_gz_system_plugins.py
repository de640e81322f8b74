# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""gz-sim systems and <gazebo reference> friction: parsing (closed forms) and the engine."""

import os

from amr_description.core.gazebo import systems as gs
from amr_description.core.gazebo.tags import apply_surface_tags
from amr_description.core.gazebo.tags import parse_reference_tags
from amr_description.core.gazebo.tags import surface_friction
from lxml import etree
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
XACRO = os.path.join(ROOT, 'test', 'data', 'gz_diff_drive', 'robot.urdf.xacro')
JOINTS = ('left_wheel_joint', 'right_wheel_joint', 'l2', 'r2')


def _robot(plugins, references=''):
    return etree.fromstring(f'<robot name="r"><gazebo>{plugins}</gazebo>{references}</robot>')


def _diff_drive(body, filename='gz-sim-diff-drive-system', name='gz::sim::systems::DiffDrive'):
    return f'<plugin filename="{filename}" name="{name}">{body}</plugin>'


WHEELS = '<left_joint>left_wheel_joint</left_joint><right_joint>right_wheel_joint</right_joint>'


@pytest.mark.parametrize('filename, name', [
    ('gz-sim-diff-drive-system', 'gz::sim::systems::DiffDrive'),
    ('libignition-gazebo-diff-drive-system.so', 'ignition::gazebo::systems::DiffDrive'),
    ('ignition-gazebo6-diff-drive-system', ''),
    ('', 'ignition::gazebo::systems::DiffDrive'),
])
def test_every_spelling_of_diff_drive_is_diff_drive(filename, name):
    systems = gs.parse_gazebo_systems(_robot(_diff_drive(WHEELS, filename, name)), JOINTS)
    assert len(systems.diff_drives) == 1 and not systems.unknown


def test_diff_drive_defaults_are_gz_sim_8s():
    systems = gs.parse_gazebo_systems(_robot(_diff_drive(WHEELS)), JOINTS)
    gs.resolve_defaults(systems, 'bot', 'base_footprint', 'empty')
    params = systems.diff_drives[0]
    assert (params.wheel_separation, params.wheel_radius, params.odom_publish_frequency) == \
        (1.0, 0.2, 50.0)
    assert (params.topic, params.odom_topic, params.tf_topic) == \
        ('/model/bot/cmd_vel', '/model/bot/odometry', '/model/bot/tf')
    assert (params.frame_id, params.child_frame_id) == ('bot/odom', 'bot/base_footprint')
    assert params.linear == {} and params.angular == {}


def test_diff_drive_elements_repeat_and_limits_override():
    body = ('<left_joint>left_wheel_joint</left_joint><left_joint>l2</left_joint>'
            '<right_joint>right_wheel_joint</right_joint><right_joint>r2</right_joint>'
            '<wheel_separation>0.35</wheel_separation><wheel_radius value="0.1"/>'
            '<topic>cmd_vel</topic><odom_topic>/odom</odom_topic>'
            '<max_velocity>2</max_velocity><max_angular_velocity>1.5</max_angular_velocity>'
            '<min_acceleration>-3</min_acceleration>')
    systems = gs.parse_gazebo_systems(_robot(_diff_drive(body)), JOINTS)
    params = systems.diff_drives[0]
    assert params.left_joints == ['left_wheel_joint', 'l2']
    assert params.right_joints == ['right_wheel_joint', 'r2']
    assert (params.wheel_separation, params.wheel_radius) == (0.35, 0.1)
    assert (params.topic, params.odom_topic) == ('/cmd_vel', '/odom')  # relative: leading /
    assert params.linear == {'max_velocity': 2.0, 'min_acceleration': -3.0}
    assert params.angular == {'max_velocity': 1.5, 'min_acceleration': -3.0}
    assert systems.driven_joints() == ['left_wheel_joint', 'l2', 'right_wheel_joint', 'r2']
    hardware = systems.hardware()[0]
    assert [j.command_interface_names() for j in hardware.joints] == [['velocity']] * 4


@pytest.mark.parametrize('body, message', [
    ('<right_joint>right_wheel_joint</right_joint>', '<left_joint> is required'),
    (WHEELS.replace('left_wheel_joint', 'nope'), "joint 'nope' is not a moving joint"),
    (WHEELS + '<wheel_radius>-0.1</wheel_radius>', '<wheel_radius>: expected a number > 0'),
    (WHEELS + '<max_velocity>fast</max_velocity>', '<max_velocity>: expected a number'),
])
def test_bad_diff_drive_is_one_line_naming_the_element(body, message):
    with pytest.raises(ValueError, match=message) as error:
        gs.parse_gazebo_systems(_robot(_diff_drive(body)), JOINTS)
    assert '<gazebo><plugin name="gz::sim::systems::DiffDrive">' in str(error.value)
    assert '\n' not in str(error.value)


def test_other_systems_defaults_and_unknown_ones():
    plugins = ('<plugin filename="gz-sim-joint-state-publisher-system" '
               'name="gz::sim::systems::JointStatePublisher"><joint_name>l2</joint_name>'
               '</plugin><plugin filename="libignition-gazebo-odometry-publisher-system.so" '
               'name="ignition::gazebo::systems::OdometryPublisher"><dimensions>3</dimensions>'
               '</plugin><plugin filename="gz-sim-sensors-system" '
               'name="gz::sim::systems::Sensors"/>'
               '<plugin filename="gz-sim-pose-publisher-system" '
               'name="gz::sim::systems::PosePublisher"/>'
               '<plugin filename="libgz_ros2_control-system.so" '
               'name="gz_ros2_control::GazeboSimROS2ControlPlugin"/>')
    systems = gs.resolve_defaults(gs.parse_gazebo_systems(_robot(plugins), JOINTS), 'bot',
                                  'base_footprint', 'empty')
    assert systems.joint_state_publishers[0].joint_names == ['l2']
    assert systems.joint_state_publishers[0].topic == '/world/empty/model/bot/joint_state'
    odometry = systems.odometry_publishers[0]
    assert (odometry.odom_frame, odometry.robot_base_frame, odometry.dimensions) == \
        ('bot/odom', 'bot/base_footprint', 3)
    assert (odometry.odom_topic, odometry.odom_covariance_topic, odometry.tf_topic) == \
        ('/model/bot/odometry', '/model/bot/odometry_with_covariance', '/model/bot/pose')
    # gz_ros2_control is not a system; the Sensors system is not needed (docs/sensors.md)
    assert systems.unknown == ['gz::sim::systems::PosePublisher']


def test_friction_tags_value_or_text_smaller_wins_and_mujoco_block_wins():
    from amr_description.core.description.mujoco_block import MujocoConfig
    assert surface_friction({'mu1': '0.8', 'mu2': '0.3'}, 'x') == 0.3
    assert surface_friction({'mu2': '0.5'}, 'x') == 0.5
    assert surface_friction({'kp': '1e6'}, 'x') is None
    with pytest.raises(ValueError, match=r'x<mu1>: expected a number >= 0'):
        surface_friction({'mu1': '-1'}, 'x')
    root = etree.fromstring('<robot name="r"><gazebo reference="caster"><mu1 value="0.01"/>'
                            '<mu2>0.02</mu2></gazebo><gazebo reference="caster"><mu2>0.005'
                            '</mu2></gazebo><gazebo reference="wheel"><mu1>0.9</mu1></gazebo>'
                            '</robot>')
    tags = parse_reference_tags(root)
    assert tags == {'caster': {'mu1': '0.01', 'mu2': '0.005'}, 'wheel': {'mu1': '0.9'}}

    class _Model:
        links = {'caster': None, 'wheel': None}
    config = MujocoConfig()
    config.link_contact['wheel'] = {'friction': (1.2,)}  # from <mujoco>: kept
    apply_surface_tags(config, tags, _Model())
    assert config.link_contact['caster']['friction'][0] == 0.005
    assert config.link_contact['caster']['priority'] == 1
    assert config.link_contact['wheel'] == {'friction': (1.2,)}


def test_gz_limiter_is_gz_maths_speed_limiter():
    from amr_description.sim.systems.diff_drive import gz_limiter
    limiter = gz_limiter({'max_acceleration': 1.0, 'min_acceleration': -2.0,
                          'max_velocity': 0.5}, 'x')
    assert limiter.limit(1.0, 0.0, 0.0, 0.1) == pytest.approx(0.1)   # +1 m/s^2
    assert limiter.limit(-1.0, 0.0, 0.0, 0.1) == pytest.approx(-0.2)  # -2 m/s^2, any sign
    assert limiter.limit(-1.0, -0.4, -0.3, 0.1) == pytest.approx(-0.6)
    assert limiter.limit(1.0, 0.45, 0.4, 0.1) == pytest.approx(0.5)   # velocity bound
    assert gz_limiter({}, 'x') is None
    with pytest.raises(ValueError, match='^x: max_velocity must be >= 0'):
        gz_limiter({'max_velocity': -1.0}, 'x')


@pytest.fixture(scope='module')
def caster_bot():
    from amr_description.core.description.files import read_description
    from amr_description.sim.simulation import Simulation
    sim = Simulation(0.001, 0.0)
    entity = sim.spawn(read_description(XACRO, {'cmd_topic': 'base/cmd_vel'}))
    return sim, entity


def _run(sim, seconds):
    start = sim.step_count
    while sim.step_count - start < int(round(seconds / sim.physics_step)):
        sim.run_cycle()


def test_engine_runs_the_systems_of_a_spawned_robot(caster_bot):
    from geometry_msgs.msg import Twist
    sim, entity = caster_bot
    diff_drive, joint_states, odometry = entity.gz_systems.systems
    assert [i.topic for i in entity.inputs] == ['/base/cmd_vel', '/model/caster_bot/enable']
    topics = {s.topic: s for s in entity.sensors}
    assert {'/odom', '/tf', '/joint_states', '/ground_truth'} <= set(topics)
    _run(sim, 0.5)
    twist = Twist()
    twist.linear.x, twist.angular.z = 0.2, 0.5
    diff_drive.on_command(twist)
    _run(sim, 0.02)
    # the first update limits the step to 1 m/s^2 and 2 rad/s^2 over 10 ms: closed form
    left, right = diff_drive.wheel_speeds(0.2, 0.5)
    assert (left, right) == pytest.approx(((0.2 - 0.5 * 0.175) / 0.1, (0.2 + 0.5 * 0.175) / 0.1))
    _run(sim, 2.0)
    message = topics['/joint_states'].measure(sim.world, sim.time)
    assert message.name == ['left_wheel_joint', 'right_wheel_joint']
    assert message.velocity == pytest.approx([left, right], rel=0.02)
    # OdometryPublisher (2-D) is the ground truth in its frames
    ground = topics['/ground_truth'].measure(sim.world, sim.time)
    position, quaternion, linear, angular = sim.world.ground_truth(entity.name)
    assert ground.header.frame_id == 'world'
    assert ground.child_frame_id == 'caster_bot/base_footprint'
    assert ground.pose.pose.position.x == pytest.approx(position[0])
    assert ground.pose.pose.position.z == 0.0
    assert ground.twist.twist.angular.z == pytest.approx(angular[2])
    # wheel odometry follows the ground truth, started from the spawn pose (the origin)
    wheel = topics['/odom'].measure(sim.world, sim.time)
    assert wheel.pose.pose.position.x == pytest.approx(position[0], abs=0.01)
    assert wheel.pose.pose.position.y == pytest.approx(position[1], abs=0.01)
    assert wheel.twist.twist.angular.z == pytest.approx(0.5, rel=0.03)
    from std_msgs.msg import Bool
    diff_drive.on_enable(Bool(data=False))
    diff_drive.on_command(twist)  # ignored while disabled
    _run(sim, 1.5)
    assert abs(joint_states.message(sim.world, sim.time).velocity[0]) < 0.05
    sim.reset()
    assert diff_drive.odometry.x == 0.0 and diff_drive._target == (0.0, 0.0)
    assert odometry.rate == 50.0


def test_a_sensor_is_measured_at_its_own_rate():
    from amr_description.sim.simulation import Simulation
    sim = Simulation(0.001, 0.0, sensor_settings={'ground_truth_rate': 40.0})
    sim.spawn(open(os.path.join(ROOT, 'urdf', 'amr.urdf')).read())
    instants = []
    sim.after_cycle.append(lambda t: instants.append(round(t * 1000)))
    _run(sim, 0.2)
    # the 100 Hz cycle also stops every 25 ms (before: only where both met, every 50 ms)
    assert {25, 75, 125, 175} <= set(instants)
    assert sim._periods == (10, 25)


def test_collada_meshes_are_read_and_a_missing_one_is_one_warning(tmp_path, caplog):
    import mujoco
    import trimesh
    from amr_description.sim.urdf_to_mjcf import urdf_to_spec
    dae = tmp_path / 'body.dae'
    dae.write_bytes(trimesh.exchange.dae.export_collada(
        trimesh.creation.box(extents=(0.4, 0.3, 0.1))))
    urdf = (f'<robot name="m"><link name="a"><collision><geometry><mesh filename="{dae}"/>'
            '</geometry></collision><visual><geometry><mesh filename="package://'
            'amr_description/meshes/nope.dae"/></geometry></visual><inertial><mass value="1"/>'
            '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>'
            '</robot>')
    model = urdf_to_spec(urdf).compile()
    assert model.nmesh == 1 and model.mesh_vertnum[0] == 8
    box = model.geom_aabb[[i for i in range(model.ngeom)
                           if model.geom_type[i] == mujoco.mjtGeom.mjGEOM_MESH][0]]
    # half sizes (m), in MuJoCo's principal frame of the mesh (axes reordered)
    assert sorted(box[3:]) == pytest.approx([0.05, 0.15, 0.2], abs=1e-6)
    warnings = [r.getMessage() for r in caplog.records if 'nope.dae' in r.getMessage()]
    assert len(warnings) == 1 and "link 'a' visual 0" in warnings[0], warnings


@pytest.mark.parametrize('self_collide, touching',
                         [('', False), ('false', False), ('true', True)])
def test_links_of_one_robot_collide_only_with_self_collide(self_collide, touching):
    import mujoco
    from amr_description.sim.simulation import Simulation
    inertial = ('<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" '
                'ixz="0" iyz="0"/></inertial>')
    box = '<collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>'
    tag = f'<gazebo reference="tip"><selfCollide>{self_collide}</selfCollide></gazebo>' \
        if self_collide else ''
    # base and tip (a grandchild: not MuJoCo's parent filter) overlap: MuJoCo collides
    # them, Gazebo does not unless one of them sets selfCollide
    urdf = (f'<robot name="r"><link name="base">{box}{inertial}</link>'
            f'<link name="mid">{inertial}</link><link name="tip">{box}{inertial}</link>'
            '<joint name="j1" type="revolute"><parent link="base"/><child link="mid"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
            '<joint name="j2" type="revolute"><parent link="mid"/><child link="tip"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/>'
            f'<origin xyz="0.05 0 0"/></joint>{tag}</robot>')
    sim = Simulation(0.001, 0.0)
    sim.spawn(urdf, pose=[0, 0, 1.0, 0, 0, 0])
    model, data = sim.world.model, sim.world.data
    mujoco.mj_forward(model, data)
    own = [c for c in data.contact[:data.ncon]
           if model.geom(c.geom1).name.startswith('r/') and
           model.geom(c.geom2).name.startswith('r/')]
    assert bool(own) == touching


def test_self_collide_that_is_not_a_boolean_refuses_the_spawn_in_one_line():
    from amr_description.sim.entity import SpawnError
    from amr_description.sim.simulation import Simulation
    urdf = ('<robot name="r"><link name="base"><inertial><mass value="1"/><inertia ixx="0.01" '
            'iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>'
            '<gazebo reference="base"><selfCollide>often</selfCollide></gazebo></robot>')
    sim = Simulation(0.001, 0.0)
    with pytest.raises(SpawnError) as refused:
        sim.spawn(urdf)
    assert str(refused.value) == ('<gazebo reference="base"><selfCollide>: expected true or '
                                  "false, found 'often'")
    assert not sim.entities and not sim.world.robots
