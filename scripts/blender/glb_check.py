# scripts/blender/glb_check.py -- imports a GLB written by `layers export
# --format glb` into Blender (its bundled glTF importer) and compares every
# mesh's vertex positions at every frame with the OBJ files `layers export
# --format obj` wrote for the same frames (<prefix>_<mesh>_<frame>.obj).
# A mesh cut into chunks (objects "<mesh>.chunk<c>", glb.h) is read from
# the chunk shown at each frame (the one whose scale is not zero); exactly
# one must be shown.
# Prints "max difference <metres> over <n> frames, <m> meshes" and exits 0
# when it is at most 1e-5 m, 1 otherwise, 77 when the importer cannot run
# (Blender without numpy). Run as:
#   blender -b --python-exit-code 1 --python scripts/blender/glb_check.py -- <file.glb> <obj prefix> <first> <count>
import sys

try:
    import numpy
    numpy.bool = bool  # bookworm's numpy 1.24 dropped the alias Blender 3.4's importer still uses
except ImportError:
    print("glb_check: Blender's Python has no numpy: the glTF importer cannot run")
    sys.exit(77)
import bpy

args = sys.argv[sys.argv.index("--") + 1:]
glb, prefix, first, count = args[0], args[1], int(args[2]), int(args[3])
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.context.scene.render.fps = 30  # the file's frame rate, before import
bpy.ops.import_scene.gltf(filepath=glb)
scene = bpy.context.scene


def obj_positions(path):
    out = []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                out.append(tuple(float(x) for x in line.split()[1:4]))
    return out


groups = {}
for obj in scene.objects:
    if obj.type == 'MESH':
        groups.setdefault(obj.name.split(".chunk")[0], []).append(obj)
worst = 0.0
for name, objs in sorted(groups.items()):
    for k in range(count):
        scene.frame_set(k)
        shown = [o for o in objs if o.matrix_world.to_scale().x > 0.5]
        if len(shown) != 1:
            print("glb_check: %s frame %d shows %d of its %d chunks" % (name, k, len(shown), len(objs)))
            sys.exit(1)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        evaluated = shown[0].evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        # Blender is z up: (x, y, z) in glTF is (x, -z, y) here.
        got = [(v.co.x, v.co.z, -v.co.y) for v in mesh.vertices]
        evaluated.to_mesh_clear()
        want = obj_positions("%s_%s_%04d.obj" % (prefix, name, first + k))
        if len(got) != len(want):
            print("glb_check: %s frame %d has %d vertices, the OBJ %d" % (name, k, len(got), len(want)))
            sys.exit(1)
        for a, b in zip(got, want):
            worst = max(worst, abs(a[0] - b[0]), abs(a[1] - b[1]), abs(a[2] - b[2]))
print("max difference %.3g over %d frames, %d meshes" % (worst, count, len(groups)))
sys.exit(0 if worst <= 1e-5 and groups else 1)
