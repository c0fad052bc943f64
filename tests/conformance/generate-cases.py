#!/usr/bin/env python3
"""Writes the MToon conformance cases: one UV sphere per case as a VRM 0.x and a VRM 1.0 file (GLB), and
cases.json, the list the reference renderer (reference/render-references.sh) and the scoring test read.

Standard library only (json, struct, zlib: the textures are PNGs made here), and deterministic: the same script
writes the same bytes, which the scoring test checks against reference/cases.sha256, the files the references were
rendered from.

    python3 tests/conformance/generate-cases.py OUT_DIR

The sphere: radius 0.3 at (0, 1.4, 0), 64 segments by 32 rings, wound counter-clockwise seen from outside, with
outward normals and texture coordinates (u east from -Z, so that 0.5 faces +Z; v down from the north pole). No
tangents: three-vrm 3.5.5's MToon does not link with vertex tangents ("FRAGMENT varying vTangent does not match any
VERTEX varying"), so the normal map case leaves them to the renderer, as glTF allows; MikkTSpace and screen
derivatives agree here, the map tilting normals along u only. Colours are chosen in sRGB: a 0.x file stores them so
(Unity's gamma-space colours), a 1.0 file stores their linear values.
"""

import hashlib
import json
import math
import os
import struct
import sys
import zlib

CENTRE = (0.0, 1.4, 0.0)
RADIUS = 0.3
SEGMENTS = 64
RINGS = 32

# The look every case starts from (sRGB colours).
LIT = (0.95, 0.60, 0.45)
SHADE = (0.40, 0.25, 0.55)


def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def linear3(rgb):
    return [round(srgb_to_linear(c), 6) for c in rgb]


# ---------------------------------------------------------------------------------------------------------------
# PNG (8-bit, filter 0 on every row, zlib level 9: the same pixels give the same bytes)


def png(width, height, channels, pixel):
    """pixel(x, y) -> tuple of `channels` ints in [0, 255]; x, y from the top-left."""
    colour_type = {1: 0, 3: 2, 4: 6}[channels]
    rows = bytearray()
    for y in range(height):
        rows.append(0)
        for x in range(width):
            rows.extend(pixel(x, y))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes(rows), 9)) +
            chunk(b"IEND", b""))


def byte(v):
    return max(0, min(255, int(round(v * 255.0))))


def texel_centre(i, n):
    return (i + 0.5) / n


def tex_stripes_alpha():
    """Base colour: 8 bands down v, white and light blue; alpha 1 and 0.2 (a cutout keeps every other band)."""
    def pixel(x, y):
        band = int(texel_centre(y, 64) * 8) % 2
        return (255, 255, 255, 255) if band == 0 else (byte(0.55), byte(0.75), 255, byte(0.2))
    return png(8, 64, 4, pixel)


def tex_shade_multiply():
    """Shade multiply: 8 bands across u, white and green."""
    def pixel(x, y):
        band = int(texel_centre(x, 64) * 8) % 2
        return (255, 255, 255) if band == 0 else (byte(0.5), 255, byte(0.5))
    return png(64, 8, 3, pixel)


def tex_matcap():
    """Matcap: black with a soft white highlight at the upper left and a warm band at the rim."""
    def pixel(x, y):
        u, v = texel_centre(x, 64), texel_centre(y, 64)
        spot = math.exp(-((u - 0.35) ** 2 + (v - 0.35) ** 2) / 0.015)
        r = math.hypot(u - 0.5, v - 0.5) * 2.0
        rim = max(0.0, min(1.0, (r - 0.75) / 0.25))
        return (byte(0.8 * spot + 0.5 * rim), byte(0.8 * spot + 0.25 * rim), byte(0.8 * spot))
    return png(64, 64, 3, pixel)


def tex_rim_multiply():
    """Rim multiply: 8 bands across u, red and cyan."""
    def pixel(x, y):
        band = int(texel_centre(x, 64) * 8) % 2
        return (255, byte(0.2), byte(0.2)) if band == 0 else (byte(0.2), 255, 255)
    return png(64, 8, 3, pixel)


def tex_shading_shift():
    """Shading shift (R, linear): 8 bands down v, 0 and 1."""
    def pixel(x, y):
        band = int(texel_centre(y, 64) * 8) % 2
        return (0, 0, 0) if band == 0 else (255, 255, 255)
    return png(8, 64, 3, pixel)


def tex_outline_width():
    """Outline width multiply (G, linear): 8 bands down v, 1 and 0.25, so the front view's silhouette, which runs
    from pole to pole, alternates thick and thin (and the poles' vertices, one v each, agree)."""
    def pixel(x, y):
        band = int(texel_centre(y, 64) * 8) % 2
        g = 255 if band == 0 else 64
        return (g, g, g)
    return png(8, 64, 3, pixel)


def tex_normal():
    """Tangent-space normal map (linear): 16 ridges across u, the normal tilting up to 37 degrees along the
    tangent."""
    def pixel(x, y):
        u = texel_centre(x, 128)
        nx = 0.6 * math.sin(2.0 * math.pi * 16.0 * u)
        nz = math.sqrt(1.0 - nx * nx)
        return (byte(nx * 0.5 + 0.5), byte(0.5), byte(nz * 0.5 + 0.5))
    return png(128, 8, 3, pixel)


def tex_emission():
    """Emission (sRGB): 8 bands down v, white and black, so the emission has structure the metric can see."""
    def pixel(x, y):
        band = int(texel_centre(y, 64) * 8) % 2
        return (255, 255, 255) if band == 0 else (0, 0, 0)
    return png(8, 64, 3, pixel)


def tex_checker():
    """Base colour for UV animation: an 8 x 8 checker, white and orange."""
    def pixel(x, y):
        c = (int(texel_centre(x, 64) * 8) + int(texel_centre(y, 64) * 8)) % 2
        return (255, 255, 255) if c == 0 else (255, byte(0.55), byte(0.2))
    return png(64, 64, 3, pixel)


def tex_uv_mask():
    """UV animation mask: 1 on the northern half (v < 0.5), 0 on the southern, in every channel (0.x reads R in
    Unity, three-vrm and 1.0 read B)."""
    def pixel(x, y):
        m = 255 if texel_centre(y, 8) < 0.5 else 0
        return (m, m, m)
    return png(8, 8, 3, pixel)


TEXTURES = {
    "stripes_alpha": tex_stripes_alpha,
    "shade_multiply": tex_shade_multiply,
    "matcap": tex_matcap,
    "rim_multiply": tex_rim_multiply,
    "shading_shift": tex_shading_shift,
    "outline_width": tex_outline_width,
    "normal": tex_normal,
    "emission": tex_emission,
    "checker": tex_checker,
    "uv_mask": tex_uv_mask,
}

# ---------------------------------------------------------------------------------------------------------------
# The sphere


def sphere():
    positions, normals, uvs = [], [], []
    for i in range(RINGS + 1):
        theta = math.pi * i / RINGS
        for j in range(SEGMENTS + 1):
            # u = 0 (the seam) at the back (-Z), u = 0.5 facing the suite's front camera (+Z): the UV animation's
            # rotation centre (0.5, 0.5) lies at the front's centre, and the seam out of sight.
            phi = 2.0 * math.pi * j / SEGMENTS + math.pi
            n = (math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi))
            positions.append(tuple(CENTRE[k] + RADIUS * n[k] for k in range(3)))
            normals.append(n)
            uvs.append((j / SEGMENTS, i / RINGS))
    indices = []
    row = SEGMENTS + 1
    for i in range(RINGS):
        for j in range(SEGMENTS):
            a, b, c, d = i * row + j, (i + 1) * row + j, (i + 1) * row + j + 1, i * row + j + 1
            # a top-left, b bottom-left, c bottom-right, d top-right seen from outside: a, b, c and a, c, d run
            # counter-clockwise. The poles' degenerate triangles are left out.
            if i != RINGS - 1:
                indices.append((a, b, c))
            if i != 0:
                indices.append((a, c, d))
    for tri in indices:  # every face wound outward
        p = [positions[k] for k in tri]
        e1 = [p[1][k] - p[0][k] for k in range(3)]
        e2 = [p[2][k] - p[0][k] for k in range(3)]
        cross = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
        centroid = [sum(q[k] for q in p) / 3.0 - CENTRE[k] for k in range(3)]
        assert sum(cross[k] * centroid[k] for k in range(3)) > 0.0, "sphere(): a face is wound inward"
    return positions, normals, uvs, indices


# ---------------------------------------------------------------------------------------------------------------
# GLB


class Glb:
    def __init__(self):
        self.buffer = bytearray()
        self.gltf = {"asset": {"version": "2.0", "generator": "inkgraph tests/conformance/generate-cases.py"},
                     "buffers": [], "bufferViews": [], "accessors": [], "images": [], "samplers": [],
                     "textures": []}
        self.texture_index = {}

    def view(self, data, target=None):
        while len(self.buffer) % 4:
            self.buffer.append(0)
        entry = {"buffer": 0, "byteOffset": len(self.buffer), "byteLength": len(data)}
        if target is not None:
            entry["target"] = target
        self.buffer.extend(data)
        self.gltf["bufferViews"].append(entry)
        return len(self.gltf["bufferViews"]) - 1

    def accessor(self, values, kind, component=5126, target=34962, bounds=False):
        width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[kind]
        fmt = {5126: "f", 5123: "H", 5125: "I"}[component]
        flat = [c for v in values for c in (v if width > 1 else (v,))]
        data = struct.pack("<%d%s" % (len(flat), fmt), *flat)
        entry = {"bufferView": self.view(data, target), "componentType": component, "count": len(values),
                 "type": kind}
        if bounds:
            entry["min"] = [min(v[k] for v in values) for k in range(width)]
            entry["max"] = [max(v[k] for v in values) for k in range(width)]
            # the bounds as float32 stores them, so the accessor's own numbers hold
            entry["min"] = [struct.unpack("<f", struct.pack("<f", x))[0] for x in entry["min"]]
            entry["max"] = [struct.unpack("<f", struct.pack("<f", x))[0] for x in entry["max"]]
        self.gltf["accessors"].append(entry)
        return len(self.gltf["accessors"]) - 1

    def texture(self, name):
        if name not in self.texture_index:
            if not self.gltf["samplers"]:
                # linear, no mipmaps: the sphere magnifies every texture at the suite's size
                self.gltf["samplers"].append({"magFilter": 9729, "minFilter": 9729, "wrapS": 10497, "wrapT": 10497})
            self.gltf["images"].append({"name": name, "mimeType": "image/png",
                                        "bufferView": self.view(TEXTURES[name]())})
            self.gltf["textures"].append({"sampler": 0, "source": len(self.gltf["images"]) - 1})
            self.texture_index[name] = len(self.gltf["textures"]) - 1
        return self.texture_index[name]

    def bytes(self):
        while len(self.buffer) % 4:
            self.buffer.append(0)
        self.gltf["buffers"] = [{"byteLength": len(self.buffer)}]
        for key in ("images", "samplers", "textures"):
            if not self.gltf[key]:
                del self.gltf[key]
        text = json.dumps(self.gltf, sort_keys=True, separators=(",", ":")).encode("utf-8")
        while len(text) % 4:
            text += b" "
        total = 12 + 8 + len(text) + 8 + len(self.buffer)
        return (struct.pack("<III", 0x46546C67, 2, total) + struct.pack("<II", len(text), 0x4E4F534A) + text +
                struct.pack("<II", len(self.buffer), 0x004E4942) + bytes(self.buffer))


# ---------------------------------------------------------------------------------------------------------------
# Cases: each a dict of MToon settings in the 1.0 terms (colours in sRGB), written to both versions where the
# feature exists in both.

BASE = {
    "lit": LIT, "alpha": 1.0, "shade": SHADE, "shift": 0.0, "toony": 0.9,
    "rim": (0.0, 0.0, 0.0), "fresnel": 5.0, "lift": 0.0, "rimMix": 1.0,
    "outlineMode": "none", "outlineWidth": 0.0, "outlineColor": (0.0, 0.0, 0.0), "outlineMix": 1.0,
    "emission": (0.0, 0.0, 0.0), "alphaMode": "OPAQUE", "cutoff": 0.5, "doubleSided": False,
    "baseTexture": None, "emissionTexture": None, "shadeTexture": None, "matcap": None, "rimTexture": None,
    "shiftTexture": None, "shiftTextureScale": 1.0, "outlineWidthTexture": None, "normalTexture": None,
    "normalScale": 1.0,
    "uvScroll": (0.0, 0.0), "uvRotation": 0.0, "uvMask": None,
}


def case(name, summary, versions=("0", "1"), views=("front",), time=0.0, **settings):
    unknown = set(settings) - set(BASE)
    assert not unknown, "case(): unknown settings %s" % sorted(unknown)
    merged = dict(BASE)
    merged.update(settings)
    return {"name": name, "summary": summary, "versions": list(versions), "views": list(views), "time": time,
            "settings": merged}


def percent(v):
    """-0.5 -> 'minus50', 0 -> '0', 0.9 -> '90': file names without dots or signs."""
    return ("minus" if v < 0 else "plus" if v > 0 else "") + "%d" % round(abs(v) * 100)


CASES = []
for shift in (-0.5, 0.0, 0.5):
    for toony in (0.0, 0.5, 0.9):
        CASES.append(case("shift-%s-toony-%d" % (percent(shift), round(toony * 100)),
                          "shading shift %g, toony %g (0.x: _ShadeShift, _ShadeToony)" % (shift, toony),
                          views=("front", "back") if (shift, toony) == (0.0, 0.9) else ("front",),
                          shift=shift, toony=toony))
CASES += [
    case("rim-fresnel5", "rim colour light blue, fresnel power 5, lift 0, lighting mix 1",
         views=("front", "back"), rim=(0.3, 0.6, 1.0), fresnel=5.0, lift=0.0, rimMix=1.0),
    case("rim-lift", "rim colour white, fresnel power 2, lift 0.2, lighting mix 0",
         rim=(1.0, 1.0, 1.0), fresnel=2.0, lift=0.2, rimMix=0.0),
    case("rim-fresnel1", "rim colour orange, fresnel power 1, lift 0, lighting mix 0.5",
         rim=(1.0, 0.5, 0.0), fresnel=1.0, lift=0.0, rimMix=0.5),
    case("outline-world", "world outline 0.02 m, dark purple, lighting mix 0 (0.x: _OutlineWidth 2 cm, fixed colour)",
         views=("front", "back"), outlineMode="worldCoordinates", outlineWidth=0.02, outlineColor=(0.15, 0.05, 0.3),
         outlineMix=0.0),
    case("outline-screen", "screen outline factor 0.02, dark green, lighting mix 0.5 (0.x: _OutlineWidth 4 in "
         "screen mode, mixed colour)", outlineMode="screenCoordinates", outlineWidth=0.02,
         outlineColor=(0.05, 0.3, 0.1), outlineMix=0.5),
    case("emission", "emissive blue, no texture (0.x: _EmissionColor)", emission=(0.0, 0.25, 0.45)),
    case("emission-texture", "emissive orange times an emissive texture of white and black bands down v (0.x: "
         "_EmissionColor, _EmissionMap)", emission=(0.6, 0.3, 0.0), emissionTexture="emission"),
    case("textured", "base colour texture (bands down v) and shade multiply texture (bands across u)",
         baseTexture="stripes_alpha", shadeTexture="shade_multiply"),
    case("alpha-cutout", "cutout at 0.5 of the base texture's alpha bands, double-sided (0.x: _BlendMode 1, "
         "_CullMode 0)", baseTexture="stripes_alpha", alphaMode="MASK", cutoff=0.5, doubleSided=True),
    case("alpha-blend", "blended, base alpha 0.8 times the base texture's alpha bands of 1 and 0.2, single-sided "
         "(0.x: _BlendMode 2)", baseTexture="stripes_alpha", alpha=0.8, alphaMode="BLEND"),
    case("matcap", "matcap texture: a highlight at the upper left and a warm rim (0.x: _SphereAdd)",
         matcap="matcap"),
    case("rim-texture", "white rim (fresnel 2, lift 0.1) times a rim multiply texture of red and cyan bands "
         "(0.x: _RimTexture)", rim=(1.0, 1.0, 1.0), fresnel=2.0, lift=0.1, rimMix=0.0, rimTexture="rim_multiply"),
    case("shift-texture", "shading shift texture: bands down v of 0 and 1, scale 0.5, shift -0.25, toony 0.8 "
         "(1.0 only)", versions=("1",), shift=-0.25, toony=0.8, shiftTexture="shading_shift",
         shiftTextureScale=0.5),
    case("outline-width-texture", "world outline 0.02 m times a width texture of bands 1 and 0.25 down v "
         "(0.x: _OutlineWidthTexture)", outlineMode="worldCoordinates", outlineWidth=0.02,
         outlineColor=(0.15, 0.05, 0.3), outlineMix=0.0, outlineWidthTexture="outline_width"),
    case("normal-map", "tangent-space normal map of 16 ridges across u, scale 1, toony 0 (0.x: _BumpMap)",
         normalTexture="normal", toony=0.0),
    case("uv-animation", "checker base texture scrolled (0.25, 0.1) per second and rotated 0.2 rad per second on "
         "the northern half (mask), at 1 s (0.x: _UvAnimScrollX, _UvAnimScrollY, _UvAnimRotation, "
         "_UvAnimMaskTexture)", time=1.0, baseTexture="checker", uvScroll=(0.25, 0.1), uvRotation=0.2,
         uvMask="uv_mask"),
]


def glb_for(case_entry, version):
    s = case_entry["settings"]
    glb = Glb()
    positions, normals, uvs, indices = sphere()
    attributes = {"POSITION": glb.accessor(positions, "VEC3", bounds=True),
                  "NORMAL": glb.accessor(normals, "VEC3"),
                  "TEXCOORD_0": glb.accessor(uvs, "VEC2")}
    index_accessor = glb.accessor([i for tri in indices for i in tri], "SCALAR", component=5123, target=34963)
    g = glb.gltf
    g["meshes"] = [{"name": "sphere", "primitives": [{"attributes": attributes, "indices": index_accessor,
                                                      "material": 0, "mode": 4}]}]
    g["nodes"] = [{"name": "sphere", "mesh": 0}]
    g["scenes"] = [{"nodes": [0]}]
    g["scene"] = 0

    def tex(name):
        return None if name is None else glb.texture(name)

    textures = {key: tex(s[key]) for key in ("baseTexture", "emissionTexture", "shadeTexture", "matcap", "rimTexture",
                                              "shiftTexture", "outlineWidthTexture", "normalTexture", "uvMask")}
    # The glTF material: what a viewer without MToon shows, and in 1.0 the surface MToon reads.
    material = {"name": case_entry["name"],
                "pbrMetallicRoughness": {"baseColorFactor": linear3(s["lit"]) + [s["alpha"]],
                                         "metallicFactor": 0.0, "roughnessFactor": 1.0},
                "emissiveFactor": linear3(s["emission"]), "alphaMode": s["alphaMode"],
                "doubleSided": s["doubleSided"]}
    if s["alphaMode"] == "MASK":
        material["alphaCutoff"] = s["cutoff"]
    if textures["baseTexture"] is not None:
        material["pbrMetallicRoughness"]["baseColorTexture"] = {"index": textures["baseTexture"]}
    if textures["emissionTexture"] is not None:
        material["emissiveTexture"] = {"index": textures["emissionTexture"]}
    if textures["normalTexture"] is not None:
        material["normalTexture"] = {"index": textures["normalTexture"], "scale": s["normalScale"]}
    g["materials"] = [material]

    if version == "1":
        mtoon = {
            "specVersion": "1.0", "transparentWithZWrite": False, "renderQueueOffsetNumber": 0,
            "shadeColorFactor": linear3(s["shade"]), "shadingShiftFactor": s["shift"],
            "shadingToonyFactor": s["toony"], "giEqualizationFactor": 0.9, "matcapFactor": [1.0, 1.0, 1.0],
            "parametricRimColorFactor": linear3(s["rim"]), "rimLightingMixFactor": s["rimMix"],
            "parametricRimFresnelPowerFactor": s["fresnel"], "parametricRimLiftFactor": s["lift"],
            "outlineWidthMode": s["outlineMode"], "outlineWidthFactor": s["outlineWidth"],
            "outlineColorFactor": linear3(s["outlineColor"]), "outlineLightingMixFactor": s["outlineMix"],
            "uvAnimationScrollXSpeedFactor": s["uvScroll"][0], "uvAnimationScrollYSpeedFactor": s["uvScroll"][1],
            "uvAnimationRotationSpeedFactor": s["uvRotation"],
        }
        for key, prop in (("shadeTexture", "shadeMultiplyTexture"), ("matcap", "matcapTexture"),
                          ("rimTexture", "rimMultiplyTexture"), ("outlineWidthTexture", "outlineWidthMultiplyTexture"),
                          ("uvMask", "uvAnimationMaskTexture")):
            if textures[key] is not None:
                mtoon[prop] = {"index": textures[key]}
        if textures["shiftTexture"] is not None:
            mtoon["shadingShiftTexture"] = {"index": textures["shiftTexture"], "scale": s["shiftTextureScale"]}
        material["extensions"] = {"VRMC_materials_mtoon": mtoon}
        g["extensionsUsed"] = ["VRMC_materials_mtoon", "VRMC_vrm"]
        g["extensions"] = {"VRMC_vrm": {
            "specVersion": "1.0",
            "meta": {"name": case_entry["name"], "version": "1", "authors": ["inkgraph conformance suite"],
                     "licenseUrl": "https://vrm.dev/licenses/1.0/", "avatarPermission": "everyone",
                     "commercialUsage": "corporation", "creditNotation": "unnecessary", "allowRedistribution": True,
                     "modification": "allowModificationRedistribution"}}}
    else:
        blend = {"OPAQUE": 0, "MASK": 1, "BLEND": 2}[s["alphaMode"]]
        floats = {
            "_Cutoff": s["cutoff"], "_BumpScale": s["normalScale"], "_ReceiveShadowRate": 1.0,
            "_ShadingGradeRate": 1.0, "_ShadeShift": s["shift"], "_ShadeToony": s["toony"],
            "_LightColorAttenuation": 0.0, "_IndirectLightIntensity": 0.1, "_RimLightingMix": s["rimMix"],
            "_RimFresnelPower": s["fresnel"], "_RimLift": s["lift"],
            "_OutlineWidthMode": {"none": 0, "worldCoordinates": 1, "screenCoordinates": 2}[s["outlineMode"]],
            # 0.x widths: world in centimetres; screen in percent of half the height (the 1.0 factor x 200)
            "_OutlineWidth": s["outlineWidth"] * (100.0 if s["outlineMode"] == "worldCoordinates" else 200.0),
            "_OutlineScaledMaxDistance": 1.0,
            "_OutlineColorMode": 0 if s["outlineMix"] == 0.0 else 1, "_OutlineLightingMix": s["outlineMix"] or 1.0,
            "_UvAnimScrollX": s["uvScroll"][0], "_UvAnimScrollY": s["uvScroll"][1],
            "_UvAnimRotation": s["uvRotation"], "_MToonVersion": 38, "_DebugMode": 0, "_BlendMode": blend,
            "_CullMode": 0 if s["doubleSided"] else 2, "_OutlineCullMode": 1,
            "_SrcBlend": 5 if blend == 2 else 1, "_DstBlend": 10 if blend == 2 else 0,
            "_ZWrite": 0 if blend == 2 else 1, "_AlphaToMask": 0, "_IsFirstSetup": 0,
        }
        vectors = {
            "_Color": list(s["lit"]) + [s["alpha"]], "_ShadeColor": list(s["shade"]) + [1.0],
            "_RimColor": list(s["rim"]) + [1.0], "_OutlineColor": list(s["outlineColor"]) + [1.0],
            "_EmissionColor": list(s["emission"]) + [1.0], "_MainTex": [0.0, 0.0, 1.0, 1.0],
        }
        texture_properties = {}
        for key, prop in (("baseTexture", "_MainTex"), ("emissionTexture", "_EmissionMap"),
                          ("shadeTexture", "_ShadeTexture"), ("matcap", "_SphereAdd"),
                          ("rimTexture", "_RimTexture"), ("outlineWidthTexture", "_OutlineWidthTexture"),
                          ("normalTexture", "_BumpMap"), ("uvMask", "_UvAnimMaskTexture")):
            if textures[key] is not None:
                texture_properties[prop] = textures[key]
        keywords = {}
        if blend == 1:
            keywords["_ALPHATEST_ON"] = True
        if blend == 2:
            keywords["_ALPHABLEND_ON"] = True
        if textures["normalTexture"] is not None:
            keywords["_NORMALMAP"] = True
        if s["outlineMode"] == "worldCoordinates":
            keywords["MTOON_OUTLINE_WIDTH_WORLD"] = True
        elif s["outlineMode"] == "screenCoordinates":
            keywords["MTOON_OUTLINE_WIDTH_SCREEN"] = True
        if s["outlineMode"] != "none":
            keywords["MTOON_OUTLINE_COLOR_FIXED" if s["outlineMix"] == 0.0 else "MTOON_OUTLINE_COLOR_MIXED"] = True
        g["extensionsUsed"] = ["VRM"]
        g["extensions"] = {"VRM": {
            "exporterVersion": "inkgraph-conformance-1", "specVersion": "0.0",
            "meta": {"title": case_entry["name"], "version": "1", "author": "inkgraph conformance suite",
                     "allowedUserName": "Everyone", "violentUssageName": "Allow", "sexualUssageName": "Allow",
                     "commercialUssageName": "Allow", "licenseName": "CC0"},
            "materialProperties": [{
                "name": case_entry["name"], "shader": "VRM/MToon",
                "renderQueue": {0: 2000, 1: 2450, 2: 3000}[blend],
                "floatProperties": floats, "vectorProperties": vectors, "textureProperties": texture_properties,
                "keywordMap": keywords,
                "tagMap": {"RenderType": {0: "Opaque", 1: "TransparentCutout", 2: "Transparent"}[blend]},
            }]}}
    return glb.bytes()


def main(argv):
    if len(argv) != 2:
        sys.stderr.write("usage: generate-cases.py OUT_DIR\n")
        return 2
    out = argv[1]
    os.makedirs(out, exist_ok=True)
    listing = []
    sums = []
    for entry in CASES:
        for version in entry["versions"]:
            file_name = "v%s-%s.vrm" % (version, entry["name"])
            data = glb_for(entry, version)
            with open(os.path.join(out, file_name), "wb") as f:
                f.write(data)
            sums.append("%s  %s" % (hashlib.sha256(data).hexdigest(), file_name))
            listing.append({"name": "v%s-%s" % (version, entry["name"]), "file": file_name, "vrm": version,
                            "case": entry["name"], "summary": entry["summary"], "views": entry["views"],
                            "time": entry["time"]})
    with open(os.path.join(out, "cases.json"), "w") as f:
        json.dump({"cases": listing}, f, indent=1, sort_keys=True)
        f.write("\n")
    with open(os.path.join(out, "cases.sha256"), "w") as f:
        f.write("\n".join(sums) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
