# Blender's side of the Cycles comparison (benchmarks/cycles/README.md), run by bench.py as
#   blender -b --factory-startup -P benchmarks/cycles/cycles_scene.py -- CONFIG.json
# It imports city.glb (glTF's y-up frame turned back to Exacity's x east, y north, z up by
# the importer and the file's root translation, so coordinates are the city's), sets up
# the camera, Exacity's sky as an environment map, its sun as a sun lamp, and Cycles on
# the CPU, then renders each run of CONFIG's "runs" to a linear EXR and times it. Writes
# CONFIG's "times" file: seconds per run, each the CPU time (user and system, every thread)
# of bpy.ops.render.render (scene sync, BVH build and path tracing; not the import).
import json
import math
import sys
import time

import bpy
import numpy
from mathutils import Vector

# Debian's Blender 3.4 glTF importer uses numpy.bool, which numpy 1.24 removed (Debian 12
# ships 1.24): the alias is given back for it.
numpy.bool = bool

config = json.load(open(sys.argv[sys.argv.index("--") + 1]))

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=config["glb"])
scene = bpy.context.scene

# Materials: Exacity shades everything Lambertian but glass and water, which get a GGX coat
# (render/material.h). The importer gives every glTF material a Principled BSDF (a specular
# layer on everything); all but water become a Diffuse BSDF of the same base colour.
for material in bpy.data.materials:
    if not material.use_nodes:
        continue
    nodes, links = material.node_tree.nodes, material.node_tree.links
    principled = next((n for n in nodes if n.type == "BSDF_PRINCIPLED"), None)
    output = next((n for n in nodes if n.type == "OUTPUT_MATERIAL"), None)
    if principled is None or output is None or "water" in material.name or "glass" in material.name:
        continue
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    base = principled.inputs["Base Color"]
    diffuse.inputs["Color"].default_value = base.default_value
    for link in list(base.links):
        links.new(link.from_socket, diffuse.inputs["Color"])
    links.new(diffuse.outputs["BSDF"], output.inputs["Surface"])
    nodes.remove(principled)

# The ground beyond the city: Exacity's infinite plane of grass (before its noise pattern),
# here a 40 km square at the lowest point of the city, 5 cm under it.
low = min((o.matrix_world @ Vector(c)).z for o in scene.objects if o.type == "MESH" for c in o.bound_box)
bpy.ops.mesh.primitive_plane_add(size=40000, location=(0, 0, low - 0.05))
grass = bpy.data.materials.new("exacity_grass")
grass.use_nodes = True
grass_bsdf = grass.node_tree.nodes["Principled BSDF"]
grass.node_tree.nodes.remove(grass_bsdf)
diffuse = grass.node_tree.nodes.new("ShaderNodeBsdfDiffuse")
diffuse.inputs["Color"].default_value = (*config["grass_albedo"], 1)
grass.node_tree.links.new(diffuse.outputs["BSDF"], grass.node_tree.nodes["Material Output"].inputs["Surface"])
bpy.context.object.data.materials.append(grass)

# The camera: Exacity's look-at camera (render/camera.h), vertical field of view.
camera = config["camera"]
cam_data = bpy.data.cameras.new("exacity")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(camera["fov_y"])
cam_data.clip_start, cam_data.clip_end = 0.1, 100000
cam = bpy.data.objects.new("exacity", cam_data)
scene.collection.objects.link(cam)
cam.location = Vector(camera["from"])
cam.rotation_euler = (Vector(camera["to"]) - Vector(camera["from"])).to_track_quat("-Z", "Y").to_euler()
scene.camera = cam

# The sky without its sun, as exacity_sky_map wrote it, and the sun as a lamp of the same
# irradiance, colour and angular size.
world = bpy.data.worlds.new("exacity_sky")
world.use_nodes = True
background = world.node_tree.nodes["Background"]
environment = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
environment.image = bpy.data.images.load(config["sky_map"])
environment.image.colorspace_settings.name = "Linear"
environment.interpolation = "Linear"
world.node_tree.links.new(environment.outputs["Color"], background.inputs["Color"])
background.inputs["Strength"].default_value = 1
scene.world = world
sun = config["sun"]
irradiance = sun["sun_irradiance"]
strength = max(irradiance)
if strength > 0:  # at night no sun lamp: it would still be drawn among the lights
    sun_data = bpy.data.lights.new("exacity_sun", "SUN")
    sun_data.energy = strength
    sun_data.color = [c / strength for c in irradiance]
    sun_data.angle = math.radians(sun["sun_diameter_deg"])
    sun_lamp = bpy.data.objects.new("exacity_sun", sun_data)
    scene.collection.objects.link(sun_lamp)
    sun_lamp.rotation_euler = Vector(sun["sun_direction"]).to_track_quat("Z", "Y").to_euler()

# The street lamps at night (render/night.h), where CONFIG names them: each a point light of
# Exacity's lamp, its intensity I straight down (Cycles' point light of power P sends P/4π
# a steradian, so P = 4πI), the lobe kUplight + (1 - kUplight)·max(0, -d.z) over the
# direction d leaving it and the window (1 - (r/reach)^4)^2 on the inverse square out to its
# reach made by the light's own nodes: the Normal texture coordinate is d, the Light
# Falloff node's Linear output at strength 1 is the distance r. Cycles 3.4 draws one light
# among all of them by power (no light tree), Exacity one among those within the reach.
# Lit windows and the lamps' glowing heads are Exacity's procedural surfaces, not in the
# glTF: Cycles has neither.
def lamp_light(intensity, uplight, reach):
    light = bpy.data.lights.new(f"exacity_lamp_{intensity:g}", "POINT")
    light.energy = 4 * math.pi * intensity
    light.shadow_soft_size = 0
    light.use_nodes = True
    tree = light.node_tree
    nodes, links = tree.nodes, tree.links
    emission = next(n for n in nodes if n.type == "EMISSION")

    def math_node(operation, a, b):
        node = nodes.new("ShaderNodeMath")
        node.operation = operation
        for socket, value in zip(node.inputs, (a, b)):
            if isinstance(value, (int, float)):
                socket.default_value = value
            else:
                links.new(value, socket)
        return node.outputs[0]

    coordinates = nodes.new("ShaderNodeTexCoord")
    split = nodes.new("ShaderNodeSeparateXYZ")
    links.new(coordinates.outputs["Normal"], split.inputs[0])
    down = math_node("MAXIMUM", math_node("MULTIPLY", split.outputs["Z"], -1), 0)
    lobe = math_node("ADD", math_node("MULTIPLY", down, 1 - uplight), uplight)
    falloff = nodes.new("ShaderNodeLightFalloff")
    falloff.inputs["Strength"].default_value = 1
    x = math_node("DIVIDE", falloff.outputs["Linear"], reach)
    x4 = math_node("POWER", x, 4)
    inside = math_node("MAXIMUM", math_node("SUBTRACT", 1, x4), 0)
    window = math_node("MULTIPLY", inside, inside)
    links.new(math_node("MULTIPLY", lobe, window), emission.inputs["Strength"])
    return light


if config.get("lamps"):
    lamps = config["lamps"]
    lights = {}
    for x, y, z, intensity in lamps["lamps"]:
        if intensity not in lights:
            lights[intensity] = lamp_light(intensity, lamps["uplight"], lamps["reach_m"])
        lamp = bpy.data.objects.new("exacity_lamp", lights[intensity])
        lamp.location = (x, y, z)
        scene.collection.objects.link(lamp)

# Cycles as close to Exacity's path tracer as it goes: CPU, 2 threads, fixed samples (no
# adaptive sampling), the same maximum bounces, no clamping, a one-pixel box filter (Exacity
# jitters each sample within its pixel), linear output.
scene.render.engine = "CYCLES"
cycles = scene.cycles
cycles.device = "CPU"
cycles.use_adaptive_sampling = False
cycles.max_bounces = cycles.diffuse_bounces = cycles.glossy_bounces = config["max_bounces"]
cycles.transmission_bounces = cycles.transparent_max_bounces = config["max_bounces"]
cycles.volume_bounces = 0
cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0
cycles.filter_width = 1.0
cycles.pixel_filter_type = "BOX"
cycles.seed = 0
scene.render.threads_mode = "FIXED"
scene.render.threads = config["threads"]
scene.render.resolution_x, scene.render.resolution_y = config["size"]
scene.render.resolution_percentage = 100
scene.render.film_transparent = False
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.render.image_settings.exr_codec = "ZIP"

times = {}
for run in config["runs"]:
    cycles.samples = run["spp"]
    cycles.use_denoising = run.get("denoise", False)
    if cycles.use_denoising:
        cycles.denoiser = "OPENIMAGEDENOISE"
    start = time.process_time()
    bpy.ops.render.render()
    times[run["name"]] = time.process_time() - start
    bpy.data.images["Render Result"].save_render(run["exr"])
    print(f"cycles {run['name']}: {run['spp']} spp in {times[run['name']]:.2f} CPU s", flush=True)
json.dump(times, open(config["times"], "w"), indent=1)
