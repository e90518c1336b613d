"""The Python module against the engine's other faces: the C interface of
libcurvenet.so (through ctypes, bit for bit), the `curvenet` program (check
and bench JSON), the tessellation contract, error mapping, threads, and the
no-copy paths. Run by ctest (python.pytest), which sets PYTHONPATH to the
built module and CURVENET_LIBRARY / CURVENET_CLI to the built library and
program."""

import ast
import ctypes
import importlib.util
import json
import os
import pathlib
import subprocess
import sys
import threading

import numpy as np
import pytest

import curvenet

SOURCE = pathlib.Path(__file__).resolve().parents[2]


def example_module(name):
    """examples/python/NAME.py as a module (its main() not run)."""
    spec = importlib.util.spec_from_file_location(name, SOURCE / "examples" / "python" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# Uniform random points of a face's domain polygon (centred at 0), drawn as
# the example draws them: points of the fan triangles (centre, corner k,
# corner k + 1).
domain_points = example_module("g1_vs_g2").domain_points


# ---- The C interface through ctypes ------------------------------------------


class Status(ctypes.Structure):
    _fields_ = [("code", ctypes.c_int), ("element", ctypes.c_char * 128), ("message", ctypes.c_char * 512)]


class SurfaceOptions(ctypes.Structure):
    _fields_ = [(name, ctypes.c_int) for name in
                ("scheme", "sweepline", "fence_normals", "edge_curvature", "master_faces")]


C_SCHEMES = {"gregory-g1": 0, "composite-ribbon": 1, "gregory-g2": 2}


@pytest.fixture(scope="module")
def capi():
    path = os.environ.get("CURVENET_LIBRARY", "")
    if not path:
        pytest.skip("libcurvenet.so not built (CURVENET_BUILD_SHARED=OFF)")
    lib = ctypes.CDLL(path)
    p = ctypes.c_void_p
    lib.curvenet_model_load.argtypes = [ctypes.c_char_p, ctypes.POINTER(SurfaceOptions), ctypes.POINTER(p),
                                        ctypes.POINTER(Status)]
    lib.curvenet_model_evaluate_positions.argtypes = [p, ctypes.c_int, p, ctypes.c_size_t, p, p,
                                                      ctypes.POINTER(Status)]
    lib.curvenet_model_evaluate.argtypes = [p, ctypes.c_int, p, ctypes.c_size_t, p, p, ctypes.POINTER(Status)]
    lib.curvenet_model_tessellate.argtypes = [p, ctypes.c_int, ctypes.c_int, ctypes.c_int,
                                              ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.c_size_t),
                                              ctypes.POINTER(Status)]
    lib.curvenet_model_copy_mesh.argtypes = [p, p, ctypes.c_size_t, p, ctypes.c_size_t, p, ctypes.c_size_t,
                                             ctypes.POINTER(Status)]
    lib.curvenet_model_destroy.argtypes = [p]
    return lib


def c_model(lib, source, scheme):
    options = SurfaceOptions()
    lib.curvenet_surface_options_init(ctypes.byref(options))
    options.scheme = C_SCHEMES[scheme]
    model, status = ctypes.c_void_p(), Status()
    assert lib.curvenet_model_load(source.encode(), ctypes.byref(options), ctypes.byref(model),
                                   ctypes.byref(status)) == 0, status.message
    return model


@pytest.mark.parametrize("scheme", ["gregory-g1", "gregory-g2"])
@pytest.mark.parametrize("source", ["builtin:pentagon", "builtin:sphere-dodecahedron"])
def test_evaluation_equals_the_c_interface_bit_for_bit(capi, source, scheme):
    model = curvenet.Model.load(source, scheme=scheme)
    native = c_model(capi, source, scheme)
    try:
        for face in range(min(model.face_count, 3)):
            uv = domain_points(model, face, 2000, seed=face)
            positions = model.evaluate_positions(face, uv)
            expected = np.empty_like(positions)
            status = Status()
            assert capi.curvenet_model_evaluate_positions(native, face, uv.ctypes.data, len(uv),
                                                          expected.ctypes.data, None, ctypes.byref(status)) == 0
            assert np.array_equal(positions, expected)

            evaluation = model.evaluate(face, uv[:300])
            points = np.empty((300, 4, 3))
            assert capi.curvenet_model_evaluate(native, face, uv.ctypes.data, 300, points.ctypes.data, None,
                                                ctypes.byref(status)) == 0
            for k, field in enumerate(("points", "du", "dv", "normals")):
                assert np.array_equal(getattr(evaluation, field), points[:, k, :]), field
    finally:
        capi.curvenet_model_destroy(native)


SHARED_MODELS = pathlib.Path(os.environ.get("CURVENET_SHARED_DATA_DIR", "../shared/data")) / "transfinite-models"


@pytest.mark.parametrize("name", ["cagd86.lop", "pocket3sided.lop"])
def test_real_models_evaluate_as_through_the_c_interface(capi, name):
    path = SHARED_MODELS / name
    if not path.exists():
        pytest.skip(f"shared model not present at {path}")
    model = curvenet.Model.load(path, scheme="gregory-g2")  # any os.PathLike
    native = c_model(capi, str(path), "gregory-g2")
    try:
        for face in range(model.face_count):
            uv = domain_points(model, face, 500, seed=face)
            expected, status = np.empty((len(uv), 3)), Status()
            assert capi.curvenet_model_evaluate_positions(native, face, uv.ctypes.data, len(uv),
                                                          expected.ctypes.data, None, ctypes.byref(status)) == 0
            assert np.array_equal(model.evaluate_positions(face, uv), expected)
    finally:
        capi.curvenet_model_destroy(native)


def test_mesh_equals_the_c_interface(capi):
    model = curvenet.Model.load("builtin:sphere-dodecahedron", scheme="gregory-g2")
    mesh = model.tessellate(resolution=6, threads=1)
    native = c_model(capi, "builtin:sphere-dodecahedron", "gregory-g2")
    try:
        vertices, triangles, status = ctypes.c_size_t(), ctypes.c_size_t(), Status()
        assert capi.curvenet_model_tessellate(native, -1, 6, 1, ctypes.byref(vertices), ctypes.byref(triangles),
                                              ctypes.byref(status)) == 0
        assert mesh.vertices.shape == (vertices.value, 3) and mesh.triangles.shape == (triangles.value, 3)
        positions = np.empty((vertices.value, 3))
        indices = np.empty((triangles.value, 3), dtype=np.uint32)
        assert capi.curvenet_model_copy_mesh(native, positions.ctypes.data, vertices.value, None, 0,
                                             indices.ctypes.data, triangles.value, ctypes.byref(status)) == 0
        assert np.array_equal(mesh.vertices, positions) and np.array_equal(mesh.triangles, indices)
    finally:
        capi.curvenet_model_destroy(native)


# ---- The program's JSON --------------------------------------------------------


def cli_json(*args):
    program = os.environ.get("CURVENET_CLI", "")
    if not program:
        pytest.skip("the curvenet program is not built")
    return json.loads(subprocess.run([program, *args], check=True, capture_output=True, text=True).stdout)


@pytest.mark.parametrize("scheme", ["gregory-g1", "gregory-g2"])
def test_check_is_the_object_check_json_prints(scheme):
    model = curvenet.Model.load("builtin:pentagon", scheme=scheme)
    assert model.check(samples=16, resolution=8) == cli_json(
        "check", "builtin:pentagon", "--json", "--scheme", scheme, "--samples", "16", "--resolution", "8")


def test_bench_reports_what_bench_json_reports():
    report = curvenet.bench("builtin:pentagon", resolution=4, points=50, threads=1)
    expected = cli_json("bench", "builtin:pentagon", "--json", "--resolution", "4", "--points", "50",
                        "--threads", "1")
    assert report.keys() == expected.keys()
    assert report["schemes"].keys() == expected["schemes"].keys() == {"gregory-g1", "gregory-g2",
                                                                      "composite-ribbon"}
    # Timings differ from run to run; the counts do not.
    for scheme, figures in report["schemes"].items():
        for count in ("evaluated_points", "mesh_points", "pointwise_points"):
            assert figures[count] == expected["schemes"][scheme][count]
        assert figures["warm_seconds"] > 0


# ---- Tessellation contract, building, editing --------------------------------------


@pytest.mark.parametrize("r", [1, 5, 12])
def test_tessellation_of_a_pentagon_follows_the_contract(r):
    mesh = curvenet.Model.load("builtin:pentagon").tessellate(resolution=r)
    vertices = 5 + 5 * (r - 1) + 1 + 5 * (r - 1) + 5 * (r - 1) * (r - 2) // 2
    assert mesh.vertices.shape == (vertices, 3) and mesh.normals.shape == (vertices, 3)
    assert mesh.triangles.shape == (5 * r * r, 3) and mesh.triangles.dtype == np.uint32
    assert list(mesh.face_triangle_start) == [0, 5 * r * r]
    assert mesh.triangles.max() < vertices
    assert np.allclose(np.linalg.norm(mesh.normals, axis=1), 1)


def square_curves(lift=0.0):
    """Four cubic Bézier curves around the unit square, the middle control
    points of the first lifted by `lift`."""
    corners = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    curves = []
    for k in range(4):
        a, b = corners[k], corners[(k + 1) % 4]
        c = np.array([a, a + (b - a) / 3, a + 2 * (b - a) / 3, b])
        if k == 0:
            c[1:3, 2] += lift
        curves.append(c)
    return curves


def test_build_from_numpy_curves_interpolates_the_corners():
    curves = square_curves(lift=0.3)
    model = curvenet.Model.build(curves, [[0, 1, 2, 3]], scheme="gregory-g1", name="square")
    assert model.face_count == 1 and model.domain_sides(0) == 4
    points = model.evaluate_positions(0, model.domain_corners(0))
    ends = np.array([c[0] for c in curves])
    # Every domain corner evaluates to a loop corner, each corner once.
    distance = np.linalg.norm(points[:, None, :] - ends[None, :, :], axis=2)
    assert np.all(distance.min(axis=1) < 1e-12)
    assert sorted(distance.argmin(axis=1)) == [0, 1, 2, 3]
    # A B-spline curve given by its data is the same curve as the Bézier array.
    spline = {"points": curves[0], "degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1]}
    same = curvenet.Model.build([spline] + curves[1:], [[0, 1, 2, 3]])
    uv = domain_points(model, 0, 200)
    assert np.array_equal(same.evaluate_positions(0, uv), model.evaluate_positions(0, uv))


def test_set_control_points_moves_the_surface_and_back():
    curves = square_curves()
    model = curvenet.Model.build(curves, [[0, 1, 2, 3]])
    uv = domain_points(model, 0, 500)
    before = model.evaluate_positions(0, uv)
    lifted = curves[0].copy()
    lifted[1:3, 2] += 0.5
    model.set_control_points(0, lifted)
    assert model.last_edited_faces == [0]
    moved = model.evaluate_positions(0, uv)
    assert np.max(np.abs(moved[:, 2] - before[:, 2])) > 0.05
    model.set_control_points(0, curves[0])
    assert np.array_equal(model.evaluate_positions(0, uv), before)


def test_per_face_schemes_and_exact_second_derivatives():
    model = curvenet.Model.load("builtin:sphere-dodecahedron")
    model.set_face_options(0, scheme="gregory-g2")
    assert model.face_scheme(0) == "gregory-g2" and model.face_scheme(1) == "gregory-g1"
    assert model.surface_count == 2 and model.has_exact_second_derivatives(0)
    uv = domain_points(model, 0, 50) * 0.8
    second = model.evaluate_second_order(0, uv)
    # duu against a central difference of the exact du.
    h = 1e-5
    step = np.array([h, 0.0])
    du_plus, du_minus = model.evaluate(0, uv + step).du, model.evaluate(0, uv - step).du
    assert np.allclose(second.duu, (du_plus - du_minus) / (2 * h), atol=1e-5 * np.abs(second.duu).max())
    # Second order is evaluated point by point; batches of first order take the
    # ribbon tables, which agree with it to ~1e-14 of the size (curvenet.hpp).
    assert np.allclose(second.points, model.evaluate(0, uv).points, rtol=0, atol=1e-12)
    assert np.allclose(second.points, model.evaluate_positions(0, uv), rtol=0, atol=1e-12)


def test_render_returns_an_srgb_picture():
    model = curvenet.Model.load("builtin:pentagon")
    reflection = model.render(size=(64, 48), resolution=8)
    assert reflection.shape == (48, 64, 3) and reflection.dtype == np.uint8
    assert reflection.min() < 80 and reflection.max() > 200  # dark and light stripes
    isophote = model.render(mode="isophote", size=(64, 48), resolution=8)
    assert not np.array_equal(reflection, isophote)
    assert np.array_equal(model.render(size=(64, 48), resolution=8, threads=1), reflection)


# ---- Errors ------------------------------------------------------------------


def test_errors_are_curvenet_errors_with_the_status():
    assert issubclass(curvenet.Error, ValueError)
    with pytest.raises(curvenet.Error, match="no-such-builtin") as raised:
        curvenet.Model.load("builtin:no-such-builtin")
    assert raised.value.code == "invalid-input"
    with pytest.raises(curvenet.Error, match="unknown scheme"):
        curvenet.Model.load("builtin:pentagon", scheme="g3")
    model = curvenet.Model.load("builtin:pentagon")
    with pytest.raises(curvenet.Error) as raised:
        model.evaluate_positions(0, np.array([[0.0, 0.0], [5.0, 5.0]]))
    assert raised.value.code == "out-of-domain" and raised.value.element == "point 1"
    with pytest.raises(curvenet.Error) as raised:
        model.evaluate(3, np.zeros((1, 2)))
    assert raised.value.code == "invalid-argument"
    with pytest.raises(curvenet.Error, match=r"shape \(N, 2\)"):
        model.evaluate_positions(0, np.zeros((4, 3)))
    with pytest.raises(curvenet.Error, match="face 9"):
        model.domain_sides(9)
    with pytest.raises(curvenet.Error) as raised:
        model.set_control_points(0, np.zeros((1, 3)))
    assert raised.value.code == "invalid-argument"
    with pytest.raises(curvenet.Error, match="unknown mode"):
        model.render(mode="x-ray")
    with pytest.raises(curvenet.Error, match="16384"):
        model.render(size=(20000, 10))


def test_an_open_loop_is_an_error_naming_the_face():
    curves = square_curves()
    curves[2] = curves[2] + np.array([0, 0, 0.5])  # no longer meets its neighbours
    with pytest.raises(curvenet.Error) as raised:
        curvenet.Model.build(curves, [[0, 1, 2, 3]])
    assert raised.value.code == "invalid-input" and "face 0" in str(raised.value)


# ---- Threads and copies --------------------------------------------------------


def test_output_is_the_same_for_any_thread_count_and_from_many_threads():
    model = curvenet.Model.load("builtin:sphere-dodecahedron", scheme="gregory-g2")
    uv = domain_points(model, 2, 20000)
    serial = model.evaluate_positions(2, uv, threads=1)
    parallel = model.evaluate_positions(2, uv, threads=0)
    assert np.array_equal(model.evaluate_positions(2, uv, threads=2), parallel)
    # The same bits serially and in parallel (fixed chunks, curvenet.hpp).
    assert np.array_equal(parallel, serial)
    jets = model.evaluate(2, uv, threads=1)
    assert np.array_equal(model.evaluate(2, uv, threads=0).normals, jets.normals)
    results, errors = [None] * 4, []

    def work(k):
        try:
            results[k] = model.evaluate_positions(2, uv, threads=1 if k % 2 == 0 else 2)
        except Exception as e:  # reported below, on the main thread
            errors.append(e)

    workers = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for w in workers:
        w.start()
    # An edit from this thread meanwhile waits for the readers, and they for it.
    model.set_face_options(None, scheme="gregory-g2")
    for w in workers:
        w.join()
    assert not errors
    assert all(np.array_equal(r, serial if k % 2 == 0 else parallel) for k, r in enumerate(results))


def test_fast_path_writes_in_place_and_converts_only_what_it_must():
    model = curvenet.Model.load("builtin:pentagon")
    uv = domain_points(model, 0, 1000)
    out = np.empty((1000, 3))
    assert model.evaluate_positions(0, uv, out=out) is out
    fresh = model.evaluate_positions(0, uv)
    assert fresh.flags.c_contiguous and fresh.flags.owndata and np.array_equal(fresh, out)
    # Other layouts and types are converted once, to the same result.
    strided = np.empty((1000, 4))
    strided[:, ::2] = uv
    assert np.array_equal(model.evaluate_positions(0, strided[:, ::2]), out)
    assert np.array_equal(model.evaluate_positions(0, uv.tolist()), out)
    with pytest.raises(curvenet.Error, match="out must be"):
        model.evaluate_positions(0, uv, out=np.empty((1000, 3), dtype=np.float32))
    # The fields of an evaluation are views of one block.
    evaluation = model.evaluate(0, uv)
    points, normals = evaluation.points, evaluation.normals
    assert points.base is normals.base and points.strides == (96, 8)
    assert normals.ctypes.data - points.ctypes.data == 9 * 8
    mesh = model.tessellate(resolution=4)
    assert not np.shares_memory(mesh.vertices, mesh.normals)
    assert mesh.vertices.flags.c_contiguous and mesh.triangles.flags.c_contiguous


# ---- The stub and the example ----------------------------------------------------


def test_the_stub_declares_what_the_module_defines_and_every_call_has_a_docstring():
    stub = ast.parse((SOURCE / "python" / "curvenet.pyi").read_text())
    declared = {}
    for node in stub.body:
        if isinstance(node, ast.ClassDef):
            declared[node.name] = {item.name if isinstance(item, ast.FunctionDef) else item.target.id
                                   for item in node.body if isinstance(item, (ast.FunctionDef, ast.AnnAssign))}
        elif isinstance(node, ast.FunctionDef):
            declared[node.name] = None
    public = {name for name in dir(curvenet) if not name.startswith("_")}
    assert public == set(declared)
    for name, members in declared.items():
        if members is None:
            assert getattr(curvenet, name).__doc__
            continue
        cls = getattr(curvenet, name)
        defined = {m for m in vars(cls) if not m.startswith("_")}
        if name == "Error":
            defined |= {"code", "file", "element"}  # set on each raised instance
        else:
            # Evaluation2 inherits the first-order fields.
            inherited = declared["Evaluation"] if name == "Evaluation2" else set()
            assert defined == {m for m in members - inherited if not m.startswith("_")}
        for member in members & set(vars(cls)):
            assert getattr(cls, member).__doc__, f"{name}.{member}"


def test_the_example_times_both_schemes_and_writes_a_png(tmp_path):
    image = tmp_path / "reflection.png"
    run = subprocess.run([sys.executable, str(SOURCE / "examples" / "python" / "g1_vs_g2.py"), "builtin:pentagon",
                          "--points", "20000", "--image", str(image), "--size", "80x60"],
                         check=True, capture_output=True, text=True)
    assert "G2/G1 cost, 1 thread" in run.stdout and "points/s" in run.stdout
    assert image.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
