# scripts/blender/glb_check.py -- imports a GLB written by `layers export
# --format glb` into Blender (its bundled glTF importer) and compares every
# mesh's vertex positions at every frame with the OBJ files `layers export
# --format obj` wrote for the same frames (<prefix>_<mesh>_<frame>.obj).
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


worst, meshes = 0.0, 0
for obj in list(scene.objects):
    if obj.type != 'MESH':
        continue
    meshes += 1
    for k in range(count):
        scene.frame_set(k)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        evaluated = obj.evaluated_get(depsgraph)
        mesh = evaluated.to_mesh()
        # Blender is z up: (x, y, z) in glTF is (x, -z, y) here.
        got = [(v.co.x, v.co.z, -v.co.y) for v in mesh.vertices]
        evaluated.to_mesh_clear()
        want = obj_positions("%s_%s_%04d.obj" % (prefix, obj.name, first + k))
        if len(got) != len(want):
            print("glb_check: %s frame %d has %d vertices, the OBJ %d" % (obj.name, k, len(got), len(want)))
            sys.exit(1)
        for a, b in zip(got, want):
            worst = max(worst, abs(a[0] - b[0]), abs(a[1] - b[1]), abs(a[2] - b[2]))
print("max difference %.3g over %d frames, %d meshes" % (worst, count, meshes))
sys.exit(0 if worst <= 1e-5 and meshes > 0 else 1)
