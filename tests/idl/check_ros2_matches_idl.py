#!/usr/bin/env python3
"""Check that the ROS 2 package idl/ros2/robotd_msgs matches robotd's DDS IDL field for field.

rmw_cyclonedds matches a ROS type with robotd's type by name only: nothing at run time checks
that the layouts agree. A field added to robotd_msgs.idl but not to the .msg (or the other way
round) makes ROS nodes decode garbage. This script makes that drift a test failure.

What it checks:
  * every struct of module robotd_msgs in the IDL has a .msg/.srv counterpart and vice versa;
  * each .msg (and each half of a .srv) has the IDL struct's members, in the same order, with
    the same names and mapped types (IDL float -> float32, sequence<T> -> T[], nested struct
    -> pkg/Name, ...);
  * each service struct starts with the rmw_cyclonedds request header
    `uint64 client_guid; int64 sequence_number;`, which the .srv does not contain;
  * the ROS standard types in ros_common.idl match their upstream ROS 2 definitions;
  * the package builds in a ROS 2 workspace: interface files are ASCII, names follow the
    rosidl rules, every file is listed in rosidl_generate_interfaces and every package a field
    refers to is a dependency in CMakeLists.txt and package.xml.

Constants and comments in .msg/.srv files are not on the wire and are not compared.
Exit status: 0 = match, 1 = drift found, 2 = a file could not be read or parsed.
Standard library only.
"""

from __future__ import annotations

import argparse
import dataclasses
import difflib
import re
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path

PACKAGE = "robotd_msgs"
SERVICE_HEADER = [("uint64", "client_guid"), ("int64", "sequence_number")]

# Upstream ROS 2 definitions (Humble and Jazzy agree) of the standard types robotd carries.
# ros_common.idl must lay them out exactly like this or ROS nodes misread robotd's samples.
STANDARD_ROS_TYPES = {
    "builtin_interfaces/msg/Time": [("int32", "sec"), ("uint32", "nanosec")],
    "std_msgs/msg/Header": [("builtin_interfaces/Time", "stamp"), ("string", "frame_id")],
    "geometry_msgs/msg/Vector3": [("float64", "x"), ("float64", "y"), ("float64", "z")],
    "geometry_msgs/msg/Quaternion": [("float64", "x"), ("float64", "y"), ("float64", "z"), ("float64", "w")],
    "geometry_msgs/msg/Point": [("float64", "x"), ("float64", "y"), ("float64", "z")],
    "geometry_msgs/msg/Pose": [("geometry_msgs/Point", "position"), ("geometry_msgs/Quaternion", "orientation")],
    "geometry_msgs/msg/PoseStamped": [("std_msgs/Header", "header"), ("geometry_msgs/Pose", "pose")],
    "sensor_msgs/msg/JointState": [
        ("std_msgs/Header", "header"),
        ("string[]", "name"),
        ("float64[]", "position"),
        ("float64[]", "velocity"),
        ("float64[]", "effort"),
    ],
    "sensor_msgs/msg/Imu": [
        ("std_msgs/Header", "header"),
        ("geometry_msgs/Quaternion", "orientation"),
        ("float64[9]", "orientation_covariance"),
        ("geometry_msgs/Vector3", "angular_velocity"),
        ("float64[9]", "angular_velocity_covariance"),
        ("geometry_msgs/Vector3", "linear_acceleration"),
        ("float64[9]", "linear_acceleration_covariance"),
    ],
}

# IDL primitive type (after folding multi-word names) -> ROS type.
IDL_TO_ROS_PRIMITIVE = {
    "boolean": "bool",
    "octet": "byte",
    "char": "char",
    "int8": "int8",
    "uint8": "uint8",
    "int16": "int16",
    "uint16": "uint16",
    "int32": "int32",
    "uint32": "uint32",
    "int64": "int64",
    "uint64": "uint64",
    "short": "int16",
    "unsigned short": "uint16",
    "long": "int32",
    "unsigned long": "uint32",
    "long long": "int64",
    "unsigned long long": "uint64",
    "float": "float32",
    "double": "float64",
    "string": "string",
    "wstring": "wstring",
}
ROS_PRIMITIVES = {
    "bool", "byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64",
    "float32", "float64", "string", "wstring",
}

# rosidl naming rules (rosidl_adapter/parser.py).
ROS_FIELD_NAME = re.compile(r"^(?!.*__)(?!.*_$)[a-z][a-z0-9_]*$")
ROS_CONSTANT_NAME = re.compile(r"^[A-Z]([A-Z0-9_]?[A-Z0-9]+)*$")
ROS_MESSAGE_NAME = re.compile(r"^[A-Z][A-Za-z0-9]*$")


class ParseError(Exception):
    """A file that cannot be understood; the message names file and line."""


@dataclasses.dataclass
class Field:
    type: str  # ROS spelling: float32, string[], std_msgs/Header, float64[9], string<=8, ...
    name: str
    line: int


@dataclasses.dataclass
class IdlStruct:
    scoped_name: tuple[str, ...]  # ("robotd_msgs", "msg", "dds_", "ControlCommand_")
    members: list[Field]
    path: Path
    line: int

    @property
    def location(self) -> str:
        return f"{self.path}:{self.line}"

    @property
    def idl_name(self) -> str:
        return "::".join(self.scoped_name)


@dataclasses.dataclass
class RosInterface:
    kind: str  # "msg" or "srv"
    name: str
    sections: list[list[Field]]  # msg: [fields]; srv: [request, response]
    path: Path


# --- IDL ------------------------------------------------------------------------------------

IDL_TOKEN = re.compile(
    r"(?P<space>\s+)|(?P<comment>//[^\n]*|/\*.*?\*/)|(?P<preprocessor>#[^\n]*)"
    r"|(?P<scope>::)|(?P<word>[A-Za-z_][A-Za-z0-9_]*)|(?P<number>\d+)"
    r"|(?P<string>\"(?:[^\"\\]|\\.)*\")|(?P<punct>[{}<>;:,\[\]()=@-])",
    re.DOTALL,
)


def tokenize_idl(text: str, path: Path) -> list[tuple[str, int]]:
    tokens = []
    position = 0
    line = 1
    while position < len(text):
        match = IDL_TOKEN.match(text, position)
        if match is None:
            raise ParseError(f"{path}:{line}: unexpected character {text[position]!r}")
        kind = match.lastgroup
        if kind not in ("space", "comment", "preprocessor"):
            tokens.append((match.group(), line))
        line += match.group().count("\n")
        position = match.end()
    return tokens


class IdlParser:
    """The IDL subset rosidl and robotd use: modules, structs, typedefs, constants, annotations."""

    def __init__(self, text: str, path: Path):
        self.path = path
        self.tokens = tokenize_idl(text, path)
        self.index = 0
        self.structs: list[IdlStruct] = []
        self.typedefs: dict[tuple[str, ...], str] = {}

    # token helpers
    def peek(self, offset: int = 0) -> str:
        index = self.index + offset
        return self.tokens[index][0] if index < len(self.tokens) else ""

    def line(self) -> int:
        if self.index < len(self.tokens):
            return self.tokens[self.index][1]
        return self.tokens[-1][1] if self.tokens else 1

    def fail(self, message: str) -> ParseError:
        return ParseError(f"{self.path}:{self.line()}: {message}")

    def take(self, expected: str | None = None) -> str:
        if self.index >= len(self.tokens):
            raise self.fail(f"unexpected end of file{f', expected {expected!r}' if expected else ''}")
        token = self.tokens[self.index][0]
        if expected is not None and token != expected:
            raise self.fail(f"expected {expected!r}, found {token!r}")
        self.index += 1
        return token

    def skip_annotations(self) -> None:
        while self.peek() == "@":
            self.take("@")
            self.take()
            if self.peek() == "(":
                depth = 0
                while True:
                    token = self.take()
                    depth += token == "("
                    depth -= token == ")"
                    if depth == 0:
                        break

    # grammar
    def parse(self) -> None:
        self.parse_definitions(())
        if self.index != len(self.tokens):
            raise self.fail(f"unexpected {self.peek()!r}")

    def parse_definitions(self, scope: tuple[str, ...]) -> None:
        while self.index < len(self.tokens) and self.peek() != "}":
            self.skip_annotations()
            keyword = self.peek()
            if keyword == "module":
                self.take()
                name = self.take()
                self.take("{")
                self.parse_definitions(scope + (name,))
                self.take("}")
                self.take(";")
            elif keyword == "struct":
                self.parse_struct(scope)
            elif keyword == "typedef":
                self.take()
                type_name = self.parse_type(scope)
                name = self.take()
                type_name = self.parse_array_suffix(type_name)
                self.take(";")
                self.typedefs[scope + (name,)] = type_name
            elif keyword == "const":
                while self.take() != ";":
                    pass
            else:
                raise self.fail(f"unsupported IDL construct {keyword!r} (the checker knows module, struct, "
                                "typedef, const)")

    def parse_struct(self, scope: tuple[str, ...]) -> None:
        self.take("struct")
        line = self.line()
        name = self.take()
        if self.peek() == ";":  # forward declaration
            self.take()
            return
        if self.peek() == ":":
            raise self.fail(f"struct {name} inherits; ROS types never do")
        self.take("{")
        members: list[Field] = []
        while self.peek() != "}":
            self.skip_annotations()
            member_line = self.line()
            type_name = self.parse_type(scope)
            while True:
                member = self.take()
                members.append(Field(self.parse_array_suffix(type_name), member, member_line))
                if self.peek() != ",":
                    break
                self.take(",")
            self.take(";")
        self.take("}")
        self.take(";")
        self.structs.append(IdlStruct(scope + (name,), members, self.path, line))

    def parse_array_suffix(self, type_name: str) -> str:
        while self.peek() == "[":
            self.take("[")
            size = self.take()
            if not size.isdigit():
                raise self.fail(f"array size {size!r} is not a number")
            self.take("]")
            type_name = f"{type_name}[{size}]"
        return type_name

    def parse_type(self, scope: tuple[str, ...]) -> str:
        """Returns the type in an intermediate spelling: primitives as IDL, sequences as
        `sequence<T>` / `sequence<T,N>`, strings as `string` / `string<N>`, structs as
        `::`-joined absolute names."""
        token = self.take()
        if token == "sequence":
            self.take("<")
            element = self.parse_type(scope)
            bound = ""
            if self.peek() == ",":
                self.take(",")
                bound = "," + self.take()
            self.take(">")
            return f"sequence<{element}{bound}>"
        if token in ("string", "wstring"):
            if self.peek() == "<":
                self.take("<")
                bound = self.take()
                self.take(">")
                return f"{token}<{bound}>"
            return token
        if token == "unsigned":
            second = self.take()
            if second == "long" and self.peek() == "long":
                self.take()
                return "unsigned long long"
            return f"unsigned {second}"
        if token == "long" and self.peek() == "long":
            self.take()
            return "long long"
        if token == "long" and self.peek() == "double":
            raise self.fail("long double has no ROS equivalent")
        if token in IDL_TO_ROS_PRIMITIVE:
            return token
        # scoped name, possibly relative or with a leading ::
        parts = [] if token == "::" else [token]
        while self.peek() == "::":
            self.take("::")
            parts.append(self.take())
        if not parts or not all(re.match(r"^[A-Za-z_]\w*$", part) for part in parts):
            raise self.fail(f"cannot read type starting with {token!r}")
        return "scoped:" + "::".join(parts) + "@" + "::".join(scope)


def parse_idl_files(paths: list[Path]) -> dict[tuple[str, ...], IdlStruct]:
    structs: dict[tuple[str, ...], IdlStruct] = {}
    typedefs: dict[tuple[str, ...], str] = {}
    for path in paths:
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as error:
            raise ParseError(f"{path}: cannot read: {error.strerror}") from error
        parser = IdlParser(text, path)
        parser.parse()
        for struct in parser.structs:
            if struct.scoped_name in structs:
                raise ParseError(f"{struct.location}: struct {struct.idl_name} defined twice "
                                 f"(first at {structs[struct.scoped_name].location})")
            structs[struct.scoped_name] = struct
        typedefs.update(parser.typedefs)
    for struct in structs.values():
        for member in struct.members:
            member.type = idl_type_to_ros(member.type, structs, typedefs, struct, member)
    return structs


def resolve_scoped(reference: str, structs, typedefs) -> tuple[str, ...] | None:
    """IDL name lookup: a relative name is searched from the innermost enclosing scope out."""
    name, _, scope_text = reference.partition("@")
    parts = tuple(name.split("::"))
    scope = tuple(scope_text.split("::")) if scope_text else ()
    for depth in range(len(scope), -1, -1):
        candidate = scope[:depth] + parts
        if candidate in structs or candidate in typedefs:
            return candidate
    return None


def idl_type_to_ros(idl_type: str, structs, typedefs, struct: IdlStruct, member: Field) -> str:
    def fail(message: str) -> ParseError:
        return ParseError(f"{struct.path}:{member.line}: {struct.idl_name}.{member.name}: {message}")

    array = re.fullmatch(r"(.*)\[(\d+)\]", idl_type, re.DOTALL)
    if array:
        element = idl_type_to_ros(array.group(1), structs, typedefs, struct, member)
        if "[" in element:
            raise fail("arrays of arrays or sequences have no ROS equivalent")
        return f"{element}[{array.group(2)}]"
    sequence = re.fullmatch(r"sequence<(.*?)(?:,(\d+))?>", idl_type, re.DOTALL)
    if sequence:
        element = idl_type_to_ros(sequence.group(1), structs, typedefs, struct, member)
        if "[" in element:
            raise fail("sequences of arrays or sequences have no ROS equivalent")
        return f"{element}[<={sequence.group(2)}]" if sequence.group(2) else f"{element}[]"
    bounded_string = re.fullmatch(r"(w?string)<(\d+)>", idl_type)
    if bounded_string:
        return f"{bounded_string.group(1)}<={bounded_string.group(2)}"
    if idl_type in IDL_TO_ROS_PRIMITIVE:
        return IDL_TO_ROS_PRIMITIVE[idl_type]
    if idl_type.startswith("scoped:"):
        target = resolve_scoped(idl_type[len("scoped:"):], structs, typedefs)
        if target is None:
            raise fail(f"type {idl_type[len('scoped:'):].split('@')[0]} is not defined in the IDL files read")
        if target in typedefs:
            return idl_type_to_ros(typedefs[target], structs, typedefs, struct, member)
        return ros_name_of_struct(target, fail)
    raise fail(f"cannot map IDL type {idl_type!r} to ROS")


def ros_name_of_struct(scoped_name: tuple[str, ...], fail=None) -> str:
    """pkg::msg::dds_::Name_ -> pkg/Name, the ROS field type that refers to the struct."""
    if len(scoped_name) != 4 or scoped_name[1] != "msg" or scoped_name[2] != "dds_" or not scoped_name[3].endswith("_"):
        message = (f"{'::'.join(scoped_name)} is not named pkg::msg::dds_::Name_, so no ROS message "
                   "type corresponds to it")
        raise fail(message) if fail else ParseError(message)
    return f"{scoped_name[0]}/{scoped_name[3][:-1]}"


# --- ROS .msg / .srv ------------------------------------------------------------------------

ROS_CONSTANT = re.compile(r"^(?P<type>\S+)\s+(?P<name>[A-Za-z][A-Za-z0-9_]*)\s*=(?P<value>.*)$")
ROS_FIELD = re.compile(
    r"^(?P<type>[A-Za-z][A-Za-z0-9_]*(?:/[A-Za-z][A-Za-z0-9_]*)?(?:<=\d+)?(?:\[(?:<=)?\d*\])?)"
    r"\s+(?P<name>\S+)(?:\s+(?P<default>\S.*))?$"
)


def normalize_ros_type(type_name: str) -> str:
    """Spells a field type the one way the comparison uses: nested types as pkg/Name."""
    match = re.fullmatch(r"([^\[]+)(\[.*\])?", type_name)
    base, array = match.group(1), match.group(2) or ""
    if base.split("<=")[0] in ROS_PRIMITIVES:
        return base + array
    if "/" not in base:
        # rosidl: a bare Header is std_msgs/Header; any other bare name is in the own package.
        base = "std_msgs/Header" if base == "Header" else f"{PACKAGE}/{base}"
    return base + array


def parse_ros_interface(path: Path, problems: list[str]) -> RosInterface:
    try:
        raw = path.read_bytes()
    except OSError as error:
        raise ParseError(f"{path}: cannot read: {error.strerror}") from error
    try:
        text = raw.decode("ascii")
    except UnicodeDecodeError as error:
        line = raw[: error.start].count(b"\n") + 1
        problems.append(f"{path}:{line}: non-ASCII character; rosidl and rosbag tools on some systems "
                        "fail on it, even in comments (write N*m, rad/s^2, us)")
        text = raw.decode("utf-8", errors="replace")
    kind = path.suffix[1:]
    sections: list[list[Field]] = [[]]
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if kind == "srv" and stripped == "---":
            sections.append([])
            continue
        constant = ROS_CONSTANT.match(stripped)
        if constant:
            if not ROS_CONSTANT_NAME.match(constant.group("name")):
                problems.append(f"{path}:{number}: constant name {constant.group('name')!r} breaks the rosidl "
                                "rule (UPPER_CASE)")
            if constant.group("type") not in ROS_PRIMITIVES:
                problems.append(f"{path}:{number}: constant type {constant.group('type')!r} is not primitive")
            continue
        content = stripped.split("#", 1)[0].strip()
        if not content:
            continue
        field = ROS_FIELD.match(content)
        if field is None:
            raise ParseError(f"{path}:{number}: cannot read {content!r} as a field or constant")
        name = field.group("name")
        if not ROS_FIELD_NAME.match(name):
            problems.append(f"{path}:{number}: field name {name!r} breaks the rosidl rule (lower_snake_case, "
                            "no double or trailing underscore)")
        sections[-1].append(Field(normalize_ros_type(field.group("type")), name, number))
    expected_sections = 2 if kind == "srv" else 1
    if len(sections) != expected_sections:
        raise ParseError(f"{path}: has {len(sections) - 1} '---' separators, expected {expected_sections - 1}")
    if not ROS_MESSAGE_NAME.match(path.stem):
        problems.append(f"{path}: interface name {path.stem!r} breaks the rosidl rule (CamelCase)")
    return RosInterface(kind, path.stem, sections, path)


def parse_package(package_dir: Path, problems: list[str]) -> dict[str, RosInterface]:
    interfaces = {}
    for kind in ("msg", "srv"):
        for path in sorted((package_dir / kind).glob(f"*.{kind}")):
            interfaces[f"{PACKAGE}/{kind}/{path.stem}"] = parse_ros_interface(path, problems)
    return interfaces


# --- comparison -----------------------------------------------------------------------------


def field_lines(fields: list[Field]) -> list[str]:
    return [f"{field.type} {field.name}" for field in fields]


def compare_fields(title: str, idl_label: str, idl_fields: list[Field], ros_label: str, ros_fields: list[Field],
                   problems: list[str]) -> None:
    idl_lines, ros_lines = field_lines(idl_fields), field_lines(ros_fields)
    if idl_lines == ros_lines:
        return
    diff = difflib.unified_diff(idl_lines, ros_lines, fromfile=idl_label, tofile=ros_label, lineterm="", n=99)
    first = next(i for i in range(max(len(idl_lines), len(ros_lines)))
                 if i >= len(idl_lines) or i >= len(ros_lines) or idl_lines[i] != ros_lines[i])
    idl_at = f"`{idl_lines[first]}`" if first < len(idl_lines) else "nothing"
    ros_at = f"`{ros_lines[first]}`" if first < len(ros_lines) else "nothing"
    details = [f"{title}: fields differ ({len(idl_lines)} in the IDL, {len(ros_lines)} in ROS; first difference at "
               f"field {first + 1}: IDL {idl_at}, ROS {ros_at}); '-' only in the IDL, '+' only in ROS:"]
    details += [f"    {line}" for line in diff]
    problems.append("\n".join(details))


def expected_structs(interface: RosInterface) -> list[tuple[tuple[str, ...], list[Field]]]:
    if interface.kind == "msg":
        return [((PACKAGE, "msg", "dds_", f"{interface.name}_"), interface.sections[0])]
    return [((PACKAGE, "srv", "dds_", f"{interface.name}_Request_"), interface.sections[0]),
            ((PACKAGE, "srv", "dds_", f"{interface.name}_Response_"), interface.sections[1])]


def check_service_header(struct: IdlStruct, problems: list[str]) -> list[Field]:
    """Returns the members after the header; reports a missing or wrong header."""
    head = [(member.type, member.name) for member in struct.members[: len(SERVICE_HEADER)]]
    if head != SERVICE_HEADER:
        wanted = "; ".join(f"{t} {n}" for t, n in SERVICE_HEADER)
        found = "; ".join(f"{t} {n}" for t, n in head) or "nothing"
        problems.append(f"{struct.idl_name} ({struct.location}): must start with the rmw_cyclonedds request "
                        f"header `{wanted};` but starts with `{found}` - rmw_cyclonedds peers would misread "
                        "every field")
        return [member for member in struct.members if (member.type, member.name) not in SERVICE_HEADER]
    return struct.members[len(SERVICE_HEADER):]


def compare(structs: dict[tuple[str, ...], IdlStruct], interfaces: dict[str, RosInterface],
            problems: list[str]) -> None:
    matched: set[tuple[str, ...]] = set()
    for ros_name, interface in interfaces.items():
        for scoped_name, ros_fields in expected_structs(interface):
            struct = structs.get(scoped_name)
            idl_name = "::".join(scoped_name)
            if struct is None:
                problems.append(f"{ros_name} ({interface.path}): no IDL struct {idl_name}; add it to the IDL "
                                "or remove the file")
                continue
            matched.add(scoped_name)
            idl_fields = struct.members
            if interface.kind == "srv":
                idl_fields = check_service_header(struct, problems)
            half = "" if interface.kind == "msg" else ("request" if scoped_name[-1].endswith("_Request_")
                                                       else "response")
            title = f"{ros_name}{' ' + half if half else ''}"
            compare_fields(title, f"IDL {idl_name} ({struct.location})", idl_fields,
                           f"ROS {interface.path}{' ' + half if half else ''}", ros_fields, problems)

    for scoped_name, struct in sorted(structs.items()):
        if scoped_name[0] != PACKAGE or scoped_name in matched:
            continue
        problems.append(f"{struct.idl_name} ({struct.location}): no ROS counterpart; expected "
                        f"{ros_file_for(scoped_name)}")


def ros_file_for(scoped_name: tuple[str, ...]) -> str:
    kind, name = scoped_name[1], scoped_name[-1]
    if kind == "srv":
        name = re.sub(r"_(Request|Response)_$", "", name)
        return f"srv/{name}.srv (with a '---' between request and response)"
    if kind == "msg":
        return f"msg/{name.rstrip('_')}.msg"
    return f"a module {PACKAGE}::msg::dds_ or {PACKAGE}::srv::dds_ struct (found module {kind})"


def check_standard_types(structs: dict[tuple[str, ...], IdlStruct], problems: list[str]) -> None:
    for scoped_name, struct in sorted(structs.items()):
        if scoped_name[0] == PACKAGE:
            continue
        ros_name = f"{scoped_name[0]}/{scoped_name[1]}/{scoped_name[-1].rstrip('_')}"
        upstream = STANDARD_ROS_TYPES.get(ros_name)
        if upstream is None:
            problems.append(f"{struct.idl_name} ({struct.location}): a standard ROS type the checker does not "
                            "know; add its upstream ROS 2 definition to STANDARD_ROS_TYPES in "
                            f"{Path(__file__).name}")
            continue
        compare_fields(ros_name, f"IDL {struct.idl_name} ({struct.location})", struct.members,
                       f"upstream ROS 2 {ros_name}", [Field(t, n, 0) for t, n in upstream], problems)


def check_package_files(package_dir: Path, interfaces: dict[str, RosInterface], problems: list[str]) -> None:
    cmake_path = package_dir / "CMakeLists.txt"
    try:
        cmake = re.sub(r"#[^\n]*", "", cmake_path.read_text(encoding="utf-8"))
    except OSError as error:
        raise ParseError(f"{cmake_path}: cannot read: {error.strerror}") from error
    call = re.search(r"rosidl_generate_interfaces\s*\((.*?)\)", cmake, re.DOTALL)
    if call is None:
        problems.append(f"{cmake_path}: no rosidl_generate_interfaces() call")
        return
    words = [word.strip('"') for word in call.group(1).split()]
    listed = {word for word in words if re.fullmatch(r"(msg|srv)/\w+\.(msg|srv)", word)}
    present = {f"{i.kind}/{i.name}.{i.kind}" for i in interfaces.values()}
    for missing in sorted(present - listed):
        problems.append(f"{cmake_path}: rosidl_generate_interfaces does not list {missing}; ROS would not "
                        "generate it")
    for stale in sorted(listed - present):
        problems.append(f"{cmake_path}: rosidl_generate_interfaces lists {stale}, which does not exist")
    dependencies = set()
    if "DEPENDENCIES" in words:
        for word in words[words.index("DEPENDENCIES") + 1:]:
            if word.isupper():  # the next keyword argument, e.g. ADD_LINTER_TESTS
                break
            dependencies.add(word)

    package_xml = package_dir / "package.xml"
    try:
        root = ElementTree.parse(package_xml).getroot()
    except (OSError, ElementTree.ParseError) as error:
        raise ParseError(f"{package_xml}: cannot read: {error}") from error
    if root.findtext("name") != PACKAGE:
        problems.append(f"{package_xml}: <name> is {root.findtext('name')!r}, expected {PACKAGE!r}")
    xml_depends = {element.text for tag in ("depend", "build_depend") for element in root.iter(tag)}

    used = set()
    for interface in interfaces.values():
        for fields in interface.sections:
            for field in fields:
                if "/" in field.type:
                    used.add(field.type.split("/")[0])
                    if field.type.split("/")[0] == PACKAGE:
                        target = f"{PACKAGE}/msg/{field.type.split('/')[1].split('[')[0]}"
                        if target not in interfaces:
                            problems.append(f"{interface.path}:{field.line}: {field.type} {field.name}: no "
                                            f"msg/{target.rsplit('/', 1)[1]}.msg in the package")
    for package in sorted(used - {PACKAGE}):
        if package not in dependencies:
            problems.append(f"{cmake_path}: fields use {package} but rosidl_generate_interfaces has no "
                            f"DEPENDENCIES {package}")
        if package not in xml_depends:
            problems.append(f"{package_xml}: fields use {package} but there is no <depend>{package}</depend>")


def check(idl_files: list[Path], package_dir: Path) -> list[str]:
    """Every difference between the IDL and the ROS package, as readable paragraphs."""
    problems: list[str] = []
    structs = parse_idl_files(idl_files)
    interfaces = parse_package(package_dir, problems)
    if not interfaces:
        problems.append(f"{package_dir}: no msg/*.msg or srv/*.srv files")
    compare(structs, interfaces, problems)
    check_standard_types(structs, problems)
    check_package_files(package_dir, interfaces, problems)
    return problems


def main(argv: list[str]) -> int:
    repo = Path(__file__).resolve().parents[2]
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--idl-dir", type=Path, default=repo / "idl",
                        help="directory holding ros_common.idl and robotd_msgs.idl (default: %(default)s)")
    parser.add_argument("--package-dir", type=Path, default=repo / "idl" / "ros2" / PACKAGE,
                        help="the ROS 2 interface package (default: %(default)s)")
    args = parser.parse_args(argv)
    idl_files = [args.idl_dir / "ros_common.idl", args.idl_dir / "robotd_msgs.idl"]
    try:
        problems = check(idl_files, args.package_dir)
    except ParseError as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    if problems:
        print(f"The ROS 2 package {args.package_dir} does not match the IDL in {args.idl_dir}:\n", file=sys.stderr)
        for problem in problems:
            print(f"- {problem}\n", file=sys.stderr)
        print(f"{len(problems)} problem(s). Change the IDL and the .msg/.srv together.", file=sys.stderr)
        return 1
    print(f"OK: {args.package_dir} matches {', '.join(str(path) for path in idl_files)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
