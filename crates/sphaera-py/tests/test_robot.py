"""Robots into the planners and the simulator: the MJCF loaded by MuJoCo (PyPI `mujoco`)
poses the spheres exactly where our kinematics puts them and they cover MuJoCo's posed
meshes; the self-collision matrix, the cuRobo file and the SRDF agree with it."""

import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest
from conftest import required

import sphaera

ROBOTS = {
    "panda": ("franka_panda", "panda.urdf"),
    "kuka": ("kuka_iiwa", "model.urdf"),
}


def robot_path(data_dir, name):
    folder, file = ROBOTS[name]
    return data_dir / "robots" / "urdf" / folder / file


GENERATED = """<robot name="generated">
  <link name="world"/>
  <link name="base"><inertial><origin xyz="0 0 0.05" rpy="0.3 0 0"/><mass value="2"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.03"/></inertial>
    <collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="turntable"><collision><origin xyz="0 0 0.05"/><geometry><cylinder radius="0.08" length="0.1"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0 0 0.2"/><geometry><capsule radius="0.04" length="0.3"/></geometry></collision></link>
  <link name="flange"/>
  <link name="finger_a"><collision><origin xyz="0 0 0.03"/><geometry><box size="0.01 0.02 0.06"/></geometry></collision></link>
  <link name="finger_b"><collision><origin xyz="0 0 0.03"/><geometry><box size="0.01 0.02 0.06"/></geometry></collision></link>
  <joint name="float" type="floating"><parent link="world"/><child link="base"/></joint>
  <joint name="turn" type="continuous"><parent link="base"/><child link="turntable"/><origin xyz="0 0 0.05" rpy="0 0 0.4"/><axis xyz="0 0 1"/></joint>
  <joint name="shoulder" type="revolute"><parent link="turntable"/><child link="upper"/><origin xyz="0 0.02 0.1" rpy="0.1 0 0"/><axis xyz="0 1 0"/><limit lower="-1.5" upper="1.5"/></joint>
  <joint name="wrist" type="fixed"><parent link="upper"/><child link="flange"/><origin xyz="0 0 0.4" rpy="0 0.3 0"/></joint>
  <joint name="grip_a" type="prismatic"><parent link="flange"/><child link="finger_a"/><origin xyz="0.02 0 0"/><axis xyz="1 0 0"/><limit lower="0" upper="0.04"/></joint>
  <joint name="grip_b" type="prismatic"><parent link="flange"/><child link="finger_b"/><origin xyz="-0.02 0 0"/><axis xyz="1 0 0"/><limit lower="-0.08" upper="0"/><mimic joint="grip_a" multiplier="-2" offset="0.01"/></joint>
</robot>
"""


@pytest.mark.parametrize("name", sorted(ROBOTS) + ["generated"])
def test_mujoco_poses_our_spheres_and_they_cover_the_meshes(data_dir, tmp_path, name):
    mujoco = required("mujoco")
    if name == "generated":
        # A robot nobody tuned for: a free base, continuous, revolute, fixed, prismatic and
        # mimic joints, primitives only.
        path = tmp_path / "generated.urdf"
        path.write_text(GENERATED)
    else:
        path = robot_path(data_dir, name)
    robot = sphaera.urdf(path, spheres_per_link=12, format="mjcf", mjcf_meshes=True, self_collision_samples=2_000)
    model_file = tmp_path / "robot.xml"
    model_file.write_text(robot["text"])
    model = mujoco.MjModel.from_xml_path(str(model_file))
    data = mujoco.MjData(model)
    disabled = [p for p in robot["self_collision"] if p["reason"] is not None]
    assert model.nexclude == len(disabled)
    sphere_geoms = {}
    for g in range(model.ngeom):
        if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_SPHERE:
            link, k = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g).rsplit("/sphere", 1)
            sphere_geoms[(link, int(k))] = g
    assert len(sphere_geoms) == sum(len(link["spheres"]) for link in robot["links"].values())
    joints = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j) for j in range(model.njnt)]
    rng = np.random.default_rng(7)
    checked_vertices = 0
    mimics = mimic_joints(path)
    for trial in range(6):
        values = {}
        for j, joint in enumerate(joints):
            if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE:
                continue  # the free base stays where the model puts it, as link_poses does
            low, high = model.jnt_range[j] if model.jnt_limited[j] else (-np.pi, np.pi)
            values[joint] = rng.uniform(low, high) if trial else 0.0
        # A mimic joint as the URDF ties it (MuJoCo's equality holds it only as the
        # simulation settles); our kinematics gets the drivers alone.
        for joint, (driver, multiplier, offset) in mimics.items():
            values[joint] = multiplier * values[driver] + offset
        for j, joint in enumerate(joints):
            if joint in values:
                data.qpos[model.jnt_qposadr[j]] = values[joint]
        mujoco.mj_forward(model, data)
        poses = sphaera.link_poses(path, {j: v for j, v in values.items() if j not in mimics})
        for (link, k), g in sphere_geoms.items():
            center = robot["links"][link]["spheres"][k, :3]
            ours = poses[link][:3, :3] @ center + poses[link][:3, 3]
            np.testing.assert_allclose(data.geom_xpos[g], ours, atol=1e-9, err_msg=f"{name} {link} {k}")
            assert model.geom_size[g, 0] == pytest.approx(robot["links"][link]["spheres"][k, 3], rel=1e-12)
        # Every vertex of MuJoCo's posed meshes lies in a sphere of its body.
        for g in range(model.ngeom):
            if model.geom_type[g] != mujoco.mjtGeom.mjGEOM_MESH:
                continue
            body = model.geom_bodyid[g]
            mesh = model.geom_dataid[g]
            start, count = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
            vertices = data.geom_xpos[g] + model.mesh_vert[start : start + count] @ data.geom_xmat[g].reshape(3, 3).T
            own = [s for s in range(model.ngeom) if model.geom_bodyid[s] == body and model.geom_type[s] == mujoco.mjtGeom.mjGEOM_SPHERE]
            gaps = np.linalg.norm(vertices[:, None, :] - data.geom_xpos[own][None, :, :], axis=2) - model.geom_size[own, 0][None, :]
            assert gaps.min(axis=1).max() <= 1e-6, f"{name}: a vertex of {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body)} is bare"
            checked_vertices += count
    assert checked_vertices > 1000 or name == "generated"


def mimic_joints(path):
    """The URDF's mimic joints (read here, not by sphaera): joint -> (driver, multiplier, offset)."""
    root = ElementTree.parse(path).getroot()
    found = {}
    for joint in root.iter("joint"):
        mimic = joint.find("mimic")
        if mimic is not None:
            found[joint.get("name")] = (
                mimic.get("joint"),
                float(mimic.get("multiplier", 1.0)),
                float(mimic.get("offset", 0.0)),
            )
    return found


def test_the_matrix_leaves_out_adjacent_pairs_and_the_files_carry_it(data_dir):
    path = robot_path(data_dir, "panda")
    robot = sphaera.urdf(path, spheres_per_link=8, format="srdf", self_collision_samples=1_000)
    pairs = robot["self_collision"]
    links = list(robot["links"])
    assert len(pairs) == len(links) * (len(links) - 1) // 2
    root = ElementTree.parse(path).getroot()
    for joint in root.iter("joint"):
        parent, child = joint.find("parent").get("link"), joint.find("child").get("link")
        if parent in robot["links"] and child in robot["links"]:
            (pair,) = [p for p in pairs if {p["first"], p["second"]} == {parent, child}]
            assert pair["reason"] == "Adjacent"
    srdf = ElementTree.fromstring(robot["text"])
    written = {(e.get("link1"), e.get("link2"), e.get("reason")) for e in srdf.iter("disable_collisions")}
    assert written == {(p["first"], p["second"], p["reason"]) for p in pairs if p["reason"]}
    # The same seed, the same matrix; the cuRobo file lists the same pairs.
    again = sphaera.urdf(path, spheres_per_link=8, format="curobo", self_collision_samples=1_000)
    assert again["self_collision"] == pairs
    assert "self_collision_ignore:" in again["text"] and "retract_config:" in again["text"]


def test_link_poses_follow_the_joints(data_dir):
    path = robot_path(data_dir, "kuka")
    rest = sphaera.link_poses(path)
    np.testing.assert_allclose(rest["lbr_iiwa_link_0"], np.eye(4))
    turned = sphaera.link_poses(path, {"lbr_iiwa_joint_1": np.pi / 2})
    # The first joint turns about the base's z axis: everything above it turns too.
    rotation = turned["lbr_iiwa_link_7"][:3, :3] @ rest["lbr_iiwa_link_7"][:3, :3].T
    np.testing.assert_allclose(rotation @ [1, 0, 0], [0, 1, 0], atol=1e-12)
    with pytest.raises(ValueError, match="no joint"):
        sphaera.link_poses(path, {"elbow": 1.0})
    with pytest.raises(ValueError, match="not finite"):
        sphaera.link_poses(path, {"lbr_iiwa_joint_1": float("nan")})
    with pytest.raises(ValueError, match="planner format"):
        sphaera.urdf(path, spheres_per_link=2, format="sdf")
