# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""ament_python build description of amr_description."""

from glob import glob
import os

from setuptools import find_packages
from setuptools import setup

package_name = 'amr_description'


def _data(folder, pattern='*'):
    """Return the files of a source folder for ``data_files``, or ``[]`` when there are none."""
    return [path for path in glob(os.path.join(folder, pattern)) if os.path.isfile(path)]


setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test', 'test.*']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        ('share/' + package_name + '/urdf', _data('urdf')),
        ('share/' + package_name + '/config', _data('config')),
        ('share/' + package_name + '/worlds', _data('worlds')),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='amr_description maintainers',
    maintainer_email='maintainers@amr-description.dev',
    description='Model, simulate (MuJoCo) and drive a four-wheeled skid-steer robot in ROS 2.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'talker = amr_description.nodes.talker:main',
            'listener = amr_description.nodes.listener:main',
            'robot_state_publisher = amr_description.nodes.robot_state_publisher:main',
            'joint_state_publisher = amr_description.nodes.joint_state_publisher:main',
            'joint_state_publisher_gui = amr_description.nodes.joint_state_publisher_gui:main',
            'viewer = amr_description.nodes.viewer:main',
            'check_model = amr_description.nodes.check_model:main',
            'render = amr_description.nodes.render:main',
            'mujoco_sim = amr_description.nodes.mujoco_sim.node:main',
            'create = amr_description.nodes.create:main',
            'spawner = amr_description.nodes.spawner:main',
            'teleop_twist_keyboard = amr_description.nodes.teleop_twist_keyboard:main',
            'bringup = amr_description.launch.bringup:main',
            'drive_square = amr_description.nodes.drive_square.main:main',
            'physics_report = amr_description.tools.physics_report:main',
            'ros2 = amr_description.cli.main:main',
            'ros2_control_node = amr_description.nodes.ros2_control_node:main',
            'component_container = amr_description.nodes.component_container:main',
            'static_transform_publisher = '
            'amr_description.nodes.static_transform_publisher:main',
        ],
        'amr_description.components': [
            'amr_description::RobotStatePublisher = '
            'amr_description.nodes.robot_state_publisher:RobotStatePublisher',
            'amr_description::StaticTransformBroadcasterNode = '
            'amr_description.nodes.static_transform_publisher:StaticTransformBroadcasterNode',
        ],
        'amr_description.controllers': [
            'joint_state_broadcaster/JointStateBroadcaster = '
            'amr_description.control.joint_state_broadcaster:JointStateBroadcaster',
            'diff_drive_controller/DiffDriveController = '
            'amr_description.control.diff_drive_controller:DiffDriveController',
        ],
        'amr_description.displays': [
            'world = amr_description.web.displays.world:WorldDisplay',
            'robot_model = amr_description.web.displays.robot_model:RobotModelDisplay',
            'tf_axes = amr_description.web.displays.tf_axes:TfAxesDisplay',
            'trails = amr_description.web.displays.trails:TrailsDisplay',
            'laser_scan = amr_description.web.displays.laser_scan:LaserScanDisplay',
            'point_cloud = amr_description.web.displays.point_cloud:PointCloudDisplay',
            'imu = amr_description.web.displays.imu:ImuDisplay',
            'image = amr_description.web.displays.image:ImageDisplay',
            'navsat = amr_description.web.displays.navsat:NavSatDisplay',
            'contacts = amr_description.web.displays.contacts:ContactsDisplay',
            'teleop_pad = amr_description.web.displays.teleop_pad:TeleopPadDisplay',
            'status = amr_description.web.displays.status:StatusDisplay',
        ],
        'amr_description.sensors': [
            'camera = amr_description.sim.sensors.camera:create',
            'contact = amr_description.sim.sensors.contact:create',
            'ground_truth = amr_description.sim.sensors.ground_truth:create',
            'imu = amr_description.sim.sensors.imu:create',
            'lidar = amr_description.sim.sensors.lidar:create',
            'navsat = amr_description.sim.sensors.navsat:create',
        ],
        'amr_description.hardware': [
            'amr_description/MujocoSystem = amr_description.sim.mujoco_system:MujocoSystem',
            'gz_ros2_control/GazeboSimSystem = amr_description.sim.mujoco_system:MujocoSystem',
            'ign_ros2_control/IgnitionSystem = amr_description.sim.mujoco_system:MujocoSystem',
            'mock_components/GenericSystem = '
            'amr_description.control.generic_system:GenericSystem',
        ],
    },
)
