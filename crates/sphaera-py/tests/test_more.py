"""HAL approximations, silhouette labels and URDF robots from Python."""

import pickle

import numpy as np
import pytest

import sphaera
from conftest import uv_sphere


def test_hal_levels_and_tolerances(ball):
    root, depth = sphaera.hal(ball)
    assert 2 <= root.triangle_count < ball.triangle_count
    assert depth >= 1
    finest, _ = sphaera.hal(ball, level=depth)
    assert finest.triangle_count == ball.triangle_count
    coarse, _ = sphaera.hal(ball, tolerance="5%")
    assert root.triangle_count <= coarse.triangle_count <= ball.triangle_count
    # A HAL approximation uses the mesh's own vertices.
    mine = {tuple(v) for v in ball.vertices}
    assert all(tuple(v) in mine for v in coarse.vertices[np.unique(coarse.faces)])


def test_hal_refuses_what_is_not_genus_zero():
    vertices, faces = uv_sphere()
    two = sphaera.Mesh(
        np.vstack([vertices, vertices + 5]), np.vstack([faces, faces + len(vertices)])
    )
    with pytest.raises(ValueError, match="component|piece|genus"):
        sphaera.hal(two)
    with pytest.raises(ValueError, match="not a length"):
        sphaera.hal(sphaera.Mesh(vertices, faces), tolerance="wide")


def test_silhouette_labels_per_view_and_vertex(ball):
    labels, directions = sphaera.silhouette_labels(ball, step_degrees=45, resolution=64)
    assert labels.dtype == np.float32 and labels.shape[1] == ball.vertex_count
    assert directions.shape == (labels.shape[0], 3)
    np.testing.assert_allclose(np.linalg.norm(directions, axis=1), 1.0, atol=1e-12)
    # On a ball the outline of each view is the great circle across the view: vertices
    # near it get small labels, the one facing the camera the largest.
    for k in range(labels.shape[0]):
        facing = np.argmax(ball.vertices @ directions[k])
        assert labels[k, facing] == pytest.approx(labels[k].max(), rel=0.2)
        across = np.argmin(np.abs(ball.vertices @ directions[k]))
        assert labels[k, across] <= 2.0
    with pytest.raises(ValueError):
        sphaera.silhouette_labels(ball, step_degrees=7)


def test_silhouette_labels_are_kept_in_a_label_file(ball, tmp_path):
    path = tmp_path / "ball.labels"
    labels, directions = sphaera.silhouette_labels(ball, step_degrees=45, resolution=32, labels_file=path)
    written = path.read_bytes()
    # 80-byte header, 2 bytes per label, 8-byte checksum.
    assert len(written) == 80 + 2 * labels.size + 8
    again, again_directions = sphaera.silhouette_labels(
        ball, step_degrees=45, resolution=32, labels_file=str(path), root=tmp_path
    )
    np.testing.assert_array_equal(again, labels)
    np.testing.assert_array_equal(again_directions, directions)
    assert path.read_bytes() == written

    # Other settings, another mesh, a damaged file: refused by name, the file kept.
    with pytest.raises(ValueError, match="step 45°, not 30°"):
        sphaera.silhouette_labels(ball, resolution=32, labels_file=path)
    with pytest.raises(ValueError, match="resolution 32, not 64"):
        sphaera.silhouette_labels(ball, step_degrees=45, resolution=64, labels_file=path)
    with pytest.raises(ValueError, match="contours outline, not all"):
        sphaera.silhouette_labels(
            ball, step_degrees=45, resolution=32, outline_only=False, labels_file=path
        )
    vertices, faces = uv_sphere(radius=2.0)
    with pytest.raises(ValueError, match="another mesh"):
        sphaera.silhouette_labels(
            sphaera.Mesh(vertices, faces), step_degrees=45, resolution=32, labels_file=path
        )
    assert path.read_bytes() == written
    damaged = bytearray(written)
    damaged[len(damaged) // 2] ^= 1
    path.write_bytes(bytes(damaged))
    with pytest.raises(ValueError, match="checksum"):
        sphaera.silhouette_labels(ball, step_degrees=45, resolution=32, labels_file=path)

    # The file policy: a folder, a file outside the root, a file over the cap.
    with pytest.raises(PermissionError, match="not a regular file"):
        sphaera.silhouette_labels(ball, step_degrees=45, resolution=32, labels_file=tmp_path)
    path.write_bytes(written)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    with pytest.raises(PermissionError, match="outside the allowed folder"):
        sphaera.silhouette_labels(
            ball, step_degrees=45, resolution=32, labels_file=path, root=elsewhere
        )
    with pytest.raises(PermissionError, match="cap"):
        sphaera.silhouette_labels(
            ball, step_degrees=45, resolution=32, labels_file=path, max_bytes=100
        )
    # A folder that does not exist cannot take a new file.
    with pytest.raises(OSError, match="missing"):
        sphaera.silhouette_labels(
            ball, step_degrees=45, resolution=32, labels_file=tmp_path / "missing" / "x.labels"
        )


def test_a_robot_from_its_urdf(data_dir):
    robot = sphaera.urdf(data_dir / "robots" / "urdf" / "kuka_iiwa" / "model.urdf", spheres_per_link=8)
    assert robot["links"] and pickle.loads(pickle.dumps(robot)).keys() == robot.keys()
    for name, link in robot["links"].items():
        assert link["spheres"].shape[1] == 4 and 1 <= len(link["spheres"]) <= 8, name
        assert link["coverage_certified"], name
        # Spheres never fit a link's mesh exactly, and none reaches out by more than its
        # own diameter (the protrusions are measured, not defaulted).
        radii = link["spheres"][:, 3]
        assert 0 < link["p95_protrusion"] <= link["worst_protrusion"] <= 2 * radii.max(), name


def test_robot_errors_name_the_file(tmp_path):
    with pytest.raises(OSError, match="missing.urdf"):
        sphaera.urdf(tmp_path / "missing.urdf")
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='r'><link name='a'>\n<visual>\n</robot>")
    with pytest.raises(ValueError, match="bad.urdf"):
        sphaera.urdf(bad)
    with pytest.raises(ValueError, match="one of"):
        sphaera.urdf(bad, spheres_per_link=4, budget=10)
