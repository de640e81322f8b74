# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""Reading an RViz 2 config: the Fixed Frame and the displays the viewer shows or not."""

import os

from amr_description.core.rviz_config import read_rviz_config
from amr_description.web.displays.registry import rviz_topic_parameters
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
VIEW = os.path.join(os.path.dirname(HERE), 'data', 'sensor_course', 'view.rviz')


def test_a_saved_rviz_config_gives_the_fixed_frame_topics_and_the_displays_not_shown():
    config = read_rviz_config(VIEW, rviz_topic_parameters())
    assert config.fixed_frame == 'odom' and config.tf
    assert config.topics == {
        'image_topics': ['/camera/image_raw'], 'imu_topics': [],
        'odometry_topics': ['/odom'], 'point_cloud_topics': [],
        'robot_description_topics': ['/robot_description'], 'scan_topics': ['/scan'],
        'map_topics': ['/map'], 'particle_cloud_topics': [], 'pose_array_topics': [],
        'pose_covariance_topics': [], 'path_topics': [], 'polygon_topics': [],
        'marker_array_topics': []}
    assert config.not_shown == []  # the Path is disabled


def test_groups_are_walked_and_a_description_file_source_is_not_a_topic(tmp_path):
    path = tmp_path / 'group.rviz'
    path.write_text("""Visualization Manager:
  Displays:
    - Class: rviz_common/Group
      Name: Sensors
      Displays:
        - Class: rviz_default_plugins/PointCloud2
          Topic: {Value: /points}
        - Class: rviz_default_plugins/Camera
          Topic: {Value: /front/image}
        - Class: rviz_default_plugins/TF
          Enabled: false
    - Class: rviz_default_plugins/RobotModel
      Description Source: File
      Description File: robot.urdf
""")
    config = read_rviz_config(str(path), rviz_topic_parameters())
    assert config.topics['point_cloud_topics'] == ['/points']
    assert config.topics['image_topics'] == ['/front/image']
    assert config.topics['robot_description_topics'] == [] and not config.tf
    assert config.fixed_frame == ''
    assert config.not_shown == ['RobotModel (rviz_default_plugins/RobotModel, no topic)']


@pytest.mark.parametrize('text, message', [
    (None, 'cannot read the RViz config'),
    ('a: [b\n', 'not a YAML RViz config (line 2)'),
    ('Panels: []\n', 'no "Visualization Manager" mapping'),
    ('Visualization Manager:\n  Displays: 3\n', 'Displays: expected a list of displays'),
])
def test_a_config_that_cannot_be_read_is_one_line_naming_the_file(tmp_path, text, message):
    path = tmp_path / 'bad.rviz'
    if text is not None:
        path.write_text(text)
    with pytest.raises(ValueError) as error:
        read_rviz_config(str(path), rviz_topic_parameters())
    assert str(error.value).startswith(str(path)) and message in str(error.value)
    assert '\n' not in str(error.value)


def test_viewer_d_becomes_the_rviz_config_parameter():
    from amr_description.nodes.viewer import display_config_args
    assert display_config_args(['viewer', '-d', '/x/view.rviz']) == \
        ['viewer', '--ros-args', '-p', 'rviz_config:=/x/view.rviz']
    assert display_config_args(['viewer', '--ros-args', '-d', 'x']) == \
        ['viewer', '--ros-args', '-d', 'x']  # inside ROS arguments: left to rclpy


def test_displays_are_plug_ins_found_through_their_entry_point_group():
    import ast
    from amr_description.web.displays import registry
    from amr_description.web.displays.base import Display
    classes = registry.display_classes()
    assert list(classes) == ['world', 'map', 'robot_model', 'tf_axes', 'trails', 'laser_scan',
                             'point_cloud', 'imu', 'image', 'navsat', 'contacts',
                             'particle_cloud', 'pose_array', 'pose_covariance', 'path',
                             'polygon', 'marker_array', 'teleop_pad', 'pose_tool', 'nav_panel',
                             'status']
    assert all(issubclass(cls, Display) for cls in classes.values())
    # every display module's Display subclass is registered: one module, one registration
    folder = os.path.join(os.path.dirname(HERE), '..', 'amr_description', 'web', 'displays')
    defined = set()
    for name in os.listdir(folder):
        if name.endswith('.py') and name not in ('base.py', 'registry.py', 'sensor_topics.py'):
            with open(os.path.join(folder, name)) as f:
                tree = ast.parse(f.read())
            defined |= {node.name for node in tree.body if isinstance(node, ast.ClassDef)
                        and node.name.endswith('Display')}
    assert defined == {cls.__name__ for cls in classes.values()}
    # the viewer's parameters and the .rviz reader's classes come from the displays
    parameters = registry.display_parameters()
    assert parameters['scan_topics'] == ['*'] and parameters['world'] == ''
    assert parameters['cmd_vel_topic'] == ''  # found in the graph
    assert registry.rviz_topic_parameters()['rviz_default_plugins/LaserScan'] == 'scan_topics'

    class RangeDisplay(Display):
        order = 56
        parameters = (('range_topics', ['/range']),)
        topics_parameter = 'range_topics'
        rviz_classes = {'rviz_default_plugins/Range': 'range_topics'}

    more = dict(classes, range=RangeDisplay)
    assert registry.display_parameters(more)['range_topics'] == ['/range']
    assert registry.rviz_topic_parameters(more)['rviz_default_plugins/Range'] == 'range_topics'
