"""Renders mesh.glb or model.vdb of `msynth synthesize` with Blender's Cycles, headless, seen
straight down through an orthographic camera that frames the model:

    blender -b --factory-startup -P Utilities/blender-render.py -- MODEL OUT.png [--size N]
        [--flat] [--oblique]

MODEL is a glTF file (mesh.glb) or an OpenVDB file (model.vdb: a volume whose `density` absorbs
and whose `color` it emits). --oblique looks from the front corner instead of straight down.

The background is transparent. With --flat every material emits its base colour instead of
shading (Standard view transform), so each pixel shows the colour the file gives the face seen
there (no blend across edges) (what the tests compare with the example's palette); without it, a sun and the sky light
the model as a picture. Debian 12's Blender 3.4 needs two things its users meet
too: its glTF importer uses numpy's removed `np.bool` (aliased here), and its Cycles has no
denoiser (turned off here)."""
import math
import sys
import warnings

import numpy as np

with warnings.catch_warnings():  # (asking numpy >= 1.24 for np.bool warns)
    warnings.simplefilter("ignore")
    if not hasattr(np, "bool"):
        np.bool = bool  # the glTF importer of Blender 3.4 with numpy >= 1.24

import bpy  # noqa: E402
import mathutils  # noqa: E402


def flatten(material):
    """The material emits its base colour (its factor, or whatever feeds it) instead of shading:
    a picture of the colours the file gives, without light or shadow."""
    tree = material.node_tree if material.use_nodes else None
    shader = tree.nodes.get("Principled BSDF") if tree else None
    output = tree.nodes.get("Material Output") if tree else None
    if not shader or not output:
        return
    emission = tree.nodes.new("ShaderNodeEmission")
    base = shader.inputs["Base Color"]
    if base.is_linked:
        tree.links.new(base.links[0].from_socket, emission.inputs["Color"])
    else:
        emission.inputs["Color"].default_value = base.default_value
    emission.inputs["Strength"].default_value = 1.0
    tree.links.new(emission.outputs["Emission"], output.inputs["Surface"])


def volume_material():
    """model.vdb's grids as a renderer reads them: `density` absorbs, strongly, so the solid sites
    are opaque, and `color` is emitted as much as it is absorbed, so what is seen is the colour
    the grid gives (no light needed)."""
    material = bpy.data.materials.new("model.vdb")
    material.use_nodes = True
    tree = material.node_tree
    for node in list(tree.nodes):
        if node.type != "OUTPUT_MATERIAL":
            tree.nodes.remove(node)
    output = tree.nodes["Material Output"]
    density = tree.nodes.new("ShaderNodeAttribute")
    density.attribute_name = "density"
    colour = tree.nodes.new("ShaderNodeAttribute")
    colour.attribute_name = "color"
    strength = tree.nodes.new("ShaderNodeMath")
    strength.operation = "MULTIPLY"
    strength.inputs[1].default_value = 20.0
    tree.links.new(density.outputs["Fac"], strength.inputs[0])
    absorb = tree.nodes.new("ShaderNodeVolumeAbsorption")
    absorb.inputs["Color"].default_value = (0, 0, 0, 1)
    tree.links.new(strength.outputs[0], absorb.inputs["Density"])
    emit = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(colour.outputs["Color"], emit.inputs["Color"])
    # `color` fades to 0 across a voxel as `density` does (both interpolated, inactive 0), so
    # emitting it at a constant strength gives the colour itself wherever the ray is absorbed.
    emit.inputs["Strength"].default_value = strength.inputs[1].default_value
    both = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(absorb.outputs[0], both.inputs[0])
    tree.links.new(emit.outputs[0], both.inputs[1])
    tree.links.new(both.outputs[0], output.inputs["Volume"])
    return material


def main(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if "--help" in args or "-h" in args:
        print(__doc__)
        return
    if len(args) < 2:
        sys.exit("usage: blender -b --factory-startup -P blender-render.py -- MODEL OUT.png "
                 "[--size N] [--flat] [--oblique]")
    glb, out = args[0], args[1]
    size = int(args[args.index("--size") + 1]) if "--size" in args else 512
    flat = "--flat" in args
    oblique = "--oblique" in args
    bpy.ops.wm.read_factory_settings(use_empty=True)
    volume = glb.endswith(".vdb")
    if volume:
        bpy.ops.object.volume_import(filepath=glb, files=[{"name": glb.rsplit("/", 1)[-1]}],
                                     directory=glb.rsplit("/", 1)[0] or ".")
    else:
        bpy.ops.import_scene.gltf(filepath=glb)
    scene = bpy.context.scene
    meshes = [o for o in scene.objects if o.type in ("MESH", "VOLUME")]
    if not meshes:
        sys.exit("blender-render: %s holds no mesh" % glb)
    if volume:
        for o in meshes:
            o.data.materials.append(volume_material())
    corners = [o.matrix_world @ mathutils.Vector(c) for o in meshes for c in o.bound_box]
    low = mathutils.Vector([min(p[i] for p in corners) for i in range(3)])
    high = mathutils.Vector([max(p[i] for p in corners) for i in range(3)])
    centre = (low + high) / 2
    extent = max(high[0] - low[0], high[1] - low[1])
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = extent * 1.05
    camera.data.clip_end = 10 * (high[2] - low[2] + extent) + 10
    if oblique:  # from the front corner, 35 degrees above the horizon
        camera.rotation_euler = (math.radians(55), 0, math.radians(35))
        camera.data.ortho_scale = extent * 1.3
        look = camera.rotation_euler.to_matrix() @ mathutils.Vector((0, 0, 1))
        camera.location = centre + look * (2 * extent + high[2] - low[2] + 1)
    else:
        camera.location = (centre[0], centre[1], high[2] + extent + 1)
        camera.rotation_euler = (0, 0, 0)  # looking down -z, +y up in the picture
    world = bpy.data.worlds.new("sky")
    scene.world = world
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0 if flat else 0.4
    if flat:
        for material in bpy.data.materials:
            flatten(material)
        scene.view_settings.view_transform = "Standard"
        scene.cycles.filter_width = 0.01  # one colour per pixel, not a blend across edges
    else:
        sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
        sun.data.energy = 3.0
        sun.rotation_euler = (0.6, 0.3, 0.8)
        scene.collection.objects.link(sun)
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 16
    scene.cycles.use_denoising = False
    scene.cycles.volume_step_rate = 0.1  # steps a tenth of a voxel: the absorption is resolved
    scene.render.resolution_x = scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.render.image_settings.file_format = "PNG"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.filepath = out
    bpy.ops.render.render(write_still=True)
    print("blender-render: %d meshes, %d materials -> %s" % (len(meshes), len(bpy.data.materials), out))


main(sys.argv)
