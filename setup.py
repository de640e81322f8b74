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
    ] + [('share/' + package_name + '/' + folder, _data(folder))
         for folder in sorted(glob('worlds/models/*')) if os.path.isdir(folder)],
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
            'navigate_job = amr_description.nodes.navigate_job.main:main',
            'physics_report = amr_description.tools.physics_report:main',
            'screenshot = amr_description.tools.screenshot:main',
            'ros2 = amr_description.cli.main:main',
            'ros2_control_node = amr_description.nodes.ros2_control_node:main',
            'component_container = amr_description.nodes.component_container:main',
            'component_container_isolated = '
            'amr_description.nodes.component_container:main_isolated',
            'static_transform_publisher = '
            'amr_description.nodes.static_transform_publisher:main',
            'lifecycle_manager = amr_description.nodes.lifecycle_manager:main',
            'map_server = amr_description.nodes.map_server:main',
            'planner_server = amr_description.nodes.planner_server:main',
            'controller_server = amr_description.nodes.controller_server:main',
            'behavior_server = amr_description.nodes.behavior_server:main',
            'bt_navigator = amr_description.nodes.bt_navigator:main',
            'velocity_smoother = amr_description.nodes.velocity_smoother:main',
            'waypoint_follower = amr_description.nodes.waypoint_follower:main',
            'map_saver_server = amr_description.nodes.map_saver:server_main',
            'map_saver_cli = amr_description.nodes.map_saver:cli_main',
            'async_slam_toolbox_node = amr_description.nodes.slam_toolbox:main',
            'sync_slam_toolbox_node = amr_description.nodes.sync_slam_toolbox:main',
            'localization_slam_toolbox_node = '
            'amr_description.nodes.slam_toolbox_localization:main',
            'amcl = amr_description.nodes.amcl:main',
            'lifecycle_autostart = amr_description.nodes.lifecycle_autostart:main',
        ],
        'amr_description.command': [
            'action = amr_description.cli.action:COMMAND',
            'bag = amr_description.cli.bag:COMMAND',
            'control = amr_description.cli.control:COMMAND',
            'daemon = amr_description.cli.daemon:COMMAND',
            'doctor = amr_description.cli.doctor:COMMAND',
            'interface = amr_description.cli.interface:COMMAND',
            'launch = amr_description.cli.launch:COMMAND',
            'lifecycle = amr_description.cli.lifecycle:COMMAND',
            'node = amr_description.cli.node:COMMAND',
            'param = amr_description.cli.param:COMMAND',
            'pkg = amr_description.cli.pkg:COMMAND',
            'run = amr_description.cli.run:COMMAND',
            'service = amr_description.cli.service:COMMAND',
            'topic = amr_description.cli.topic:COMMAND',
            'wtf = amr_description.cli.doctor:COMMAND',
        ],
        'amr_description.action.verb': [
            'list = amr_description.cli.action:VERB_LIST',
            'info = amr_description.cli.action:VERB_INFO',
            'send_goal = amr_description.cli.action:VERB_SEND_GOAL',
        ],
        'amr_description.bag.verb': [
            'info = amr_description.cli.bag.info:VERB_INFO',
            'play = amr_description.cli.bag.play:VERB_PLAY',
            'record = amr_description.cli.bag.record:VERB_RECORD',
        ],
        'amr_description.control.verb': [
            'cleanup_controller = amr_description.cli.control.lifecycle:VERB_CLEANUP_CONTROLLER',
            'list_controller_types = '
            'amr_description.cli.control.listing:VERB_LIST_CONTROLLER_TYPES',
            'list_controllers = amr_description.cli.control.listing:VERB_LIST_CONTROLLERS',
            'list_hardware_components = '
            'amr_description.cli.control.listing:VERB_LIST_HARDWARE_COMPONENTS',
            'list_hardware_interfaces = '
            'amr_description.cli.control.listing:VERB_LIST_HARDWARE_INTERFACES',
            'load_controller = amr_description.cli.control.lifecycle:VERB_LOAD_CONTROLLER',
            'reload_controller_libraries = '
            'amr_description.cli.control.lifecycle:VERB_RELOAD_CONTROLLER_LIBRARIES',
            'set_controller_state = '
            'amr_description.cli.control.lifecycle:VERB_SET_CONTROLLER_STATE',
            'set_hardware_component_state = '
            'amr_description.cli.control.hardware:VERB_SET_HARDWARE_COMPONENT_STATE',
            'switch_controllers = amr_description.cli.control.lifecycle:VERB_SWITCH_CONTROLLERS',
            'unload_controller = amr_description.cli.control.lifecycle:VERB_UNLOAD_CONTROLLER',
            'view_controller_chains = '
            'amr_description.cli.control.chains:VERB_VIEW_CONTROLLER_CHAINS',
        ],
        'amr_description.daemon.verb': [
            'start = amr_description.cli.daemon:VERB_START',
            'status = amr_description.cli.daemon:VERB_STATUS',
            'stop = amr_description.cli.daemon:VERB_STOP',
        ],
        'amr_description.interface.verb': [
            'list = amr_description.cli.interface:VERB_LIST',
            'package = amr_description.cli.interface:VERB_PACKAGE',
            'packages = amr_description.cli.interface:VERB_PACKAGES',
            'show = amr_description.cli.interface:VERB_SHOW',
        ],
        'amr_description.lifecycle.verb': [
            'get = amr_description.cli.lifecycle:VERB_GET',
            'list = amr_description.cli.lifecycle:VERB_LIST',
            'nodes = amr_description.cli.lifecycle:VERB_NODES',
            'set = amr_description.cli.lifecycle:VERB_SET',
        ],
        'amr_description.node.verb': [
            'info = amr_description.cli.node:VERB_INFO',
            'list = amr_description.cli.node:VERB_LIST',
        ],
        'amr_description.param.verb': [
            'delete = amr_description.cli.param.change:VERB_DELETE',
            'describe = amr_description.cli.param.query:VERB_DESCRIBE',
            'dump = amr_description.cli.param.change:VERB_DUMP',
            'get = amr_description.cli.param.query:VERB_GET',
            'list = amr_description.cli.param.query:VERB_LIST',
            'load = amr_description.cli.param.change:VERB_LOAD',
            'set = amr_description.cli.param.change:VERB_SET',
        ],
        'amr_description.pkg.verb': [
            'executables = amr_description.cli.pkg:VERB_EXECUTABLES',
            'list = amr_description.cli.pkg:VERB_LIST',
            'prefix = amr_description.cli.pkg:VERB_PREFIX',
            'xml = amr_description.cli.pkg:VERB_XML',
        ],
        'amr_description.service.verb': [
            'call = amr_description.cli.service:VERB_CALL',
            'find = amr_description.cli.service:VERB_FIND',
            'list = amr_description.cli.service:VERB_LIST',
            'type = amr_description.cli.service:VERB_TYPE',
        ],
        'amr_description.topic.verb': [
            'bw = amr_description.cli.topic.rates:VERB_BW',
            'delay = amr_description.cli.topic.rates:VERB_DELAY',
            'echo = amr_description.cli.topic.echo:VERB_ECHO',
            'find = amr_description.cli.topic.listing:VERB_FIND',
            'hz = amr_description.cli.topic.rates:VERB_HZ',
            'info = amr_description.cli.topic.listing:VERB_INFO',
            'list = amr_description.cli.topic.listing:VERB_LIST',
            'pub = amr_description.cli.topic.pub:VERB_PUB',
            'type = amr_description.cli.topic.listing:VERB_TYPE',
        ],
        'amr_description.components': [
            'amr_description::RobotStatePublisher = '
            'amr_description.nodes.robot_state_publisher:RobotStatePublisher',
            'amr_description::StaticTransformBroadcasterNode = '
            'amr_description.nodes.static_transform_publisher:StaticTransformBroadcasterNode',
            'nav2_amcl::AmclNode = amr_description.nodes.amcl:Amcl',
            'behavior_server::BehaviorServer = '
            'amr_description.nodes.behavior_server:BehaviorServer',
            'nav2_bt_navigator::BtNavigator = amr_description.nodes.bt_navigator:BtNavigator',
            'nav2_controller::ControllerServer = '
            'amr_description.nodes.controller_server:ControllerServer',
            'nav2_lifecycle_manager::LifecycleManager = '
            'amr_description.nodes.lifecycle_manager:LifecycleManager',
            'nav2_map_server::MapServer = amr_description.nodes.map_server:MapServer',
            'nav2_planner::PlannerServer = amr_description.nodes.planner_server:PlannerServer',
            'nav2_velocity_smoother::VelocitySmoother = '
            'amr_description.nodes.velocity_smoother:VelocitySmoother',
            'nav2_waypoint_follower::WaypointFollower = '
            'amr_description.nodes.waypoint_follower:WaypointFollower',
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
            'map = amr_description.web.displays.map:MapDisplay',
            'laser_scan = amr_description.web.displays.laser_scan:LaserScanDisplay',
            'particle_cloud = amr_description.web.displays.particle_cloud:ParticleCloudDisplay',
            'pose_array = amr_description.web.displays.particle_cloud:PoseArrayDisplay',
            'pose_covariance = '
            'amr_description.web.displays.pose_covariance:PoseWithCovarianceDisplay',
            'pose_tool = amr_description.web.displays.pose_tool:PoseToolDisplay',
            'path = amr_description.web.displays.path:PathDisplay',
            'polygon = amr_description.web.displays.path:PolygonDisplay',
            'marker_array = amr_description.web.displays.markers:MarkerArrayDisplay',
            'nav_panel = amr_description.web.displays.nav_panel:NavigationPanelDisplay',
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
