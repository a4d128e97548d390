#!/usr/bin/env python3
"""Writes the <visual> geometry of lang2manip's built-in robots (data/models/robots/*/*.urdf)
from their collision models and kinematics, so that they read as the real arms: each capsule's
tube slightly slimmer than its collision capsule, a drum on every joint axis where a capsule ends
at a joint (a cylinder along the axis, with caps of the maker's accent colour on both faces),
and the maker's colours. The collision geometry is not touched. Run it after changing a model's
collision geometry or joints:

    python3 scripts/dress-builtin-robots.py data/models/robots/*/*.urdf
"""
import math
import re
import sys
import xml.etree.ElementTree as ET

# body, drum and cap colours (RGB), and the gripper's body and finger colours, per robot name.
PALETTES = {
    "panda": {"body": (0.95, 0.95, 0.95), "drum": (0.93, 0.93, 0.93), "cap": (0.16, 0.16, 0.17),
              "hand": (0.92, 0.92, 0.92), "finger": (0.18, 0.18, 0.19)},
    "ur5": {"body": (0.78, 0.80, 0.82), "drum": (0.86, 0.87, 0.88), "cap": (0.36, 0.66, 0.84),
            "hand": (0.25, 0.25, 0.27), "finger": (0.55, 0.56, 0.58)},
    "iiwa14": {"body": (0.88, 0.88, 0.86), "drum": (0.90, 0.90, 0.88), "cap": (0.97, 0.45, 0.05),
               "hand": (0.25, 0.25, 0.27), "finger": (0.55, 0.56, 0.58)},
    "tx90": {"body": (0.93, 0.93, 0.90), "drum": (0.93, 0.93, 0.90), "cap": (0.95, 0.75, 0.10),
             "hand": (0.25, 0.25, 0.27), "finger": (0.55, 0.56, 0.58)},
    "yumi": {"body": (0.82, 0.83, 0.84), "drum": (0.88, 0.88, 0.89), "cap": (0.30, 0.31, 0.33),
             "hand": (0.80, 0.80, 0.80), "finger": (0.25, 0.25, 0.27)},
}
TUBE_SCALE = 0.92          # tube radius / collision capsule radius
DRUM_LENGTH = 1.9          # drum length / capsule radius
CAP_RADIUS = 0.72          # cap radius / capsule radius
CAP_THICKNESS = 0.006      # m
GRIPPER_WORDS = ("finger", "hand", "gripper", "tcp", "tool")


def numbers(text, count=3):
    values = [float(v) for v in (text or "").split()]
    return values if values else [0.0] * count


def rotation(rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def apply(matrix, vector):
    return [sum(matrix[i][k] * vector[k] for k in range(3)) for i in range(3)]


def rpy_along(axis):
    """Roll and pitch turning a cylinder's z axis onto `axis` (unit)."""
    x, y, z = axis
    return (-math.asin(max(-1.0, min(1.0, y))), math.atan2(x, z), 0.0)


def fmt(values):
    return " ".join(f"{v:.6g}" if abs(v) > 1e-12 else "0" for v in values)


def distance(a, b):
    return math.sqrt(sum((a[i] - b[i]) ** 2 for i in range(3)))


class Writer:
    def __init__(self, robot):
        self.robot = robot
        self.lines = []

    def visual(self, name, xyz, rpy, geometry, material):
        self.lines += [f'    <visual name="{name}">',
                       f'      <origin xyz="{fmt(xyz)}" rpy="{fmt(rpy)}"/>',
                       f"      <geometry>{geometry}</geometry>",
                       f'      <material name="{self.robot}_{material}"/>',
                       "    </visual>"]


def joint_frames(root):
    """Per link: the joints at it, as (origin in the link's frame, axis in the link's frame)."""
    frames = {}
    for joint in root.findall("joint"):
        if joint.get("type") in ("fixed", "floating", "planar"):
            continue
        origin = joint.find("origin")
        xyz = numbers(origin.get("xyz") if origin is not None else None)
        rpy = numbers(origin.get("rpy") if origin is not None else None)
        axis_element = joint.find("axis")
        axis = numbers(axis_element.get("xyz") if axis_element is not None else "1 0 0")
        parent, child = joint.find("parent").get("link"), joint.find("child").get("link")
        frames.setdefault(child, []).append(([0.0, 0.0, 0.0], axis))
        frames.setdefault(parent, []).append((xyz, apply(rotation(rpy), axis)))
    return frames


def capsules(link):
    """(name, radius, end a, end b, cylinder origin element) of every capsule of a link."""
    found = {}
    for collision in link.findall("collision"):
        match = re.fullmatch(r"(capsule\d+)_(cylinder|a|b)", collision.get("name") or "")
        if match:
            found.setdefault(match.group(1), {})[match.group(2)] = collision
    result = []
    for name, parts in sorted(found.items()):
        if set(parts) != {"cylinder", "a", "b"}:
            continue
        radius = float(parts["a"].find("geometry/sphere").get("radius"))
        ends = [numbers(parts[e].find("origin").get("xyz")) for e in ("a", "b")]
        result.append((name, radius, ends[0], ends[1], parts["cylinder"]))
    return result


def dress_link(link, joints, writer, palette_is_gripper):
    name = link.get("name")
    gripper = palette_is_gripper
    body = "finger" if gripper and "finger" in name else "hand" if gripper else "body"
    drums = []
    for capsule, radius, a, b, cylinder in capsules(link):
        origin = cylinder.find("origin")
        geometry = cylinder.find("geometry/cylinder")
        writer.visual(f"{capsule}_tube", numbers(origin.get("xyz")), numbers(origin.get("rpy")),
                      f'<cylinder radius="{radius * TUBE_SCALE:.6g}" length="{float(geometry.get("length")):.6g}"/>', body)
        for end, point in (("a", a), ("b", b)):
            at_joint = next(((xyz, axis) for xyz, axis in joints if distance(xyz, point) < radius), None)
            if at_joint is None or gripper:
                writer.visual(f"{capsule}_{end}", point, (0, 0, 0), f'<sphere radius="{radius * TUBE_SCALE:.6g}"/>', body)
            else:
                drums.append((f"{capsule}_{end}", point, at_joint, radius))
    for label, end, (joint_origin, axis), radius in drums:
        norm = math.sqrt(sum(c * c for c in axis)) or 1.0
        unit = [c / norm for c in axis]
        rpy = rpy_along(unit)
        # On the joint's axis, beside the capsule's end.
        along = sum((end[i] - joint_origin[i]) * unit[i] for i in range(3))
        point = [joint_origin[i] + along * unit[i] for i in range(3)]
        length = DRUM_LENGTH * radius
        writer.visual(f"{label}_drum", point, rpy, f'<cylinder radius="{radius:.6g}" length="{length:.6g}"/>', "drum")
        for side in (1, -1):
            centre = [point[i] + side * unit[i] * (length / 2 + CAP_THICKNESS / 2) for i in range(3)]
            writer.visual(f"{label}_cap{'+' if side > 0 else '-'}", centre, rpy,
                          f'<cylinder radius="{CAP_RADIUS * radius:.6g}" length="{CAP_THICKNESS:.6g}"/>', "cap")
    for collision in link.findall("collision"):
        if re.fullmatch(r"capsule\d+_(cylinder|a|b)", collision.get("name") or ""):
            continue
        origin = collision.find("origin")
        geometry = ET.tostring(collision.find("geometry")[0], encoding="unicode").strip()
        writer.visual(collision.get("name") or "shape", numbers(origin.get("xyz") if origin is not None else None),
                      numbers(origin.get("rpy") if origin is not None else None), geometry, body)


def dress(path):
    text = open(path).read()
    root = ET.fromstring(text)
    robot = root.get("name")
    palette = PALETTES[robot]
    frames = joint_frames(root)
    for link in root.findall("link"):
        name = link.get("name")
        if link.find("collision") is None:
            continue
        writer = Writer(robot)
        dress_link(link, frames.get(name, []), writer, any(word in name for word in GRIPPER_WORDS))
        block = re.compile(r'(  <link name="' + re.escape(name) + r'">\n)(.*?)(  </link>\n)', re.S)
        found = block.search(text)
        inner = re.sub(r"    <visual\b.*?</visual>\n", "", found.group(2), flags=re.S)
        first = inner.find("    <collision")
        inner = inner[:first] + "\n".join(writer.lines) + "\n" + inner[first:]
        text = text[:found.start(2)] + inner + text[found.end(2):]
    materials = "".join(f'  <material name="{robot}_{part}"><color rgba="{fmt(rgb)} 1"/></material>\n'
                        for part, rgb in palette.items())
    text = re.sub(r'  <material name="[^"]*"><color rgba="[^"]*"/></material>\n', "", text)
    text = re.sub(r'(<robot name="[^"]*">\n)', lambda m: m.group(1) + materials, text, count=1)
    open(path, "w").write(text)


if __name__ == "__main__":
    for argument in sys.argv[1:]:
        dress(argument)
