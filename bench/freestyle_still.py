# The comparison still for issue 20, rendered by Blender Freestyle: the same model, size, view direction and field of
# view as `inkgraph render MODEL --shading cel --lines silhouette,contour,suggestive`, with Freestyle's silhouette,
# crease and suggestive-contour edges over a five-band toon material, rendered by EEVEE (Workbench cannot run
# Freestyle; Cycles is slower still). Run by bench/whole-process.sh:
#   blender -b --factory-startup -noaudio -P bench/freestyle_still.py -- MODEL.obj OUT.png [SIZE]
import math
import sys

import bpy
from mathutils import Vector

arguments = sys.argv[sys.argv.index("--") + 1:]
model, output = arguments[0], arguments[1]
size = int(arguments[2]) if len(arguments) > 2 else 1024

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
bpy.ops.wm.obj_import(filepath=model, forward_axis="NEGATIVE_Z", up_axis="Y")
mesh_objects = [o for o in scene.objects if o.type == "MESH"]

# Bounding sphere (box centre, farthest vertex), as inkgraph's auto-framing fits it.
points = [o.matrix_world @ v.co for o in mesh_objects for v in o.data.vertices]
low = Vector((min(p.x for p in points), min(p.y for p in points), min(p.z for p in points)))
high = Vector((max(p.x for p in points), max(p.y for p in points), max(p.z for p in points)))
centre = (low + high) / 2
radius = max((p - centre).length for p in points)

# Five flat bands of the diffuse light, like inkgraph's default cel map {0, .25, .5, .75, 1} x 0.8 grey.
material = bpy.data.materials.new("cel")
material.use_nodes = True
nodes, links = material.node_tree.nodes, material.node_tree.links
nodes.clear()
diffuse = nodes.new("ShaderNodeBsdfDiffuse")
diffuse.inputs["Color"].default_value = (0.8, 0.8, 0.8, 1.0)
to_rgb = nodes.new("ShaderNodeShaderToRGB")
ramp = nodes.new("ShaderNodeValToRGB")
ramp.color_ramp.interpolation = "CONSTANT"
stops = ramp.color_ramp.elements
stops[0].position, stops[0].color = 0.0, (0.0, 0.0, 0.0, 1.0)
stops[1].position, stops[1].color = 0.2, (0.2, 0.2, 0.2, 1.0)
for position, value in ((0.4, 0.4), (0.6, 0.6), (0.8, 0.8)):
    stop = stops.new(position)
    stop.color = (value, value, value, 1.0)
out = nodes.new("ShaderNodeOutputMaterial")
links.new(diffuse.outputs["BSDF"], to_rgb.inputs["Shader"])
links.new(to_rgb.outputs["Color"], ramp.inputs["Fac"])
links.new(ramp.outputs["Color"], out.inputs["Surface"])
for o in mesh_objects:
    o.data.materials.clear()
    o.data.materials.append(material)
    for polygon in o.data.polygons:
        polygon.use_smooth = True

# inkgraph's default view: from the front (+Z), 14.04 degrees above, the distance that fits the sphere in 35 degrees.
fov = math.radians(35.0)
distance = radius / math.sin(fov / 2)
elevation = math.radians(14.04)
camera_data = bpy.data.cameras.new("camera")
camera_data.sensor_fit = "VERTICAL"
camera_data.angle_y = fov
camera_data.clip_start = max(distance - radius, 1e-3) * 0.9
camera_data.clip_end = (distance + radius) * 1.1
camera = bpy.data.objects.new("camera", camera_data)
scene.collection.objects.link(camera)
# Blender is Z-up: inkgraph's +Y up / +Z front is Blender's +Z up / -Y front after the importer's axis change.
eye = centre + distance * Vector((0.0, -math.cos(elevation), math.sin(elevation)))
camera.location = eye
camera.rotation_euler = (centre - eye).to_track_quat("-Z", "Y").to_euler()
scene.camera = camera

sun_data = bpy.data.lights.new("sun", "SUN")
sun = bpy.data.objects.new("sun", sun_data)
scene.collection.objects.link(sun)
sun.rotation_euler = (math.radians(40), math.radians(-25), 0)

world = bpy.data.worlds.new("paper")
world.color = (1.0, 1.0, 1.0)
scene.world = world
scene.render.engine = "BLENDER_EEVEE"
scene.eevee.taa_render_samples = 1
scene.render.resolution_x = scene.render.resolution_y = size
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.view_settings.view_transform = "Standard"
scene.render.use_freestyle = True
scene.render.line_thickness_mode = "ABSOLUTE"
scene.render.line_thickness = 2.0
settings = bpy.context.view_layer.freestyle_settings
settings.crease_angle = math.radians(134.43)
settings.use_smoothness = True
lineset = settings.linesets[0] if settings.linesets else settings.linesets.new("lines")
lineset.select_by_visibility = True
lineset.select_by_edge_types = True
lineset.select_silhouette = True
lineset.select_border = True
lineset.select_crease = True
lineset.select_suggestive_contour = True
if lineset.linestyle is None:
    lineset.linestyle = bpy.data.linestyles.new("ink")
lineset.linestyle.thickness = 2.0
lineset.linestyle.color = (0.0, 0.0, 0.0)
scene.render.filepath = output
scene.render.image_settings.file_format = "PNG"
bpy.ops.render.render(write_still=True)
