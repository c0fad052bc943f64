"""inkgraph for Python: render 3D models as anime/comic-style stills; the picture, any buffer and the camera as NumPy
arrays.

    import inkgraph

    result = inkgraph.render("models/bunny_c3d_70k.obj", look={"shading": "cel", "silhouette-width": 3},
                             size=512, lines=["silhouette", "contour"], buffers=["normal", "depth", "lines.contour"])
    result.picture                   # 512 x 512 x 4 uint8, RGBA
    result.buffers["normal"]         # 512 x 512 x 4 float32, alpha = coverage
    result.camera.intrinsics         # OpenCV's K, 3 x 3 float64

The typed API is the C++ library's (inkgraph/inkgraph.h, docs/api.md) as the extension `inkgraph._inkgraph` binds it:
Scene (a file or NumPy arrays), Look and Frame with typed fields (Shading.CEL, LineType.CONTOUR, Orbit(30, 10)),
Renderer, Still and its StillCamera. Every field is checked as the command line's flag that sets it, so errors read the
same (inkgraph.UsageError and the rest of the inkgraph.Error family); warnings are inkgraph.InkgraphWarning, issued
through Python's warnings module. render() draws with a renderer kept for the process, so a batch makes its GL
context once. docs/python.md has it all.
"""

from ._errors import ContextError, Error, InputError, OutputError, RenderError, UsageError
from ._front import Result, default_renderer, make_frame, make_look, render
from ._inkgraph import (
    CameraPlacement,
    CameraSource,
    Clip,
    Color,
    FaceOrientation,
    Frame,
    LineStyle,
    LineType,
    Look,
    Orbit,
    Precision,
    Renderer,
    Scene,
    Shading,
    Still,
    StillCamera,
    StrokeSettings,
    Vec3,
    ViewSample,
    ViewVector,
    buffer_names,
    git_commit,
    sample_views,
    version,
    write_image,
)
from ._warnings import InkgraphWarning

__version__: str = version()

__all__ = [
    "CameraPlacement",
    "CameraSource",
    "Clip",
    "Color",
    "ContextError",
    "Error",
    "FaceOrientation",
    "Frame",
    "InkgraphWarning",
    "InputError",
    "LineStyle",
    "LineType",
    "Look",
    "Orbit",
    "OutputError",
    "Precision",
    "RenderError",
    "Renderer",
    "Result",
    "Scene",
    "Shading",
    "Still",
    "StillCamera",
    "StrokeSettings",
    "UsageError",
    "Vec3",
    "ViewSample",
    "ViewVector",
    "buffer_names",
    "default_renderer",
    "git_commit",
    "make_frame",
    "make_look",
    "render",
    "sample_views",
    "version",
    "write_image",
]
