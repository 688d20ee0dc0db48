"""HAL trees from Python: point inclusion over numpy arrays against references written
here (even-odd crossings in numpy, a ball's radius), intersection, bad input, pickling."""

import pickle

import numpy as np
import pytest

import sphaera
from conftest import share_kept_by_python, uv_sphere


def even_odd(ring, points):
    """Inside (True) by the even-odd rule, points strictly off the edges."""
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    a, b = ring, np.roll(ring, -1, axis=0)
    ax, ay, bx, by = a[:, 0], a[:, 1], b[:, 0], b[:, 1]
    straddles = (ay > y) != (by > y)
    with np.errstate(divide="ignore", invalid="ignore"):
        cross_x = ax + (y - ay) * (bx - ax) / (by - ay)
    return (np.count_nonzero(straddles & (x < cross_x), axis=1) % 2) == 1


def star(n=40, seed=3):
    rng = np.random.default_rng(seed)
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
    radii = rng.uniform(0.3, 1.0, n)
    return np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])


def test_2d_inclusion_matches_even_odd_and_reports_the_boundary():
    ring = star()
    tree = sphaera.HalTree2(ring)
    assert tree.closed and len(tree) == len(ring) and tree.depth >= 1
    rng = np.random.default_rng(5)
    points = rng.uniform(-1.1, 1.1, (2000, 2))
    answers = tree.contains(points)
    assert answers.dtype == np.int8 and answers.shape == (2000,)
    assert set(np.unique(answers)) <= {-1, 1}
    np.testing.assert_array_equal(answers == 1, even_odd(ring, points))
    # Vertices and edge midpoints are on the boundary.
    on = np.vstack([ring, (ring + np.roll(ring, -1, axis=0)) / 2])
    assert (tree.contains(on[: len(ring)]) == 0).all()
    # A list of lists works too, and no point gives an empty answer.
    assert tree.contains([[0.0, 0.0]]).tolist() == [1]
    assert tree.contains(np.zeros((0, 2))).shape == (0,)


def test_2d_intersection_and_open_polylines():
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    a = sphaera.HalTree2(square)
    assert a.intersects(sphaera.HalTree2(square + [0.5, 0.5]))
    assert not a.intersects(sphaera.HalTree2(square + [2.0, 0.0]))
    # Nested: one outline holds the other.
    assert a.intersects(sphaera.HalTree2(square * 0.2 + 0.4))
    line = sphaera.HalTree2([[-1.0, 0.5], [2.0, 0.5]], closed=False)
    assert not line.closed and line.intersects(a)
    with pytest.raises(ValueError, match="open polyline"):
        line.contains([[0.0, 0.0]])


def test_3d_inclusion_matches_a_ball_and_intersection():
    vertices, faces = uv_sphere(radius=1.0, rings=16, segments=32)
    ball = sphaera.Mesh(vertices, faces)
    tree = sphaera.HalTree3(ball)
    assert tree.depth >= 1 and tree.mesh.triangle_count == ball.triangle_count
    rng = np.random.default_rng(9)
    points = rng.uniform(-1.3, 1.3, (3000, 3))
    r = np.linalg.norm(points, axis=1)
    # The inscribed polyhedron lies between radius cos(π/16) and 1.
    clear = (r < 0.95) | (r > 1.0 + 1e-9)
    answers = tree.contains(points)
    assert answers.dtype == np.int8
    np.testing.assert_array_equal(answers[clear] == 1, r[clear] < 0.95)
    assert (tree.contains(vertices) == 0).all()
    far = sphaera.HalTree3(sphaera.Mesh(vertices + 5.0, faces))
    near = sphaera.HalTree3(sphaera.Mesh(vertices * 0.5 + 0.2, faces))
    assert not tree.intersects(far) and tree.intersects(near)


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        sphaera.HalTree2(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="finite"):
        sphaera.HalTree2([[0.0, 0.0], [1.0, np.nan], [0.0, 1.0]])
    with pytest.raises(ValueError):
        sphaera.HalTree2([[0.0, 0.0], [1.0, 0.0]])
    tree = sphaera.HalTree2(star())
    with pytest.raises(ValueError, match=r"\(n, 2\)"):
        tree.contains(np.zeros((3, 3)))
    vertices, faces = uv_sphere()
    two = sphaera.Mesh(
        np.vstack([vertices, vertices + 5]), np.vstack([faces, faces + len(vertices)])
    )
    with pytest.raises(ValueError, match="component|piece|genus"):
        sphaera.HalTree3(two)


def test_trees_pickle_and_answer_the_same():
    ring = star()
    tree = sphaera.HalTree2(ring)
    copy = pickle.loads(pickle.dumps(tree))
    points = np.random.default_rng(1).uniform(-1, 1, (200, 2))
    np.testing.assert_array_equal(copy.contains(points), tree.contains(points))
    vertices, faces = uv_sphere()
    solid = sphaera.HalTree3(sphaera.Mesh(vertices, faces))
    again = pickle.loads(pickle.dumps(solid))
    queries = np.random.default_rng(2).uniform(-1.2, 1.2, (200, 3))
    np.testing.assert_array_equal(again.contains(queries), solid.contains(queries))


def square(lo, hi):
    return np.array([[lo, lo], [hi, lo], [hi, hi], [lo, hi]], dtype=float)


def test_multipolygon_with_a_lake_and_an_island_says_where():
    land = sphaera.HalMultiPolygon2([[square(0, 10), square(4, 6)], [square(12, 13)]])
    assert land.polygon_count == 2 and len(land) == 2
    points = np.array([[1, 1], [5, 5], [12.5, 12.5], [4, 5], [20, 20]], dtype=float)
    np.testing.assert_array_equal(land.contains(points), [1, -1, 1, 0, -1])
    where = land.locate(points)
    np.testing.assert_array_equal(where["containment"], [1, -1, 1, 0, -1])
    np.testing.assert_array_equal(where["polygon"], [0, 0, 1, 0, -1])
    np.testing.assert_array_equal(where["ring"], [0, 1, 0, 1, -1])
    nearest = land.nearest_edge(points)
    np.testing.assert_allclose(nearest["distance"], [1, 1, 0.5, 0, np.hypot(7, 7)])
    assert nearest["point"].shape == (5, 2)
    np.testing.assert_array_equal(nearest["ring"][:2], [0, 1])


def test_multipolygon_against_even_odd_on_random_islands():
    rings = [star(30, seed) * 0.4 + offset for seed, offset in ((1, 0.0), (2, 1.0), (3, -1.0))]
    shape = sphaera.HalMultiPolygon2([[r] for r in rings])
    rng = np.random.default_rng(9)
    points = rng.uniform(-1.5, 1.5, (3000, 2))
    expected = np.zeros(len(points), dtype=bool)
    for r in rings:
        expected |= even_odd(r, points)
    np.testing.assert_array_equal(shape.contains(points) == 1, expected)


def test_geojson_wkt_intersection_and_pickling():
    lake = sphaera.HalMultiPolygon2.from_wkt(
        "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0), (4 4, 6 4, 6 6, 4 6, 4 4))"
    )
    same = sphaera.HalMultiPolygon2.from_geojson(
        '{"type": "Polygon", "coordinates": [[[0,0],[10,0],[10,10],[0,10],[0,0]],'
        '[[4,4],[6,4],[6,6],[4,6],[4,4]]]}'
    )
    points = np.array([[1, 1], [5, 5], [4, 4.5]], dtype=float)
    np.testing.assert_array_equal(lake.contains(points), same.contains(points))
    boat = sphaera.HalMultiPolygon2([[square(4.5, 5.5)]])
    assert not lake.intersects(boat)
    assert lake.intersecting_edges(boat).shape == (0, 6)
    road = sphaera.HalTree2(np.array([[1.0, 1.0], [2.0, 3.0]]), closed=False)
    assert lake.intersects(road), "a road inside the land meets it"
    pier = sphaera.HalTree2(np.array([[3.0, 5.0], [5.0, 5.0]]), closed=False)
    pairs = lake.intersecting_edges(pier)
    np.testing.assert_array_equal(pairs, [[0, 1, 3, -1, -1, 0]])
    square_tree = sphaera.HalTree2(square(0, 2))
    crossing = sphaera.HalTree2(np.array([[1.0, -1.0], [1.0, 1.0], [3.0, 1.0]]), closed=False)
    np.testing.assert_array_equal(square_tree.intersecting_edges(crossing), [[0, 0], [1, 1]])
    distance, edge, nearest = square_tree.nearest_edge(np.array([[1.0, 0.5]]))
    assert distance[0] == 0.5 and edge[0] == 0 and nearest.tolist() == [[1.0, 0.0]]
    again = pickle.loads(pickle.dumps(lake))
    np.testing.assert_array_equal(again.contains(points), lake.contains(points))
    assert repr(again) == "HalMultiPolygon2(1 polygons, 1 holes)"


def test_multipolygon_bad_input_is_named():
    with pytest.raises(ValueError, match="polygon 1, ring 0"):
        sphaera.HalMultiPolygon2([[square(0, 1)], [np.array([[0.0, np.nan], [1, 1], [2, 0]])]])
    with pytest.raises(ValueError, match="no polygon"):
        sphaera.HalMultiPolygon2([])
    with pytest.raises(ValueError, match="WKT"):
        sphaera.HalMultiPolygon2.from_wkt("POLYGON ((0 0,")
    with pytest.raises(ValueError, match="holds no polygon"):
        sphaera.HalMultiPolygon2.from_wkt("LINESTRING (0 0, 1 1)")
    with pytest.raises(ValueError, match="HalMultiPolygon2 or a HalTree2"):
        sphaera.HalMultiPolygon2([[square(0, 1)]]).intersects(3)
    sliver = sphaera.HalMultiPolygon2([[square(0, 4), np.array([[1.0, 1], [2, 2], [1, 1]])]])
    assert sliver.dropped_rings == [(0, 1)]


def test_inclusion_releases_the_gil():
    """While `contains` answers a large array, another Python thread keeps running."""
    rng = np.random.default_rng(11)
    points = rng.uniform(-1.1, 1.1, (200_000, 2))
    tree = sphaera.HalTree2(star(2000))
    assert share_kept_by_python(tree.contains, points) > 0.05
    land = sphaera.HalMultiPolygon2([[star(500, 1)], [star(500, 2) * 0.3 + 2]])
    assert share_kept_by_python(land.contains, points) > 0.05
    solid = sphaera.HalTree3(sphaera.Mesh(*uv_sphere()))
    assert share_kept_by_python(solid.contains, rng.uniform(-1.1, 1.1, (100_000, 3))) > 0.05


def test_3d_nearest_face_and_intersecting_faces():
    vertices, faces = uv_sphere()
    tree = sphaera.HalTree3(sphaera.Mesh(vertices, faces))
    points = np.array([[0.0, 0.0, 3.0], [0.2, 0.1, -0.1], [2.0, 0.0, 0.0]])
    distance, face, nearest = tree.nearest_face(points)
    assert distance.shape == (3,) and face.dtype == np.int64 and nearest.shape == (3, 3)
    # Brute force over the faces' vertices bounds the answer from above; the nearest
    # point lies on the surface's polyhedron, at most the radius away.
    np.testing.assert_allclose(np.linalg.norm(nearest - points, axis=1), distance)
    assert np.all(distance <= np.min(np.linalg.norm(vertices[None] - points[:, None], axis=2), axis=1) + 1e-12)
    assert 1.9 < distance[0] <= 2.0 and 0.0 < distance[2] <= 1.0
    near = sphaera.HalTree3(sphaera.Mesh(vertices + [1.5, 0, 0], faces))
    far = sphaera.HalTree3(sphaera.Mesh(vertices + [3.0, 0, 0], faces))
    pairs = tree.intersecting_faces(near)
    assert pairs.shape[1] == 2 and len(pairs) > 0
    assert tree.intersects(near) and not tree.intersects(far)
    assert tree.intersecting_faces(far).shape == (0, 2)
