"""Mass properties: shapes, MassProperties, meshes and scenes against Appendix A closed forms."""

import numpy as np
import pytest

import chasles
from conftest import assert_rel, example


def test_cylinder_shape_matches_appendix_a():
    # Solid cylinder of radius R, length h along z (Appendix A):
    #   Izz = m R^2 / 2,  Ixx = Iyy = m (3 R^2 + h^2) / 12.
    m, R, h = 2.5, 0.1, 0.4
    mp = chasles.cylinder(R, h).mass_properties(m)
    assert mp.mass == m
    Ixx = m * (3 * R**2 + h**2) / 12
    assert_rel(mp.inertia, np.diag([Ixx, Ixx, m * R**2 / 2]))
    assert_rel(mp.principal_moments, sorted([Ixx, Ixx, m * R**2 / 2]))
    # Radii of gyration k = sqrt(I / m) (eq. 8.19).
    assert_rel(mp.radii_of_gyration, np.sqrt(np.array([Ixx, Ixx, m * R**2 / 2]) / m))
    assert_rel(mp.principal_radii_of_gyration, np.sqrt(np.array(sorted([Ixx, Ixx, m * R**2 / 2])) / m))
    assert chasles.cylinder(R, h).kind == "cylinder"
    assert_rel(chasles.cylinder(R, h).measure(), np.pi * R**2 * h)


def test_parallel_axis_and_principal_axes():
    # Parallel-axis theorem (eq. 8.29): I_P = I_cm + m (|d|^2 E - d d^T), d = P - cm.
    m = 3.0
    I = chasles.RotationalInertia(1.0, 2.0, 2.5, Ixy=-0.3)
    mp = chasles.MassProperties(m, [0.1, 0.2, 0.3], I)
    p = np.array([1.0, -0.5, 2.0])
    d = p - np.array([0.1, 0.2, 0.3])
    expected = I.matrix + m * (d @ d * np.eye(3) - np.outer(d, d))
    assert_rel(mp.inertia_about(p), expected)
    # Principal axes diagonalise the tensor: A^T I A = diag(moments), A orthonormal, det +1.
    A = mp.principal_axes
    assert_rel(A.T @ I.matrix @ A, np.diag(mp.principal_moments), scale=np.trace(I.matrix))
    assert_rel(np.linalg.det(A), 1.0)
    # The moments of [[1, -0.3], [-0.3, 2]] with 2.5 apart: 1.5 -+ sqrt(0.25 + 0.09).
    s = np.sqrt(0.25 + 0.09)
    assert_rel(mp.principal_moments, [1.5 - s, 1.5 + s, 2.5])


def test_composite_and_hole():
    # Two point masses: the composite's centre of mass is the mass-weighted mean (eq. 8.4);
    # removing one again (a negated part) gives the other back.
    a = chasles.MassProperties.point_mass(1.0, [0.0, 0.0, 0.0])
    b = chasles.MassProperties.point_mass(3.0, [2.0, 0.0, 0.0])
    c = a + b
    assert_rel(c.mass, 4.0)
    assert_rel(c.center_of_mass, [1.5, 0.0, 0.0])
    # About the centre of mass: Iyy = Izz = 1 * 1.5^2 + 3 * 0.5^2 = 3.
    assert_rel(c.inertia, np.diag([0.0, 3.0, 3.0]), scale=3.0)
    back = c + b.negated()
    assert_rel(back.mass, 1.0)
    assert_rel(back.center_of_mass, [0.0, 0.0, 0.0], scale=1.0)


def test_invalid_inertia_is_an_input_error():
    # The triangle inequality I1 + I2 >= I3 fails for (1, 1, 3).
    mp = chasles.MassProperties(1.0, [0, 0, 0], chasles.RotationalInertia(1.0, 1.0, 3.0))
    with pytest.raises(chasles.InputError) as e:
        mp.validate("body")
    assert isinstance(e.value, ValueError)
    assert "triangle" in str(e.value) or "I1 + I2" in str(e.value)
    with pytest.raises(chasles.InputError):
        chasles.sphere(-1.0)


def cube_mesh(a):
    """A closed cube of side a centred at the origin, outward counter-clockwise triangles."""
    v = np.array([[x, y, z] for x in (-a / 2, a / 2) for y in (-a / 2, a / 2) for z in (-a / 2, a / 2)])
    # Vertex index = 4 i + 2 j + k for x_i, y_j, z_k.
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = []
    for q in quads:
        tris += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    return v, np.array(tris)


def test_mesh_from_arrays_is_exact_for_a_cube():
    # A solid cube of side a and density rho: m = rho a^3, I = m a^2 / 6 about every axis.
    a, rho = 0.2, 7850.0
    v, t = cube_mesh(a)
    r = chasles.mesh_mass_properties_from_arrays(v, t, density=rho)
    m = rho * a**3
    assert_rel(r.mass_properties.mass, m)
    assert_rel(r.mass_properties.inertia, np.eye(3) * m * a**2 / 6)
    assert_rel(r.mass_properties.center_of_mass, [0, 0, 0], scale=a)
    assert_rel(r.report.volume, a**3)
    assert r.report.triangles == 12
    # In millimetres with the total mass given instead: the same body.
    r2 = chasles.mesh_mass_properties_from_arrays(v * 1000, t, scale=1e-3, mass=m)
    assert_rel(r2.mass_properties.inertia, np.eye(3) * m * a**2 / 6)
    # A shell (the six faces, areal density sigma): m = 6 sigma a^2; each face contributes
    # about the cube's axis z: two faces normal to z (plate a x a at +-a/2 on z: m_f a^2/6)
    # and four side faces (m_f (a^2/12 + a^2/4) each for the two at +-a/2 along x or y,
    # spread along z too: m_f (a^2/12 + a^2/4) for the ones normal to x about z... summed):
    # Izz = 2 m_f a^2/6 + 4 m_f (a^2/12 + a^2/4) = m_f a^2 (1/3 + 4/3) = (5/3) m_f a^2.
    sigma = 2.0
    r3 = chasles.mesh_mass_properties_from_arrays(v, t, mode="shell", areal_density=sigma)
    mf = sigma * a**2
    assert_rel(r3.mass_properties.mass, 6 * mf)
    assert_rel(r3.mass_properties.inertia, np.eye(3) * 5 / 3 * mf * a**2)


def test_open_mesh_is_refused_in_solid_mode():
    v, t = cube_mesh(1.0)
    with pytest.raises(chasles.InputError):
        chasles.mesh_mass_properties_from_arrays(v, t[:-1], density=1000.0)
    with pytest.raises(chasles.InputError):
        chasles.mesh_mass_properties_from_arrays(v, t, density=1000.0, mode="liquid")


def test_mesh_file(tmp_path):
    # An ASCII OBJ of the cube, in millimetres.
    a = 0.05
    v, t = cube_mesh(a * 1000)
    path = tmp_path / "cube.obj"
    path.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in v) +
                    "".join(f"f {i + 1} {j + 1} {k + 1}\n" for i, j, k in t))
    r = chasles.mesh_mass_properties(str(path), scale=1e-3, density=1000.0)
    m = 1000.0 * a**3
    assert_rel(r.mass_properties.mass, m)
    assert_rel(r.mass_properties.inertia, np.eye(3) * m * a**2 / 6)
    assert r.report.format
    assert not r.report.single_precision  # text: the doubles it denotes
    assert np.isnan(r.report.float32_spacing)
    scene = chasles.load_mesh_scene(str(path), unit="mm", density="1 g/cm^3")
    assert_rel(scene.bodies[0].mass_properties.mass, m)


def test_binary_stl_reports_its_float_spacing(tmp_path):
    # The same cube as a binary STL (80-byte header, uint32 count, 50-byte records of 12
    # little-endian floats and a uint16): its largest coordinate, 25 mm, lies in [2^4, 2^5),
    # where floats are 2^(4 - 23) mm apart (IEEE 754 binary32: a 24-bit significand).
    a = 0.05
    v, t = cube_mesh(a * 1000)
    records = np.zeros(len(t), dtype=[("normal", "<f4", 3), ("xyz", "<f4", 9), ("attr", "<u2")])
    records["xyz"] = v[t].reshape(len(t), 9)
    path = tmp_path / "cube.stl"
    path.write_bytes(b" " * 80 + np.uint32(len(t)).tobytes() + records.tobytes())
    r = chasles.mesh_mass_properties(str(path), scale=1e-3, density=1000.0)
    assert r.report.format == "binary STL"
    assert r.report.single_precision
    assert r.report.float32_spacing == 2.0 ** (4 - 23) * 1e-3
    m = 1000.0 * a**3  # 25 mm is a float: the cube is exact
    assert_rel(r.mass_properties.inertia, np.eye(3) * m * a**2 / 6)


def test_scene_mass_properties_two_rods():
    # Example 8.2's bodies through the scene loader, compared with the same sums done here.
    scene = chasles.load_scene_string("""
chasles: 1
parameters: {L: 2 m, m: 3 kg}
bodies:
  - name: tee
    parts:
      - {shape: box, size: [L, 0.02 m, 0.02 m], mass: m}
      - {shape: box, size: [0.02 m, L, 0.02 m], mass: m, position: [L/2, L/2, 0]}
    points: {end: [-L/2, 0, 0]}
""")
    L, m, w = 2.0, 3.0, 0.02
    a = chasles.box(L, w, w).mass_properties(m)
    b = chasles.box(w, L, w).mass_properties(m).expressed_in_parent(np.eye(3), [L / 2, L / 2, 0])
    expected = a + b
    mp = scene.mass_properties()["tee"]
    assert_rel(mp.mass, 2 * m)
    assert_rel(mp.center_of_mass, [L / 4, L / 4, 0])
    assert_rel(mp.inertia, expected.inertia)
    # About the named point, by the parallel-axis theorem.
    assert_rel(mp.inertia_about(scene.bodies[0].points["end"]), expected.inertia_about([-L / 2, 0, 0]))
    assert_rel(scene.point("[1 m, 0, 0]"), [1, 0, 0])
    assert scene.bodies[0].parts[1].shape == "box"


def test_example_8_1_scene_file():
    scene = chasles.load_scene(example("example-8.1-cylinder.yaml"))
    assert scene.bodies
    for name, mp in scene.mass_properties().items():
        assert mp.mass > 0
        assert mp.inertia.shape == (3, 3)


def test_every_shape_factory_against_appendix_a():
    # Unit-mass central moments (Appendix A), axis of symmetry along z.
    m = 2.0
    R, L, a, b, c = 0.3, 1.1, 0.4, 0.5, 0.6
    cases = {
        "rod": (chasles.rod(L), [L**2 / 12, L**2 / 12, 0.0]),
        "ring": (chasles.ring(R), [R**2 / 2, R**2 / 2, R**2]),
        "disk": (chasles.disk(R), [R**2 / 4, R**2 / 4, R**2 / 2]),
        "plate": (chasles.plate(a, b), [b**2 / 12, a**2 / 12, (a**2 + b**2) / 12]),
        "sphere": (chasles.sphere(R), [0.4 * R**2] * 3),
        "spherical_shell": (chasles.spherical_shell(R), [2 / 3 * R**2] * 3),
        "box": (chasles.box(a, b, c), [(b**2 + c**2) / 12, (a**2 + c**2) / 12, (a**2 + b**2) / 12]),
        "ellipsoid": (chasles.ellipsoid(a, b, c), [(b**2 + c**2) / 5, (a**2 + c**2) / 5, (a**2 + b**2) / 5]),
        # Tube: (Ri^2 + Ro^2) / 2 about z, (3 (Ri^2 + Ro^2) + h^2) / 12 across.
        "tube": (chasles.tube(0.1, R, L), [(3 * (0.01 + R**2) + L**2) / 12] * 2 + [(0.01 + R**2) / 2]),
        # Cone about its centroid (h/4 above the base): 3/10 R^2 about z, 3/20 R^2 + 3/80 h^2 across.
        "cone": (chasles.cone(R, L), [3 / 20 * R**2 + 3 / 80 * L**2] * 2 + [3 / 10 * R**2]),
        # Torus (major R, minor r): about z R^2 + 3/4 r^2, across R^2/2 + 5/8 r^2.
        "torus": (chasles.torus(R, 0.1), [R**2 / 2 + 5 / 8 * 0.01] * 2 + [R**2 + 0.75 * 0.01]),
    }
    for name, (shape, moments) in cases.items():
        assert shape.kind == name
        assert_rel(np.diag(shape.unit_inertia()), moments)
        assert_rel(shape.mass_properties(m).inertia, m * np.diag(moments))
        assert name.split("_")[0] in shape.describe()
    assert_rel(chasles.cone(R, L).centroid(), [0, 0, L / 4])


def test_rotational_inertia_operations():
    I = chasles.RotationalInertia(1.0, 2.0, 3.0)
    # A quarter turn about z swaps the x and y moments: R I R^T.
    Rz = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    assert_rel(I.re_expressed_in(Rz).matrix, np.diag([2.0, 1.0, 3.0]))
    # Parallel axis: the centre of mass 2 m along x of P adds m d^2 to Iyy and Izz.
    assert_rel(I.shift_from_center_of_mass(0.5, [2.0, 0, 0]).matrix, np.diag([1.0, 4.0, 5.0]))
    assert_rel(I.radii_of_gyration(4.0), np.sqrt([0.25, 0.5, 0.75]))
    assert I.check_physically_valid() == ""
    assert_rel(chasles.RotationalInertia.from_matrix(np.diag([1.0, 2.0, 3.0])).matrix, I.matrix)
    pa = I.principal_axes()
    assert_rel(pa.moments, [1.0, 2.0, 3.0])
    assert_rel(pa.axes, np.eye(3), scale=1.0)
    assert chasles.parse_sweep("theta=0 deg:60 deg:7") == ("theta", "0 deg", "60 deg", 7)
