"""The scripted session: the SDK's public XArmAPI calls a user makes, in order, each named as a
step (the transcript tags every frame with the step that sent it). Error cases included: a target
beyond a joint limit (the SDK refuses it itself), servo_j outside servo mode, a register the
simulator does not emulate, a gripper fault, the e-stop state. The gripper also closes onto an
object the simulator is told to place between its fingers."""
import math
import time


def plain(value):
    """The call's result as JSON: tuples as lists, floats rounded (they come from fp32)."""
    if isinstance(value, float):
        return round(value, 4) if math.isfinite(value) else str(value)
    if isinstance(value, (list, tuple)):
        return [plain(item) for item in value]
    if isinstance(value, dict):
        return {str(key): plain(item) for key, item in value.items()}
    return value


def run_session(XArmAPI, proxy, sim_control):
    calls = []

    def step(name, call, function):
        proxy.step = name
        result = function()
        calls.append({'step': name, 'call': call, 'result': plain(result)})
        time.sleep(0.05)  # keeps the steps apart on the wire
        return result

    proxy.step = 'connect'
    arm = XArmAPI('127.0.0.1', is_radian=True)  # report_type 'rich', the SDK's default
    calls.append({'step': 'connect', 'call': "XArmAPI('127.0.0.1', is_radian=True)",
                  'result': {'connected': arm.connected, 'version': arm.version, 'sn': arm.sn,
                             'axis': arm.axis, 'device_type': arm.device_type}})
    time.sleep(0.5)  # a few rich reports

    step('version', 'get_version()', arm.get_version)
    step('version', 'get_robot_sn()', arm.get_robot_sn)
    step('state', 'get_state()', arm.get_state)
    step('state', 'get_err_warn_code()', arm.get_err_warn_code)
    step('state', 'get_cmdnum()', arm.get_cmdnum)
    step('state', 'get_position()', arm.get_position)
    step('state', 'get_servo_angle()', arm.get_servo_angle)
    step('state', 'get_servo_debug_msg()', arm.get_servo_debug_msg)

    step('enable', 'motion_enable(True)', lambda: arm.motion_enable(True))
    step('enable', 'set_mode(0)', lambda: arm.set_mode(0))
    step('enable', 'set_state(0)', lambda: arm.set_state(0))
    time.sleep(0.5)  # the next rich report shows the arm ready

    target = [0.2, -0.3, -0.2, 0.0, 0.5, 0.0]
    step('joint_move', 'set_servo_angle(angle=%s, speed=0.8, wait=True)' % target,
         lambda: arm.set_servo_angle(angle=target, speed=0.8, mvacc=8, wait=True, timeout=20))
    step('joint_move', 'get_servo_angle()', arm.get_servo_angle)
    code, pose = step('line_move', 'get_position()', arm.get_position)
    goal = list(pose)
    goal[2] -= 20
    step('line_move', 'set_position(z - 20 mm, speed=50, wait=True)',
         lambda: arm.set_position(*goal, speed=50, mvacc=500, wait=True, timeout=20))
    step('line_move', 'get_position()', arm.get_position)
    step('kinematics', 'get_forward_kinematics(%s)' % target, lambda: arm.get_forward_kinematics(target))
    step('kinematics', 'is_joint_limit(%s)' % target, lambda: arm.is_joint_limit(target))

    step('gripper', 'set_gripper_mode(0)', lambda: arm.set_gripper_mode(0))
    step('gripper', 'set_gripper_enable(True)', lambda: arm.set_gripper_enable(True))
    step('gripper', 'set_gripper_speed(2000)', lambda: arm.set_gripper_speed(2000))
    step('gripper', 'get_gripper_version()', arm.get_gripper_version)
    step('gripper', 'set_gripper_position(600, wait=True)', lambda: arm.set_gripper_position(600, wait=True, timeout=10))
    step('gripper', 'get_gripper_position()', arm.get_gripper_position)
    step('gripper', 'get_gripper_status()', arm.get_gripper_status)
    step('gripper', 'set_gripper_position(0, wait=True)', lambda: arm.set_gripper_position(0, wait=True, timeout=10))
    step('gripper', 'get_gripper_err_code()', arm.get_gripper_err_code)
    step('gripper', 'set_gripper_position(600, wait=True)', lambda: arm.set_gripper_position(600, wait=True, timeout=10))
    proxy.step = 'grip'
    sim_control({'op': 'gripper_object', 'width_pulses': 300})  # an object 300 pulses wide
    step('grip', 'set_gripper_position(0, wait=True) onto an object',
         lambda: arm.set_gripper_position(0, wait=True, timeout=10))
    step('grip', 'get_gripper_status()', arm.get_gripper_status)
    step('grip', 'get_gripper_position()', arm.get_gripper_position)

    step('reduced', 'get_reduced_mode()', arm.get_reduced_mode)
    step('reduced', 'set_reduced_mode(True)', lambda: arm.set_reduced_mode(True))
    step('reduced', 'get_reduced_mode()', arm.get_reduced_mode)
    step('reduced', 'set_reduced_mode(False)', lambda: arm.set_reduced_mode(False))

    step('errors', 'set_servo_angle(angle=[0, 3.0, 0, 0, 0, 0]) beyond joint 2',
         lambda: arm.set_servo_angle(angle=[0, 3.0, 0, 0, 0, 0], wait=True, timeout=5))
    step('errors', 'set_servo_angle_j(%s) in mode 0' % target, lambda: arm.set_servo_angle_j(target))
    step('errors', 'get_joints_torque() (not emulated)', arm.get_joints_torque)
    step('errors', 'get_err_warn_code()', arm.get_err_warn_code)
    step('errors', 'clean_warn()', arm.clean_warn)
    proxy.step = 'errors'
    sim_control({'op': 'gripper_error', 'code': 14})
    step('errors', 'get_gripper_err_code() with gripper fault 14', arm.get_gripper_err_code)
    step('errors', 'set_gripper_position(300) with the fault', lambda: arm.set_gripper_position(300))
    step('errors', 'clean_gripper_error()', arm.clean_gripper_error)
    step('errors', 'get_gripper_err_code()', arm.get_gripper_err_code)

    step('servo', 'set_mode(1)', lambda: arm.set_mode(1))
    step('servo', 'set_state(0)', lambda: arm.set_state(0))
    time.sleep(0.5)
    for i in range(3):
        angles = [0.2 + 0.01 * (i + 1), -0.3, -0.2, 0.0, 0.5, 0.0]
        step('servo', 'set_servo_angle_j(%s)' % angles, lambda angles=angles: arm.set_servo_angle_j(angles))
        time.sleep(0.02)
    step('servo', 'set_mode(0)', lambda: arm.set_mode(0))
    step('servo', 'set_state(0)', lambda: arm.set_state(0))
    time.sleep(0.5)

    step('home', 'move_gohome(wait=True)', lambda: arm.move_gohome(speed=0.8, wait=True, timeout=20))
    step('stop', 'emergency_stop()', arm.emergency_stop)
    step('stop', 'get_state()', arm.get_state)
    step('disconnect', 'disconnect()', arm.disconnect)
    return calls
