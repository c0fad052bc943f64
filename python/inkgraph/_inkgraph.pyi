"""Type stubs of the extension inkgraph._inkgraph (python/Bindings.cpp): every class, enum, property and function it
defines, with the types it takes and gives. Where an enum is taken, its command-line word is taken too, and where a
Vec3, Color, Orbit or Clip is taken, a tuple of its numbers: the functions' stubs say so; the attributes of Look and
Frame are typed by what they hold (mypy 1.0, Debian 12's, cannot type a property's setter apart from its getter), so
type-checked code assigns the typed values (look.shading = Shading.CEL, frame.eye = Vec3(0, 1, 5))."""

import os
from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import Any, ClassVar, SupportsFloat, SupportsIndex, TypeVar, Union

import numpy as np
import numpy.typing as npt

from ._warnings import InkgraphWarning

_PathLike = Union[str, os.PathLike[str]]
_Number = Union[SupportsFloat, SupportsIndex]
_Vec3Like = Union["Vec3", Sequence[_Number], npt.NDArray[Any]]
_ColorLike = Union["Color", Sequence[_Number], npt.NDArray[Any]]
_OrbitLike = Union["Orbit", Sequence[_Number]]
_ClipLike = Union["Clip", Sequence[_Number]]
_ArrayLike = npt.ArrayLike
_Self = TypeVar("_Self")

def version() -> str: ...
def git_commit() -> str: ...
def buffer_names(look: Look) -> list[str]: ...
def sample_views(
    count: int,
    seed: int,
    model_key: _PathLike,
    *,
    elevation: Sequence[_Number] = ...,
    distance_jitter: float = 0.0,
    light_jitter: float = 0.0,
    light: _Vec3Like | None = None,
    expressions: Sequence[str] = ...,
    poses: Sequence[str] = ...,
) -> list[ViewSample]: ...
def write_image(path: _PathLike, image: npt.NDArray[np.uint8] | npt.NDArray[np.float32]) -> None: ...
def _stop_calls_for_exit() -> None: ...

# ---- The small value types: immutable, equal by their fields, replace() gives a changed copy. ----

class Vec3:
    def __init__(self, x: float = 0.0, y: float = 0.0, z: float = 0.0) -> None: ...
    @property
    def x(self) -> float: ...
    @property
    def y(self) -> float: ...
    @property
    def z(self) -> float: ...
    def replace(self, *, x: float = ..., y: float = ..., z: float = ...) -> Vec3: ...
    def __iter__(self) -> Iterator[float]: ...
    def __len__(self) -> int: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class Color:
    def __init__(self, r: float = 0.0, g: float = 0.0, b: float = 0.0, a: float = 1.0) -> None: ...
    @property
    def r(self) -> float: ...
    @property
    def g(self) -> float: ...
    @property
    def b(self) -> float: ...
    @property
    def a(self) -> float: ...
    def replace(self, *, r: float = ..., g: float = ..., b: float = ..., a: float = ...) -> Color: ...
    def __iter__(self) -> Iterator[float]: ...
    def __len__(self) -> int: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class Orbit:
    def __init__(
        self, azimuth: float = 0.0, elevation: float = 0.0, distance: float | None = None, distance_scale: float = 1.0
    ) -> None: ...
    @property
    def azimuth(self) -> float: ...
    @property
    def elevation(self) -> float: ...
    @property
    def distance(self) -> float | None: ...
    @property
    def distance_scale(self) -> float: ...
    def replace(
        self, *, azimuth: float = ..., elevation: float = ..., distance: float | None = ..., distance_scale: float = ...
    ) -> Orbit: ...
    def __iter__(self) -> Iterator[float | None]: ...
    def __len__(self) -> int: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class ViewSample:
    def __init__(
        self,
        index: int = 0,
        azimuth: float = 0.0,
        elevation: float = 0.0,
        distance_scale: float = 1.0,
        light: _Vec3Like | None = None,
        expression: str | None = None,
        pose: str | None = None,
    ) -> None: ...
    @property
    def index(self) -> int: ...
    @property
    def azimuth(self) -> float: ...
    @property
    def elevation(self) -> float: ...
    @property
    def distance_scale(self) -> float: ...
    @property
    def light(self) -> Vec3 | None: ...
    @property
    def expression(self) -> str | None: ...
    @property
    def pose(self) -> str | None: ...
    def orbit(self) -> Orbit: ...
    def replace(
        self,
        *,
        index: int = ...,
        azimuth: float = ...,
        elevation: float = ...,
        distance_scale: float = ...,
        light: _Vec3Like | None = ...,
        expression: str | None = ...,
        pose: str | None = ...,
    ) -> ViewSample: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class Clip:
    def __init__(self, near: float, far: float) -> None: ...
    @property
    def near(self) -> float: ...
    @property
    def far(self) -> float: ...
    def replace(self, *, near: float = ..., far: float = ...) -> Clip: ...
    def __iter__(self) -> Iterator[float]: ...
    def __len__(self) -> int: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class LineStyle:
    def __init__(self, width: float = 2.0, color: _ColorLike = ...) -> None: ...
    @property
    def width(self) -> float: ...
    @property
    def color(self) -> Color: ...
    def replace(self, *, width: float = ..., color: _ColorLike = ...) -> LineStyle: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class StrokeSettings:
    def __init__(
        self,
        min_length: float = 0.01,
        weight_by_depth: bool = False,
        weight_by_strength: bool = False,
        taper_ends: bool = False,
        merge_overlaps: bool = False,
    ) -> None: ...
    @property
    def min_length(self) -> float: ...
    @property
    def weight_by_depth(self) -> bool: ...
    @property
    def weight_by_strength(self) -> bool: ...
    @property
    def taper_ends(self) -> bool: ...
    @property
    def merge_overlaps(self) -> bool: ...
    def replace(
        self,
        *,
        min_length: float = ...,
        weight_by_depth: bool = ...,
        weight_by_strength: bool = ...,
        taper_ends: bool = ...,
        merge_overlaps: bool = ...,
    ) -> StrokeSettings: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

# ---- Enums: pybind11 enums; Name("word") and Name.from_name("word") take the command line's word. ----

class _Enum:
    def __init__(self, name: str) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def value(self) -> int: ...
    @property
    def cli_name(self) -> str: ...
    def __int__(self) -> int: ...
    def __index__(self) -> int: ...
    def __eq__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...

class Shading(_Enum):
    NONE: ClassVar[Shading]
    FLAT: ClassVar[Shading]
    GOURAUD: ClassVar[Shading]
    LAMBERT: ClassVar[Shading]
    PHONG: ClassVar[Shading]
    CEL: ClassVar[Shading]
    COMIC: ClassVar[Shading]
    MTOON: ClassVar[Shading]
    AUTO: ClassVar[Shading]
    __members__: ClassVar[dict[str, Shading]]
    @staticmethod
    def from_name(name: str) -> Shading: ...

class LineType(_Enum):
    HIDDEN_MESH_SILHOUETTE: ClassVar[LineType]
    HIDDEN_CREASE: ClassVar[LineType]
    HIDDEN_BORDER: ClassVar[LineType]
    HIDDEN_INTERSECTION: ClassVar[LineType]
    HIDDEN_SUGGESTIVE_OBJECT: ClassVar[LineType]
    OUTLINE: ClassVar[LineType]
    SILHOUETTE: ClassVar[LineType]
    NORMAL_EDGE: ClassVar[LineType]
    DEPTH_EDGE: ClassVar[LineType]
    CREASE: ClassVar[LineType]
    BORDER: ClassVar[LineType]
    INTERSECTION: ClassVar[LineType]
    MATERIAL_BOUNDARY: ClassVar[LineType]
    OBJECT_BOUNDARY: ClassVar[LineType]
    SUGGESTIVE: ClassVar[LineType]
    SUGGESTIVE_OBJECT: ClassVar[LineType]
    CONTOUR: ClassVar[LineType]
    MESH_SILHOUETTE: ClassVar[LineType]
    __members__: ClassVar[dict[str, LineType]]
    @staticmethod
    def from_name(name: str) -> LineType: ...

class ViewVector(_Enum):
    EXACT: ClassVar[ViewVector]
    CONSTANT: ClassVar[ViewVector]
    __members__: ClassVar[dict[str, ViewVector]]
    @staticmethod
    def from_name(name: str) -> ViewVector: ...

class FaceOrientation(_Enum):
    STANDARD: ClassVar[FaceOrientation]
    DURING_TRIANGLES: ClassVar[FaceOrientation]
    DURING_VERTICES: ClassVar[FaceOrientation]
    AFTER_VERTICES: ClassVar[FaceOrientation]
    __members__: ClassVar[dict[str, FaceOrientation]]
    @staticmethod
    def from_name(name: str) -> FaceOrientation: ...

class Precision(_Enum):
    FLOAT32: ClassVar[Precision]
    FLOAT16: ClassVar[Precision]
    __members__: ClassVar[dict[str, Precision]]
    @staticmethod
    def from_name(name: str) -> Precision: ...

class CameraPlacement(_Enum):
    FILE_OR_AUTO: ClassVar[CameraPlacement]
    AUTO: ClassVar[CameraPlacement]
    __members__: ClassVar[dict[str, CameraPlacement]]
    @staticmethod
    def from_name(name: str) -> CameraPlacement: ...

class CameraSource(_Enum):
    FILE: ClassVar[CameraSource]
    AUTO: ClassVar[CameraSource]
    ORBIT: ClassVar[CameraSource]
    EYE: ClassVar[CameraSource]
    __members__: ClassVar[dict[str, CameraSource]]
    @staticmethod
    def from_name(name: str) -> CameraSource: ...

# ---- Look and Frame ----

class Look:
    def __init__(
        self,
        *,
        shading: Shading | str = ...,
        shininess: float = ...,
        bands: int = ...,
        shade_map: _PathLike = ...,
        view_vector: ViewVector | str = ...,
        face_orientation: FaceOrientation | str = ...,
        front_rule: int = ...,
        light: _Vec3Like = ...,
        ambient: _ColorLike = ...,
        paper: _ColorLike = ...,
        supersample: int = ...,
        msaa: int = ...,
        gbuffer_precision: Precision | str = ...,
        lines: Iterable[LineType | str] = ...,
        strokes: StrokeSettings = ...,
        outline_width_map: str = ...,
    ) -> None: ...
    @staticmethod
    def from_arguments(arguments: Sequence[str]) -> Look: ...
    @staticmethod
    def from_style_file(path: _PathLike) -> Look: ...
    def set(self: _Self, flag: str, value: str = "") -> _Self: ...
    @property
    def arguments(self) -> list[str]: ...
    shading: Shading
    shininess: float
    bands: int | None
    shade_map: str
    view_vector: ViewVector
    face_orientation: FaceOrientation
    front_rule: int
    light: Vec3 | None
    ambient: Color | None
    paper: Color
    supersample: int
    msaa: int
    gbuffer_precision: Precision
    lines: list[LineType]
    strokes: StrokeSettings
    outline_width_map: str
    def line_style(self, type: LineType | str) -> LineStyle: ...
    def set_line_style(self: _Self, type: LineType | str, style: LineStyle) -> _Self: ...
    @staticmethod
    def line_parameter_names(type: LineType | str) -> list[str]: ...
    def line_parameter(self, name: str) -> float: ...
    def line_choice(self, name: str) -> str: ...
    def set_line_parameter(self: _Self, name: str, value: float) -> _Self: ...
    def set_line_choice(self: _Self, name: str, value: str) -> _Self: ...
    def __copy__(self) -> Look: ...
    def __deepcopy__(self, memo: Any) -> Look: ...

class Frame:
    def __init__(
        self,
        width: int = 1024,
        height: int = 1024,
        *,
        eye: _Vec3Like | None = ...,
        orbit: _OrbitLike | None = ...,
        target: _Vec3Like | None = ...,
        up: _Vec3Like | None = ...,
        fov: float | None = ...,
        clip: _ClipLike | None = ...,
        placement: CameraPlacement | str = ...,
        frame_nodes: Sequence[str] = ...,
        animation: str = ...,
        time: float | None = ...,
        pose: str = ...,
        expressions: Mapping[str, float] = ...,
        look_at: _Vec3Like | None = ...,
    ) -> None: ...
    @staticmethod
    def from_arguments(arguments: Sequence[str]) -> Frame: ...
    width: int
    height: int
    eye: Vec3 | None
    orbit: Orbit | None
    target: Vec3 | None
    up: Vec3 | None
    fov: float | None
    clip: Clip | None
    placement: CameraPlacement
    frame_nodes: list[str]
    animation: str
    time: float | None
    pose: str
    expressions: dict[str, float]
    look_at: Vec3 | None
    def __copy__(self) -> Frame: ...
    def __deepcopy__(self, memo: Any) -> Frame: ...

# ---- Scenes, stills, the renderer ----

class Scene:
    @staticmethod
    def load(
        path: _PathLike,
        animation: str = "",
        time: float = 0.0,
        memory_limit: int = 0,
        strict: bool = False,
        pose: str = "",
        expressions: Mapping[str, float] = ...,
        look_at: _Vec3Like | None = None,
        weld_distance: float = 1e-6,
    ) -> Scene: ...
    @staticmethod
    def from_arrays(
        vertices: _ArrayLike,
        faces: _ArrayLike,
        normals: _ArrayLike | None = None,
        uvs: _ArrayLike | None = None,
        colors: _ArrayLike | None = None,
        name: str = "arrays",
        memory_limit: int = 0,
        weld_distance: float = 1e-6,
    ) -> Scene: ...
    @property
    def path(self) -> str: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def mesh_count(self) -> int: ...
    @property
    def objects(self) -> list[dict[str, Any]]: ...
    @property
    def meshes(self) -> list[dict[str, Any]]: ...
    @property
    def warnings(self) -> list[InkgraphWarning]: ...

class StillCamera:
    @property
    def intrinsics(self) -> npt.NDArray[np.float64]: ...
    @property
    def extrinsics(self) -> npt.NDArray[np.float64]: ...
    @property
    def view(self) -> npt.NDArray[np.float64]: ...
    @property
    def projection(self) -> npt.NDArray[np.float64]: ...
    @property
    def eye(self) -> Vec3: ...
    @property
    def target(self) -> Vec3: ...
    @property
    def up(self) -> Vec3: ...
    @property
    def fov_y(self) -> float: ...
    @property
    def near(self) -> float: ...
    @property
    def far(self) -> float: ...
    @property
    def clip_given(self) -> bool: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def source(self) -> CameraSource: ...
    def as_dict(self) -> dict[str, Any]: ...

class Still:
    @property
    def picture(self) -> npt.NDArray[np.uint8]: ...
    def buffer(self, name: str) -> npt.NDArray[Any]: ...
    @property
    def buffer_names(self) -> list[str]: ...
    @property
    def camera(self) -> StillCamera: ...
    @property
    def meshes(self) -> list[dict[str, Any]]: ...
    @property
    def objects(self) -> list[dict[str, Any]]: ...
    def strokes(self) -> list[dict[str, Any]]: ...
    @property
    def warnings(self) -> list[InkgraphWarning]: ...
    def write(self, path: _PathLike) -> None: ...
    @property
    def milliseconds(self) -> float: ...

class Renderer:
    class Platform(_Enum):
        AUTO: ClassVar[Renderer.Platform]
        DEVICE: ClassVar[Renderer.Platform]
        SURFACELESS: ClassVar[Renderer.Platform]
        __members__: ClassVar[dict[str, Renderer.Platform]]
        @staticmethod
        def from_name(name: str) -> Renderer.Platform: ...

    def __init__(self, platform: Renderer.Platform | str = ...) -> None: ...
    def render(
        self,
        scene: Scene,
        look: Look | None = None,
        frame: Frame | None = None,
        buffers: Sequence[str] = ...,
        out: npt.NDArray[np.uint8] | None = None,
    ) -> Still: ...
    @property
    def gl_description(self) -> str: ...
    def close(self) -> None: ...
    @property
    def closed(self) -> bool: ...
    def __enter__(self: _Self) -> _Self: ...
    def __exit__(self, *args: object) -> None: ...
