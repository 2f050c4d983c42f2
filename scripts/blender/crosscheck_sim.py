# scripts/blender/crosscheck_sim.py -- re-simulates one exported LAYERS
# sequence with Blender's cloth solver, for `layers crosscheck`
# (docs/sim.md "Cross-check against Blender").
#
# Runs inside Blender (tested with Debian's 3.4.1):
#   blender -b -t 1 --factory-startup --python crosscheck_sim.py -- \
#       --scene DIR/crosscheck.json --setup merged|separate --frames N --out OUT
#
# DIR is a folder written by `layers export --format pc2` plus the
# crosscheck.json that `layers crosscheck` writes beside it: the body's
# <seq>_body.obj/.pc2, each garment's frame-0 <seq>_<mesh>.obj, its rest
# shape <seq>_<mesh>_rest.obj, layer and attributes, the per-frame wind
# and the gaps our solver keeps (mapped to Blender's distances so that its
# effective gaps equal ours: blender_distances()).
# Without crosscheck.json (a plain export), garments get the middle of the
# paper's attribute ranges, layers from their names and no wind.
#
# Meshes are built from the OBJ files with from_pydata (no importer), so
# vertex order is the exported order. Coordinates stay as stored (metres,
# y up): the scene's gravity is set to (0, -9.81, 0) instead of rotating
# anything. Dataset frame t is Blender frame t + 1; frame 0 is the stored
# frame 0 (the cloth starts there at rest velocity). Writes OUT/<mesh>.pc2
# per garment (frames 0..N-1, same vertex order) and OUT/timing.txt
# ("ms_per_frame <mean>" over frames 1..N-1); prints the time of each frame.
# The garment attributes are used as Blender's cloth settings as they are
# (the paper's recipe); docs/sim.md tabulates the whole mapping.
import argparse
import json
import os
import struct
import sys
import time
from array import array

try:
    import bpy
except ImportError:  # outside Blender: only the file helpers (tests) are usable
    bpy = None

LAYER_OUTER_NAMES = ("jacket", "jacket_hood")
SELF_COLLISION_NAMES = ("skirt", "dress", "jacket_hood")  # as the generator's self-contact
DEFAULT_ATTRIBUTES = {"mass": 0.5, "tension": 57.5, "compression": 57.5, "shear": 57.5,
                      "bending": 107.5, "friction": 60.0, "self_friction": 60.0}

# The gaps our solver keeps (m; crosscheck.json "gaps", else the solver's
# defaults): garment-body, inner-outer garment, within one garment.
DEFAULT_GAPS = {"body": 0.005, "layer": 0.004, "self": 0.004}
# Blender 3.4.1 (source/blender/blenkernel/intern/collision.cc) pushes a
# cloth to (distance_min + the collider's thickness_outer) * 8/9 from a
# collider, and two self-colliding parts to 2 * self_distance_min * 8/9
# from each other. blender_distances() inverts that, so that Blender's
# effective gaps equal ours.
EFFECTIVE = 8.0 / 9.0


def blender_distances(gaps, merged):
    """Blender's cloth distance_min, the body's and an inner garment's
    thickness_outer, and self_distance_min for our gaps. In the merged
    setup the layers meet through self-collision: the self distance then
    keeps the larger of the layer and self gaps."""
    cloth = 0.75 * min(gaps["body"], gaps["layer"]) / EFFECTIVE
    self_gap = max(gaps["layer"], gaps["self"]) if merged else gaps["self"]
    return {"cloth_distance": cloth,
            "body_thickness_outer": gaps["body"] / EFFECTIVE - cloth,
            "layer_thickness_outer": gaps["layer"] / EFFECTIVE - cloth,
            "self_distance": self_gap / (2.0 * EFFECTIVE)}


QUALITY = 5                    # solver steps per frame


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="crosscheck_sim.py")
    p.add_argument("--scene", required=True, help="crosscheck.json, or an export folder")
    p.add_argument("--setup", choices=("merged", "separate"), required=True)
    p.add_argument("--frames", type=int, required=True)
    p.add_argument("--out", required=True)
    return p.parse_args(argv)


def read_obj(path):
    """Vertices and triangles (fan-triangulated), in file order."""
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append((float(parts[1]), float(parts[2]), float(parts[3])))
            elif parts[0] == "f":
                idx = []
                for corner in parts[1:]:
                    i = int(corner.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):
                    faces.append((idx[0], idx[k], idx[k + 1]))
    return verts, faces


def write_pc2(path, frames, n_points):
    """POINTCACHE2: header, then frames of n_points x float32[3], little-endian."""
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(struct.pack("<12siiffi", b"POINTCACHE2\0", 1, n_points, 0.0, 1.0, len(frames)))
        for coords in frames:
            data = array("f", coords)
            if sys.byteorder != "little":
                data.byteswap()
            f.write(data.tobytes())
    os.replace(tmp, path)


def load_scene(arg):
    """The scene description: crosscheck.json, or one made from an export folder."""
    if os.path.isfile(arg):
        with open(arg) as f:
            scene = json.load(f)
        scene["dir"] = os.path.dirname(os.path.abspath(arg))
        for g in scene["garments"]:  # an attribute the dataset lacks gets the middle of its range
            g["attributes"] = dict(DEFAULT_ATTRIBUTES, **g["attributes"])
        return scene
    objs = sorted(n for n in os.listdir(arg) if n.endswith(".obj") and not n.endswith("_rest.obj"))
    body = [n for n in objs if n.endswith("_body.obj")]
    if len(body) != 1:
        raise SystemExit("crosscheck_sim: error: expected one <seq>_body.obj in " + arg)
    prefix = body[0][:-len("body.obj")]
    garments = []
    for n in objs:
        if n == body[0] or not n.startswith(prefix):
            continue
        name = n[len(prefix):-4]
        garments.append({"mesh": name, "layer": 1 if name.startswith(LAYER_OUTER_NAMES) else 0,
                         "self_collision": name.startswith(SELF_COLLISION_NAMES),
                         "attributes": dict(DEFAULT_ATTRIBUTES)})
    return {"dir": os.path.abspath(arg), "prefix": prefix, "garments": garments, "wind": None}


def new_object(name, verts, faces):
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.validate(clean_customdata=False)
    if len(mesh.vertices) != len(verts):
        raise SystemExit("crosscheck_sim: error: Blender changed the vertex count of " + name)
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def add_rest_shape(obj, rest):
    """Springs take their rest lengths from a 'rest' shape key (value 0)."""
    obj.shape_key_add(name="Basis", from_mix=False)
    key = obj.shape_key_add(name="rest", from_mix=False)
    flat = [c for v in rest for c in v]
    key.data.foreach_set("co", flat)
    key.value = 0.0
    return key.name


def add_collider(obj, thickness_outer, friction):
    obj.modifiers.new("collision", "COLLISION")
    c = obj.collision
    c.thickness_outer = thickness_outer
    c.thickness_inner = 0.01
    c.cloth_friction = friction
    c.damping = 0.0


def add_cloth(obj, attrs, rest_key, colliders, self_collision, dist):
    """Blender cloth with the garment's attributes as its settings (docs/sim.md)."""
    mod = obj.modifiers.new("cloth", "CLOTH")
    s = mod.settings
    s.quality = QUALITY
    s.mass = attrs["mass"]
    s.tension_stiffness = attrs["tension"]
    s.compression_stiffness = attrs["compression"]
    s.shear_stiffness = attrs["shear"]
    s.bending_stiffness = attrs["bending"]
    s.rest_shape_key = obj.data.shape_keys.key_blocks[rest_key]
    c = mod.collision_settings
    c.use_collision = True
    c.distance_min = dist["cloth_distance"]
    c.collision_quality = 2
    c.friction = attrs["friction"]
    c.collection = colliders
    c.use_self_collision = self_collision
    c.self_distance_min = dist["self_distance"]
    c.self_friction = attrs["self_friction"]
    return mod


def range_groups(obj, parts, attrs_list, mod):
    """Merged cloth: per-garment stiffness through Blender's stiffness vertex
    groups (setting = min + weight x (max - min) over the garments)."""
    s = mod.settings
    for key, base, top, group in (("tension", "tension_stiffness", "tension_stiffness_max", "structural"),
                                  ("shear", "shear_stiffness", "shear_stiffness_max", "shear"),
                                  ("bending", "bending_stiffness", "bending_stiffness_max", "bending")):
        values = [a[key] for a in attrs_list]
        lo, hi = min(values), max(values)
        setattr(s, base, lo)
        setattr(s, top, hi)
        vg = obj.vertex_groups.new(name=group)
        for (start, count), v in zip(parts, values):
            w = 0.0 if hi <= lo else (v - lo) / (hi - lo)
            vg.add(list(range(start, start + count)), w, "REPLACE")
        setattr(s, "vertex_group_" + ("structural_stiffness" if group == "structural" else
                                      "shear_stiffness" if group == "shear" else "bending"), group)
    s.compression_stiffness = min(a["compression"] for a in attrs_list)
    s.compression_stiffness_max = max(a["compression"] for a in attrs_list)


def add_wind(wind, frames):
    """A Blender wind field following the stored wind frame by frame (keyed
    with constant interpolation wherever strength or direction change)."""
    if not wind or max(wind["strength"][:frames]) <= 0:
        return None
    bpy.ops.object.effector_add(type="WIND")
    empty = bpy.context.view_layer.objects.active
    empty.name = "wind"
    empty.field.shape = "PLANE"
    empty.field.falloff_power = 0.0  # no falloff: the same wind everywhere
    empty.rotation_mode = "QUATERNION"
    last = None
    for t in range(frames):
        q = tuple(wind["rotation"][4 * t:4 * t + 4])
        s = wind["strength"][t]
        if (q, s) == last:
            continue
        last = (q, s)
        empty.rotation_quaternion = q
        d = (2 * (q[1] * q[3] + q[0] * q[2]), 2 * (q[2] * q[3] - q[0] * q[1]), 1 - 2 * (q[1] ** 2 + q[2] ** 2))
        empty.location = (-5 * d[0], 1 - 5 * d[1], -5 * d[2])
        empty.field.strength = s
        empty.keyframe_insert("rotation_quaternion", frame=t + 1)
        empty.keyframe_insert("location", frame=t + 1)
        empty.field.keyframe_insert("strength", frame=t + 1)
    for fc in empty.animation_data.action.fcurves:
        for k in fc.keyframe_points:
            k.interpolation = "CONSTANT"
    return empty


def main():
    args = parse_args()
    scene_desc = load_scene(args.scene)
    folder, prefix = scene_desc["dir"], scene_desc["prefix"]
    os.makedirs(args.out, exist_ok=True)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.gravity = (0.0, -9.81, 0.0)
    scene.frame_start, scene.frame_end = 1, args.frames
    scene.render.fps = 30

    body_verts, body_faces = read_obj(os.path.join(folder, prefix + "body.obj"))
    body = new_object("body", body_verts, body_faces)
    cache = body.modifiers.new("cache", "MESH_CACHE")
    cache.cache_format = "PC2"
    cache.filepath = os.path.join(folder, prefix + "body.pc2")
    cache.frame_start = 1.0  # Blender frame 1 reads sample 0
    garments = scene_desc["garments"]
    frictions = [g["attributes"]["friction"] for g in garments]
    dist = blender_distances(dict(DEFAULT_GAPS, **scene_desc.get("gaps", {})), args.setup == "merged")
    add_collider(body, dist["body_thickness_outer"], sum(frictions) / max(1, len(frictions)))
    body_only = bpy.data.collections.new("body_only")
    body_only.objects.link(body)
    with_inner = bpy.data.collections.new("body_and_inner")
    with_inner.objects.link(body)

    meshes = []
    for g in garments:
        verts, faces = read_obj(os.path.join(folder, prefix + g["mesh"] + ".obj"))
        rest_path = os.path.join(folder, prefix + g["mesh"] + "_rest.obj")
        rest = read_obj(rest_path)[0] if os.path.exists(rest_path) else verts
        if len(rest) != len(verts):
            raise SystemExit("crosscheck_sim: error: rest shape of %s has %d vertices, not %d" %
                             (g["mesh"], len(rest), len(verts)))
        meshes.append((verts, faces, rest))

    cloths = []  # (object, [(garment index, first vertex, count)])
    if args.setup == "merged":
        verts, faces, rest, parts = [], [], [], []
        for k, (v, f, r) in enumerate(meshes):
            base = len(verts)
            parts.append((base, len(v)))
            verts += v
            rest += r
            faces += [(a + base, b + base, c + base) for a, b, c in f]
        obj = new_object("garments", verts, faces)
        key = add_rest_shape(obj, rest)
        attrs = [g["attributes"] for g in garments]
        n = [p[1] for p in parts]
        merged = {a: sum(x[a] * c for x, c in zip(attrs, n)) / sum(n) for a in attrs[0]}
        mod = add_cloth(obj, merged, key, body_only, self_collision=True, dist=dist)
        range_groups(obj, parts, attrs, mod)
        cloths.append((obj, [(k, p[0], p[1]) for k, p in enumerate(parts)]))
    else:
        for k, (g, (v, f, r)) in enumerate(zip(garments, meshes)):
            obj = new_object(g["mesh"], v, f)
            key = add_rest_shape(obj, r)
            outer = g["layer"] >= 1
            add_cloth(obj, g["attributes"], key, with_inner if outer else body_only,
                      self_collision=bool(g.get("self_collision", True)), dist=dist)
            if not outer:  # a collider for the outer garments, after its cloth modifier
                add_collider(obj, dist["layer_thickness_outer"], g["attributes"]["self_friction"])
                with_inner.objects.link(obj)
            cloths.append((obj, [(k, 0, len(v))]))
    for obj, _ in cloths:
        cache_settings = obj.modifiers["cloth"].point_cache
        cache_settings.frame_start, cache_settings.frame_end = 1, args.frames
    add_wind(scene_desc.get("wind"), args.frames)

    results = [[] for _ in garments]
    times = []
    for t in range(args.frames):
        start = time.perf_counter()
        scene.frame_set(t + 1)
        depsgraph = bpy.context.evaluated_depsgraph_get()
        if t > 0:
            times.append(time.perf_counter() - start)
        for obj, parts in cloths:
            mesh = obj.evaluated_get(depsgraph).data
            coords = array("f", [0.0]) * (3 * len(mesh.vertices))
            mesh.vertices.foreach_get("co", coords)
            for k, first, count in parts:
                results[k].append(coords[3 * first:3 * (first + count)])
        if t > 0:
            print("crosscheck_sim: frame %d %.1f ms" % (t, 1000 * times[-1]), flush=True)

    for g, frames in zip(garments, results):
        write_pc2(os.path.join(args.out, g["mesh"] + ".pc2"), frames, len(frames[0]) // 3)
    mean_ms = 1000 * sum(times) / len(times) if times else float("nan")
    with open(os.path.join(args.out, "timing.txt"), "w") as f:
        f.write("ms_per_frame %.3f\nframes %d\nsetup %s\n" % (mean_ms, len(times), args.setup))
    print("crosscheck_sim: %s, %d frames, %.1f ms per frame" % (args.setup, args.frames, mean_ms), flush=True)


if __name__ == "__main__":
    try:
        main()
    except SystemExit:
        raise
    except Exception as e:  # one line for the caller, and a non-zero exit
        print("crosscheck_sim: error: %s: %s" % (type(e).__name__, e), file=sys.stderr, flush=True)
        sys.exit(1)
