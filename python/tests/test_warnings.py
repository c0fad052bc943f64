"""Warnings (issue 33): each record of a load or a render is an inkgraph.InkgraphWarning, listed (Scene.warnings,
Still.warnings, Result.warnings) and issued through Python's warnings module, so its filters apply: "error" makes the
call raise, "ignore" silences it. The codes are docs/robustness.md's ("Warning codes")."""

from __future__ import annotations

import base64
import json
import pathlib
import pickle
import struct
import warnings

import pytest

import inkgraph

SIZE = 64


def write_missing_texture_obj(folder: pathlib.Path) -> pathlib.Path:
    (folder / "skin.mtl").write_text("newmtl skin\nKd 0.8 0.6 0.5\nmap_Kd missing.png\n")
    model = folder / "tri.obj"
    model.write_text("mtllib skin.mtl\nusemtl skin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
                     "f 1/1/1 2/2/1 3/3/1\n")
    return model


def write_ktx2_only_gltf(folder: pathlib.Path) -> pathlib.Path:
    """A triangle whose material's texture has only a KHR_texture_basisu (KTX2) source, no PNG or JPEG."""
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    uvs = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
    data = positions + uvs
    gltf = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_texture_basisu"],
        "buffers": [{"uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode(),
                     "byteLength": len(data)}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
        "images": [{"uri": "skin.ktx2", "mimeType": "image/ktx2"}],
        "textures": [{"extensions": {"KHR_texture_basisu": {"source": 0}}}],
        "materials": [{"name": "skin", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    model = folder / "basisu.gltf"
    model.write_text(json.dumps(gltf))
    return model


def test_a_missing_texture_is_a_record_and_a_python_warning(tmp_path):
    model = write_missing_texture_obj(tmp_path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        scene = inkgraph.Scene.load(model)
    records = [w for w in scene.warnings if w.code == "texture-missing"]
    assert len(records) == 1, scene.warnings
    record = records[0]
    assert isinstance(record, inkgraph.InkgraphWarning) and isinstance(record, UserWarning)
    assert record.file.endswith("missing.png") and "missing.png" in str(record) and record.message == str(record)
    assert record.item == "skin" or "skin" in record.message, record
    issued = [w for w in caught if issubclass(w.category, inkgraph.InkgraphWarning)]
    assert [w.message for w in issued] == scene.warnings
    # Attributed to the caller's line, here, not to the package.
    assert all(pathlib.Path(w.filename).name == pathlib.Path(__file__).name for w in issued), issued

    # inkgraph.render() loads the file: the load's records are the result's, issued from the caller's line too.
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = inkgraph.render(model, size=SIZE)
    assert "texture-missing" in [w.code for w in result.warnings]
    issued = [w for w in caught if issubclass(w.category, inkgraph.InkgraphWarning)]
    assert [w.message for w in issued] == result.warnings
    assert all(pathlib.Path(w.filename).name == pathlib.Path(__file__).name for w in issued), issued


def test_a_ktx2_only_texture_is_a_record_naming_the_texture(tmp_path):
    model = write_ktx2_only_gltf(tmp_path)
    with pytest.warns(inkgraph.InkgraphWarning) as caught:
        scene = inkgraph.Scene.load(model)
    records = [w for w in scene.warnings if w.code == "texture-without-core-image"]
    assert len(records) == 1, scene.warnings
    assert "KHR_texture_basisu" in records[0].message and records[0].item, records[0]
    assert any(w.message.code == "texture-without-core-image" for w in caught)
    # It still renders, untextured.
    with pytest.warns(inkgraph.InkgraphWarning):
        assert inkgraph.render(model, size=SIZE).picture.shape == (SIZE, SIZE, 4)


def test_the_error_filter_makes_the_call_raise(tmp_path):
    model = write_missing_texture_obj(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("error", inkgraph.InkgraphWarning)
        with pytest.raises(inkgraph.InkgraphWarning) as caught:
            inkgraph.Scene.load(model)
        with pytest.raises(inkgraph.InkgraphWarning):
            inkgraph.render(model, size=SIZE)
    assert caught.value.code == "texture-missing"
    # A filter on the code alone: the message names the texture, the category is inkgraph's.
    with warnings.catch_warnings():
        warnings.simplefilter("error", inkgraph.InkgraphWarning)
        warnings.filterwarnings("ignore", message=".*missing.png", category=inkgraph.InkgraphWarning)
        assert inkgraph.Scene.load(model).warnings


def test_the_ignore_filter_silences_them_and_the_records_stay(tmp_path):
    model = write_missing_texture_obj(tmp_path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("ignore", inkgraph.InkgraphWarning)
        result = inkgraph.render(model, size=SIZE)
    assert not caught and result.warnings


def test_a_render_warning_is_the_stills(suzanne):
    # A camera that looks away from the model: a warning of the render, not of the load.
    look = inkgraph.Look(shading="flat")
    frame = inkgraph.Frame(SIZE, SIZE, eye=(0, 0, 10), target=(0, 0, 20))
    with pytest.warns(inkgraph.InkgraphWarning) as caught:
        still = inkgraph.default_renderer().render(suzanne, look, frame)
    assert still.warnings and [w.message for w in caught] == still.warnings
    assert all(w.code for w in still.warnings)


def test_records_compare_and_pickle():
    record = inkgraph.InkgraphWarning("a message", code="texture-missing", file="a.png", item="skin")
    same = inkgraph.InkgraphWarning("a message", code="texture-missing", file="a.png", item="skin")
    assert record == same and hash(record) == hash(same) and record != inkgraph.InkgraphWarning("a message")
    copy = pickle.loads(pickle.dumps(record))
    assert copy == record and (copy.code, copy.file, copy.item) == ("texture-missing", "a.png", "skin")
    assert "code='texture-missing'" in repr(record)


def test_an_undecodable_texture_is_a_record_of_the_still_and_strict_makes_it_an_input_error(tmp_path):
    # Issue 35: a texture whose bytes cannot be decoded no longer fails the render; the still's records say so with
    # texture-undecodable, and a scene loaded strict fails its render (InputError) as --strict fails the command.
    (tmp_path / "skin.mtl").write_text("newmtl skin\nKd 0.8 0.6 0.5\nmap_Kd skin.png\n")
    (tmp_path / "skin.png").write_bytes(b"this is not a PNG")
    model = tmp_path / "tri.obj"
    model.write_text("mtllib skin.mtl\nusemtl skin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
                     "f 1/1/1 2/2/1 3/3/1\n")
    with warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        result = inkgraph.render(model, size=SIZE)
    assert "texture-undecodable" in [w.code for w in result.still.warnings], result.still.warnings

    strict = inkgraph.Scene.load(model, strict=True)  # the load itself has nothing to say
    with pytest.raises(inkgraph.InputError) as caught:
        inkgraph.render(strict, size=SIZE)
    assert "--strict" in str(caught.value) and "skin.png" in str(caught.value)


def test_strict_load_refuses_a_model_with_load_warnings(tmp_path):
    model = write_missing_texture_obj(tmp_path)
    with pytest.raises(inkgraph.InputError) as caught:
        inkgraph.Scene.load(model, strict=True)
    assert "SceneOptions::strict" in str(caught.value) and "missing.png" in str(caught.value), caught.value
