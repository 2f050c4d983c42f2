# scripts/blender/body_roundtrip.py -- a rig as Blender gives it back to a
# user: imports a skinned, animated GLB (our body written by `layers
# tpose`, body.glb) with Blender's glTF importer, the scene at the file's
# 30 fps, and exports it again with Blender's glTF exporter as
# <out>/blender_body.glb (+Y up, skin and animation, no normals or
# materials) and with its FBX exporter as <out>/blender_body.fbx (its
# defaults: centimetres, -Z forward, Y up; the animation baked, no leaf
# bones added). Exits 0 when both were written, 77 when the glTF add-on
# cannot run (Blender without numpy). Run as:
#   blender -b --python-exit-code 1 --python scripts/blender/body_roundtrip.py -- <in.glb> <out dir>
import os
import sys

try:
    import numpy
    numpy.bool = bool  # bookworm's numpy 1.24 dropped the alias Blender 3.4's glTF add-on still uses
except ImportError:
    print("body_roundtrip: Blender's Python has no numpy: the glTF add-on cannot run")
    sys.exit(77)
import bpy

args = sys.argv[sys.argv.index("--") + 1:]
source, out = args[0], args[1]
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = 30  # the file's frame rate, before import
bpy.ops.import_scene.gltf(filepath=source)
last = 0
for action in bpy.data.actions:
    last = max(last, int(round(action.frame_range[1])))
scene.frame_start, scene.frame_end = 0, last
bpy.ops.export_scene.gltf(filepath=os.path.join(out, "blender_body.glb"), export_format='GLB', export_yup=True,
                          export_normals=False, export_materials='NONE', export_texcoords=False,
                          export_skins=True, export_animations=True, export_frame_range=False)
bpy.ops.export_scene.fbx(filepath=os.path.join(out, "blender_body.fbx"), bake_anim=True, add_leaf_bones=False,
                         bake_anim_use_all_actions=False, bake_anim_use_nla_strips=False, bake_anim_simplify_factor=0.0)
print("body_roundtrip: wrote blender_body.glb and blender_body.fbx with frames 0-%d" % last)
