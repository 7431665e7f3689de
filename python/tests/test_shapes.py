"""Shapes from Python: analytic dimensions, volumes, ray casts and closest points; pickling;
errors naming the field; the subclass of each kind."""

import math
import pickle

import numpy as np
import pytest

import proxima
from conftest import convex_shapes


def test_every_kind_is_a_shape_subclass_with_its_type_name():
    for shape, spec in convex_shapes():
        assert isinstance(shape, proxima.Shape)
        expected = {"convex": "hull"}.get(spec["type"], spec["type"])
        assert shape.type in (spec["type"], expected)


def test_volumes_match_the_closed_forms():
    r, h = 0.3, 0.6
    cases = [
        (proxima.Sphere(0.5), 4 / 3 * math.pi * 0.5**3),
        (proxima.Capsule(r, h), math.pi * r * r * 2 * h + 4 / 3 * math.pi * r**3),
        (proxima.Box((0.5, 0.4, 0.3)), 8 * 0.5 * 0.4 * 0.3),
        (proxima.Cylinder(0.4, 0.5), math.pi * 0.16 * 1.0),
        (proxima.Cone(0.4, 0.6), math.pi * 0.16 * 1.2 / 3),
        (proxima.Ellipsoid((0.5, 0.3, 0.4)), 4 / 3 * math.pi * 0.5 * 0.3 * 0.4),
    ]
    for shape, volume in cases:
        props = shape.mass_properties(density=2.0)
        assert props.volume == pytest.approx(volume, rel=1e-5)
        assert props.mass == pytest.approx(2 * volume, rel=1e-5)


def test_sphere_ray_and_closest_point_are_analytic():
    s = proxima.Sphere(2.0)
    pose = proxima.Transform((1, 2, 3))
    hit = s.raycast((1, 2, 13), (0, 0, -2), pose=pose)
    assert hit.t == pytest.approx(4.0)
    np.testing.assert_allclose(hit.point, (1, 2, 5), atol=1e-6)
    np.testing.assert_allclose(hit.normal, (0, 0, 1), atol=1e-6)
    assert s.raycast((1, 2, 13), (0, 0, -2), max_t=3.9, pose=pose) is None
    sp = s.closest_point((1, 2, 3 + 5), pose=pose)
    assert sp.signed_distance == pytest.approx(3.0)
    assert s.contains((1, 2, 4.9), pose=pose) and not s.contains((1, 2, 5.1), pose=pose)


def test_mesh_from_numpy_is_a_closed_tetrahedron():
    vertices = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    triangles = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)
    mesh = proxima.TriangleMesh(vertices, triangles)
    assert mesh.is_closed
    assert mesh.mass_properties().volume == pytest.approx(1 / 6, rel=1e-6)
    assert mesh.triangles.shape == (4, 3) and mesh.vertices.shape == (4, 3)
    assert mesh.contains((0.1, 0.1, 0.1)) and not mesh.contains((1, 1, 1))


def test_every_shape_and_transform_pickles_to_an_equal_one():
    mesh = proxima.TriangleMesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    compound = proxima.Compound([proxima.Sphere(1), (proxima.Box((1, 1, 1)), proxima.Transform((3, 0, 0)))])
    shapes = [s for s, _ in convex_shapes()] + [mesh, compound, proxima.HalfSpace((0, 0, 2), 1)]
    for shape in shapes:
        copy = pickle.loads(pickle.dumps(shape))
        assert type(copy) is type(shape)
        assert repr(copy) == repr(shape)
        b1, b2 = shape.aabb(proxima.Transform((1, 2, 3))), copy.aabb(proxima.Transform((1, 2, 3)))
        np.testing.assert_array_equal(b1.min, b2.min)
        np.testing.assert_array_equal(b1.max, b2.max)
    t = proxima.Transform((1, 2, 3), (0, 0, math.sin(0.3), math.cos(0.3)))
    np.testing.assert_array_equal(pickle.loads(pickle.dumps(t)).to_array(), t.to_array())


@pytest.mark.parametrize("make, field", [
    (lambda: proxima.Sphere(-1), "radius"),
    (lambda: proxima.Box((1, float("nan"), 1)), "half_extents"),
    (lambda: proxima.Capsule(1, -0.5), "half_length"),
    (lambda: proxima.ConvexHull([[0, 0, 0], [1, 0, 0], [0, 1, 0]]), "points"),
    (lambda: proxima.TriangleMesh([[0, 0, 0]], [[0, 1, 2]]), "triangles"),
    (lambda: proxima.Transform((0, 0, 0), (0, 0, 0, 2)), "rotation"),
    (lambda: proxima.Compound([(proxima.Sphere(1), "not a pose")]), "children[0].pose"),
    (lambda: proxima.Sphere(1).raycast((0, 0, 0), (0, 0, 0)), "direction"),
])
def test_bad_input_raises_an_error_naming_the_field(make, field):
    with pytest.raises(proxima.Error) as info:
        make()
    assert info.value.field.startswith(field), (info.value.field, str(info.value))
    assert isinstance(info.value, ValueError)


def test_a_halfspace_has_no_mass_and_a_compound_no_containment():
    with pytest.raises(proxima.Error):
        proxima.HalfSpace((0, 0, 1), 0).mass_properties()
    with pytest.raises(proxima.Error):
        proxima.Compound([proxima.Sphere(1)]).contains((0, 0, 0))
