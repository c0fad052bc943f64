"""Still.camera: the depth buffer of an off-centre sphere back-projects through K and [R|t] onto the sphere; the OpenCV
and OpenGL matrices agree; examples/orbit-cameras/orbit_cameras.py writes each picture with its camera."""

from __future__ import annotations

import json
import math
import os
import pathlib
import subprocess
import sys

import numpy as np

import inkgraph
from pngread import read_png

CENTRE = np.array([0.7, -0.3, 0.4])
RADIUS = 0.5


def write_uv_sphere(path: pathlib.Path, centre: np.ndarray, radius: float, rings: int = 96,
                    segments: int = 192) -> None:
    """A UV sphere as an OBJ: poles on y, fine enough that its facets stay far inside the test's tolerance (the
    chord's sag is r (1 - cos(pi / segments)), 0.013% of r here)."""
    lines = []
    for ring in range(rings + 1):
        polar = math.pi * ring / rings
        for segment in range(segments):
            azimuth = 2 * math.pi * segment / segments
            x, y, z = math.sin(polar) * math.cos(azimuth), math.cos(polar), math.sin(polar) * math.sin(azimuth)
            lines.append(f"v {centre[0] + radius * x:.9f} {centre[1] + radius * y:.9f} {centre[2] + radius * z:.9f}")
    for ring in range(rings):
        for segment in range(segments):
            a = ring * segments + segment + 1
            b = ring * segments + (segment + 1) % segments + 1
            c, d = a + segments, b + segments
            lines.append(f"f {a} {b} {d}")  # counter-clockwise seen from outside
            lines.append(f"f {a} {d} {c}")
    path.write_text("\n".join(lines) + "\n")


def test_depth_back_projects_through_k_and_rt_onto_an_off_centre_sphere(tmp_path):
    model = tmp_path / "sphere.obj"
    write_uv_sphere(model, CENTRE, RADIUS)
    result = inkgraph.render(model, size=(640, 480), lines=[], frame=inkgraph.Frame(orbit=inkgraph.Orbit(30, 20)),
                             buffers=["depth"])
    camera = result.camera
    assert (camera.width, camera.height) == (640, 480) and camera.source == inkgraph.CameraSource.ORBIT
    depth = result.buffers["depth"].astype(np.float64)
    assert depth.shape == (480, 640)
    rows, columns = np.nonzero(depth > 0)
    assert len(rows) > 0.05 * depth.size  # the sphere fills a good part of the picture

    K = camera.intrinsics
    R, t = camera.extrinsics[:, :3], camera.extrinsics[:, 3]
    pixels = np.stack([columns, rows, np.ones_like(rows)]).astype(np.float64)  # u right, v down
    x_camera = depth[rows, columns] * (np.linalg.inv(K) @ pixels)
    x_world = R.T @ (x_camera - t[:, None])
    distance_to_surface = np.abs(np.linalg.norm(x_world - CENTRE[:, None], axis=0) - RADIUS)
    assert distance_to_surface.max() <= 0.005 * RADIUS, distance_to_surface.max() / RADIUS


def test_the_opencv_and_opengl_matrices_agree(suzanne):
    still = inkgraph.default_renderer().render(suzanne, inkgraph.Look(), inkgraph.Frame(160, 120, orbit=(40, 25)))
    camera = still.camera
    for matrix, shape in ((camera.intrinsics, (3, 3)), (camera.extrinsics, (3, 4)), (camera.view, (4, 4)),
                          (camera.projection, (4, 4))):
        assert matrix.shape == shape and matrix.dtype == np.float64
    K = camera.intrinsics
    focal = (camera.height / 2) / math.tan(math.radians(camera.fov_y) / 2)
    assert np.allclose(K, [[focal, 0, camera.width / 2 - 0.5], [0, focal, camera.height / 2 - 0.5], [0, 0, 1]])
    # [R|t] is the view matrix with y and z turned around (OpenGL looks down -z with y up; OpenCV down +z, y down).
    assert np.allclose(camera.extrinsics, np.diag([1, -1, -1]) @ camera.view[:3, :])
    # The eye is where [R|t] puts the camera's centre.
    R, t = camera.extrinsics[:, :3], camera.extrinsics[:, 3]
    assert np.allclose(-R.T @ t, tuple(camera.eye))
    # A world point projects to the same pixel through K [R|t] and through OpenGL's projection and viewport.
    point = np.array([0.1, 0.2, 0.3])
    pixel = K @ (R @ point + t)
    clip = camera.projection @ camera.view @ np.append(point, 1)
    ndc = clip[:3] / clip[3]
    gl_pixel = ((ndc[0] + 1) / 2 * camera.width - 0.5, (1 - ndc[1]) / 2 * camera.height - 0.5)
    assert np.allclose(pixel[:2] / pixel[2], gl_pixel)
    assert 0 < camera.near < camera.far and not camera.clip_given
    record = camera.as_dict()
    assert record["intrinsics"] == K.tolist() and record["source"] == "orbit" and record["width"] == 160
    json.dumps(record)


def test_the_orbit_cameras_example_writes_each_picture_with_its_camera(repo, tmp_path):
    output = tmp_path / "orbits"
    script = repo / "examples" / "orbit-cameras" / "orbit_cameras.py"
    package_parent = str(pathlib.Path(inkgraph.__file__).resolve().parents[1])
    environment = dict(os.environ, PYTHONPATH=os.pathsep.join([package_parent, os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run([sys.executable, str(script), "--output", str(output), "--views", "4", "--width", "64",
                          "--height", "80"], capture_output=True, text=True, env=environment, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    cameras = json.loads((output / "cameras.json").read_text())
    assert len(cameras["views"]) == 4
    eyes = []
    for view in cameras["views"]:
        assert json.loads((output / f"view-{view['index']}.json").read_text()) == view
        picture = read_png(output / view["picture"])
        camera = view["camera"]
        assert picture.shape == (80, 64, 4) and (camera["width"], camera["height"]) == (64, 80)
        assert camera["source"] == "orbit" and view["orbit"]["azimuth"] == 90.0 * view["index"]
        extrinsics = np.array(camera["extrinsics"])
        eye = -extrinsics[:, :3].T @ extrinsics[:, 3]
        assert np.allclose(eye, camera["eye"])
        eyes.append(eye)
    # Four views around the model: the eyes are different places at one distance from the target.
    target = np.array(cameras["views"][0]["camera"]["target"])
    distances = [np.linalg.norm(eye - target) for eye in eyes]
    assert np.allclose(distances, distances[0]) and len({tuple(np.round(eye, 6)) for eye in eyes}) == 4
