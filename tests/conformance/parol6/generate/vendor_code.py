"""Loads the PAROL6 vendor functions the generator runs, straight from a vendor checkout.

Neither vendor module can be imported whole here: the API's modules pull in numba, msgspec,
ormsgpack, pinokin and waldoctl, and the commander's Serial_sender_good_latest.py opens a serial
port, a GUI and processes at import. So each vendor file is parsed and only the top-level
definitions named below (functions, a class, constant assignments) are compiled and executed,
unchanged, in a namespace that holds what they use. numba's `njit` is replaced by an identity
decorator: the functions then run as the plain Python they are written in (numba compiles the
same source; see provenance.json).
"""
import __future__
import ast
import logging
import math
import struct
import threading
import types
from pathlib import Path

import numpy as np
import serial

# What is taken from each vendor file (paths relative to the checkout).
API_ROBOT = "parol6/PAROL6_ROBOT.py"
API_CONFIG = "parol6/config.py"
API_WIRE = "parol6/protocol/wire.py"
API_TRANSPORT = "parol6/server/transports/serial_transport.py"
COMMANDER_SENDER = "GUI/files/Serial_sender_good_latest.py"
COMMANDER_ROBOT = "GUI/files/PAROL6_ROBOT.py"

API_ROBOT_NAMES = {"Microstep", "steps_per_revolution", "degree_per_step_constant",
                   "radian_per_step_constant", "_joint_ratio"}
API_CONFIG_NAMES = {"SERIAL_RX_RING_DEFAULT", "_degree_per_step", "_radian_per_step", "_joint_ratio",
                    "_rad_to_steps_jit", "rad_to_steps", "rad_to_steps_scalar", "_tls",
                    "_get_scratch_f64", "steps_to_rad", "steps_to_rad_scalar", "speed_rad_to_steps",
                    "speed_rad_to_steps_scalar", "speed_steps_to_rad", "speed_steps_to_rad_scalar"}
API_WIRE_NAMES = {"START", "END", "PAYLOAD_LEN", "split_to_3_bytes", "fuse_3_bytes", "fuse_2_bytes",
                  "_pack_positions", "_unpack_positions", "_pack_bitfield", "_unpack_bitfield",
                  "pack_tx_frame_into", "unpack_rx_frame_into"}
API_TRANSPORT_NAMES = {"_append_to_ring_numba", "_parse_frames_njit", "SerialTransport"}
COMMANDER_SENDER_NAMES = {
    "int_to_3_bytes", "start_bytes", "end_bytes", "input_byte", "start_cond1_byte", "start_cond2_byte",
    "start_cond3_byte", "end_cond1_byte", "end_cond2_byte", "start_cond1", "start_cond2", "start_cond3",
    "good_start", "data_len", "data_buffer", "data_counter", "Pack_data", "Unpack_data", "Get_data",
    "Split_2_3_bytes", "Split_2_bitfield", "Fuse_3_bytes", "Fuse_2_bytes", "Fuse_bitfield_2_bytearray"}
COMMANDER_ROBOT_NAMES = {"Microstep", "steps_per_revolution", "degree_per_step_constant",
                         "radian_per_step_constant", "Joint_reduction_ratio", "RAD2STEPS", "DEG2STEPS",
                         "STEPS2DEG", "STEPS2RADS", "SPEED_RAD2STEP", "SPEED_STEP2RAD"}

FILES_RUN = {"api": [API_ROBOT, API_CONFIG, API_WIRE, API_TRANSPORT],
             "commander": [COMMANDER_SENDER, COMMANDER_ROBOT]}


def njit(*args, **_options):
    """numba.njit stand-in: @njit and @njit(cache=True) both leave the function as written."""
    if len(args) == 1 and callable(args[0]):
        return args[0]
    return lambda function: function


numba_stub = types.SimpleNamespace(njit=njit)


def _defined_names(node):
    if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
        return {node.name}
    if isinstance(node, ast.Assign):
        return {t.id for t in node.targets if isinstance(t, ast.Name)}
    if isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
        return {node.target.id}
    return set()


def load(checkout, relative_path, names, namespace):
    """Executes the top-level statements of `relative_path` that define one of `names`, in
    file order, in `namespace` (annotations left unevaluated, as `from __future__ import
    annotations` would). Fails if a name is not defined there: the vendor file changed."""
    path = Path(checkout) / relative_path
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    wanted = [node for node in tree.body if _defined_names(node) & names]
    missing = names - set().union(*(_defined_names(node) for node in wanted))
    if missing:
        raise SystemExit(f"{path}: no top-level definition of {sorted(missing)}; is this the right checkout?")
    code = compile(ast.Module(body=wanted, type_ignores=[]), str(path), "exec",
                   flags=__future__.annotations.compiler_flag, dont_inherit=True)
    exec(code, namespace)  # noqa: S102 - running the vendor's own code is the point
    return namespace


def load_api(checkout):
    robot = load(checkout, API_ROBOT, API_ROBOT_NAMES, {"np": np})
    robot_module = types.SimpleNamespace(
        degree_per_step_constant=robot["degree_per_step_constant"],
        radian_per_step_constant=robot["radian_per_step_constant"],
        joint=types.SimpleNamespace(ratio=robot["_joint_ratio"]))
    config = load(checkout, API_CONFIG, API_CONFIG_NAMES,
                  {"np": np, "njit": njit, "threading": threading, "PAROL6_ROBOT": robot_module})
    wire = load(checkout, API_WIRE, API_WIRE_NAMES, {"np": np, "njit": njit})
    transport = load(checkout, API_TRANSPORT, API_TRANSPORT_NAMES, {
        "np": np, "numba": numba_stub, "serial": serial, "os": __import__("os"),
        "time": __import__("time"), "cast": lambda _type, value: value,
        "logger": logging.getLogger("parol6.transport"),
        "SERIAL_RX_RING_DEFAULT": config["SERIAL_RX_RING_DEFAULT"],
        "pack_tx_frame_into": wire["pack_tx_frame_into"]})
    return types.SimpleNamespace(config=config, wire=wire, transport=transport)


def load_commander(checkout, line):
    """`line` stands in for the module's `ser` (pyserial): inWaiting() and read()."""
    sender = load(checkout, COMMANDER_SENDER, COMMANDER_SENDER_NAMES,
                  {"struct": struct, "logging": logging, "ser": line})
    robot = load(checkout, COMMANDER_ROBOT, COMMANDER_ROBOT_NAMES, {"np": np, "pi": math.pi})
    return types.SimpleNamespace(sender=sender, robot=robot)
