"""The numbers against the Rust CLI and brute force; every result pickles exactly."""

import pickle

import numpy as np
import pytest

import sphaera
from conftest import share_kept_by_python, uv_sphere


def brute_distances(vertices, faces, points):
    """Closest distance from each point to the triangles, by projecting onto every
    triangle's plane, edges and corners (vectorised over triangles)."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    out = []
    for p in points:
        best = np.full(len(faces), np.inf)
        # Corners and edges.
        for u, v in [(a, b), (b, c), (c, a)]:
            d = v - u
            t = np.clip(np.einsum("ij,ij->i", p - u, d) / np.einsum("ij,ij->i", d, d), 0, 1)
            best = np.minimum(best, np.linalg.norm(u + t[:, None] * d - p, axis=1))
        # The interior, where the projection lies inside.
        n = np.cross(b - a, c - a)
        n /= np.linalg.norm(n, axis=1)[:, None]
        h = np.einsum("ij,ij->i", p - a, n)
        q = p - h[:, None] * n
        inside = np.ones(len(faces), dtype=bool)
        for u, v in [(a, b), (b, c), (c, a)]:
            inside &= np.einsum("ij,ij->i", np.cross(v - u, q - u), n) >= 0
        best = np.where(inside, np.minimum(best, np.abs(h)), best)
        out.append(best.min())
    return np.asarray(out)


def test_distances_match_brute_force_and_intervals_hold(ball):
    rng = np.random.default_rng(7)
    points = rng.uniform(-1.5, 1.5, size=(300, 3))
    exact = sphaera.distance(ball, points)
    reference = brute_distances(ball.vertices, ball.faces.astype(np.int64), points)
    np.testing.assert_allclose(exact.distance, reference, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(exact.lower, exact.upper)
    # The closest points lie on the mesh at the reported distance.
    np.testing.assert_allclose(np.linalg.norm(exact.closest - points, axis=1), exact.distance, atol=1e-12)
    approx = sphaera.distance(ball, points, tolerance="1%")
    assert approx.tolerance == pytest.approx(0.01 * ball.diagonal)
    assert np.all(approx.lower <= reference + 1e-12) and np.all(reference <= approx.upper + 1e-12)
    assert np.all(approx.upper - approx.lower <= approx.tolerance + 1e-12)
    assert len(exact) == 300 and "exact" in repr(exact)


def test_the_numbers_are_the_cli_s(cli, data_dir, tmp_path):
    path = data_dir / "bunny_lowres.obj"
    bunny = sphaera.load(path)
    tree = sphaera.spheretree(bunny)
    report = cli("spheretree", path)
    assert [len(level) for level in tree.levels] == [level["spheres"] for level in report["levels"]]
    simplified = sphaera.simplify(bunny, ratio=0.1)
    out = tmp_path / "small.ply"
    report = cli("simplify", path, "--ratio", "0.1", "-o", out)
    assert simplified.error_bound == report["error_bound"]
    assert simplified.mesh.triangle_count == report["triangles_out"]
    h = sphaera.hausdorff(bunny, simplified.mesh, tolerance="0.001%")
    report = cli("hausdorff", path, out, "--tolerance", "0.001%")
    assert (h.lower, h.upper) == (report["lower"], report["upper"])


def test_sphere_trees_cover_and_nest(ball):
    tree = sphaera.spheretree(ball, depth=2, branch=4, samples=1500)
    assert tree.depth == len(tree.levels) == 3 and len(tree.levels[0]) == 1
    vertices = ball.vertices
    for level, (spheres, parents) in enumerate(zip(tree.levels, tree.parents, strict=True)):
        assert spheres.shape[1] == 4 and np.all(spheres[:, 3] > 0)
        # Every vertex lies in some sphere of every level.
        gaps = np.linalg.norm(vertices[:, None, :] - spheres[None, :, :3], axis=2) - spheres[None, :, 3]
        assert np.all(gaps.min(axis=1) <= 1e-9 * ball.diagonal)
        if level == 0:
            assert list(parents) == [-1]
        else:
            assert np.all((0 <= parents) & (parents < len(tree.levels[level - 1])))
        lower, upper = tree.errors[level]
        assert 0 <= lower <= upper
    # Deterministic: the same call gives the same tree.
    again = sphaera.spheretree(ball, depth=2, branch=4, samples=1500)
    for x, y in zip(tree.levels, again.levels, strict=True):
        np.testing.assert_array_equal(x, y)


def test_scaling_by_a_power_of_two_scales_every_result_exactly():
    vertices, faces = uv_sphere()
    one = sphaera.Mesh(vertices, faces)
    eight = sphaera.Mesh(8 * vertices, faces)
    s1, s8 = sphaera.simplify(one, ratio=0.3), sphaera.simplify(eight, ratio=0.3)
    assert s8.error_bound == 8 * s1.error_bound
    np.testing.assert_array_equal(s8.mesh.vertices, 8 * s1.mesh.vertices)
    h1, h8 = sphaera.hausdorff(one, s1.mesh), sphaera.hausdorff(eight, s8.mesh)
    assert (h8.lower, h8.upper) == (8 * h1.lower, 8 * h1.upper)
    t1 = sphaera.spheretree(one, depth=2, branch=4, samples=1500)
    t8 = sphaera.spheretree(eight, depth=2, branch=4, samples=1500)
    for a, b in zip(t1.levels, t8.levels, strict=True):
        np.testing.assert_array_equal(8 * a, b)


def test_every_result_pickles_exactly_and_reads_well(ball):
    rng = np.random.default_rng(1)
    results = [
        ball,
        sphaera.simplify(ball, ratio=0.5),
        sphaera.distance(ball, rng.uniform(-2, 2, (50, 3))),
        sphaera.distance(ball, rng.uniform(-2, 2, (50, 3)), tolerance=0.01),
        sphaera.hausdorff(ball, sphaera.simplify(ball, ratio=0.5).mesh),
        sphaera.spheretree(ball, depth=1, branch=4, samples=1000),
    ]
    for result in results:
        copy = pickle.loads(pickle.dumps(result))
        assert type(copy) is type(result)
        assert repr(copy) == repr(result)
        assert_same(result.to_dict(), copy.to_dict())
        assert type(result).__name__ in repr(result)


def assert_same(a, b):
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for key in a:
            assert_same(a[key], b[key])
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b)
        for x, y in zip(a, b, strict=True):
            assert_same(x, y)
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype
        np.testing.assert_array_equal(a, b)
    else:
        assert a == b


def test_long_calls_release_the_gil(data_dir):
    """While `distance` runs, another Python thread keeps running. (Each call already
    uses every core, so two concurrent calls on a 2-core machine are no faster than one
    after the other; what releasing the GIL buys is that Python goes on meanwhile.)"""
    mesh = sphaera.load(data_dir / "bunny_lowres.obj")
    points = np.random.default_rng(3).uniform(-10, 10, (200_000, 3))
    sphaera.distance(mesh, points[:10])  # the tree is built once, here
    # With the GIL held the counter would stop for the whole call (a few ticks at most, at
    # the switch into the call); released, it keeps a good share of its idle rate even
    # while the call uses every core.
    kept = share_kept_by_python(lambda p: sphaera.distance(mesh, p), points)
    assert kept > 0.05, kept
