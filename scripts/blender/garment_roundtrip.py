# scripts/blender/garment_roundtrip.py -- a garment as Blender gives it to
# a user: imports an OBJ (one of our templates written by `layers tpose`)
# with Blender's OBJ importer and exports it again with Blender's own
# exporters, as OBJ (<out>/blender.obj: UVs, no normals or materials,
# Blender's default axes, y up) and as glTF binary (<out>/blender.glb:
# +Y up). Exits 0 when both were written, 77 when the glTF exporter cannot
# run (Blender without numpy). Run as:
#   blender -b --python-exit-code 1 --python scripts/blender/garment_roundtrip.py -- <in.obj> <out dir>
import os
import sys

try:
    import numpy
    numpy.bool = bool  # bookworm's numpy 1.24 dropped the alias Blender 3.4's glTF add-on still uses
except ImportError:
    print("garment_roundtrip: Blender's Python has no numpy: the glTF exporter cannot run")
    sys.exit(77)
import bpy

args = sys.argv[sys.argv.index("--") + 1:]
source, out = args[0], args[1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.wm.obj_import(filepath=source)
bpy.ops.wm.obj_export(filepath=os.path.join(out, "blender.obj"), export_materials=False, export_normals=False,
                      export_uv=True)
bpy.ops.export_scene.gltf(filepath=os.path.join(out, "blender.glb"), export_format='GLB', export_yup=True,
                          export_normals=False, export_materials='NONE', export_texcoords=True)
print("garment_roundtrip: wrote blender.obj and blender.glb")
