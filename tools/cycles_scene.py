# Blender (3.4, headless) script for tools/cycles-reference.sh: the scene of a
# `jade reference` command line path-traced by Cycles, for ground truth that
# jade did not write. Run as
#   blender -b --factory-startup --python tools/cycles_scene.py -- KEY=VALUE...
# (the wrapper passes every key). Never imported by jade; never a dependency.
#
# The object is what jade's model describes, physically: a homogeneous medium
# with jade's sigma_s' (as sigma_s, isotropic phase: g = 0) and sigma_a per
# channel, in millimetres (one Blender unit = 1 mm), lit by a directional
# light. Two boundaries (boundary=):
# - "matched" (the default): no surface at all, the medium's index equals the
#   air's (eta 1): light enters and leaves unrefracted, so Cycles' next-event
#   estimation reaches the sun from inside the medium and converges.
# - "walk": Cycles' random-walk subsurface scattering (Chiang et al. 2016) with
#   the colour and radius that Cycles' own mapping turns back into jade's
#   sigma values (see walk_inputs): the same medium behind a diffuse boundary,
#   light entering and leaving with a cosine distribution (Cycles 3.4 samples
#   the entry that way), no Fresnel reflection and no total internal
#   reflection.
# A smooth dielectric boundary (eta > 1) under a delta light is a caustic path
# a path tracer cannot sample; it is not offered here (see docs/quality.md).
#
# Camera, light and units follow jade exactly: the mesh is centred on its
# bounding box and scaled by mm-per-unit (default: the box's diagonal 100 mm),
# the camera frames the box as core/scene.c's fit_distance does, the light
# comes from (cos el sin az, sin el, cos el cos az) in jade's Y-up frame
# (the OBJ's own axes, imported without conversion). Radiance is scaled by pi
# (the sun's strength pi W/m^2 for jade's intensity 1), so a white diffuser
# reads 1 as in jade. Writes OUT.pfm (linear, jade's background behind the
# object), OUT.png (jade's tone curve) and OUT.mask.png (the object's pixels).
import math
import struct
import sys

import bpy
import mathutils

args = dict(a.split("=", 1) for a in sys.argv[sys.argv.index("--") + 1:])


def f3(key):
    return [float(x) for x in args[key].split(",")]


mesh_path = args["mesh"]
width, height = (int(x) for x in args["size"].split("x"))
sigma_s, sigma_a = f3("sigma_s"), f3("sigma_a")
density = float(args.get("density", "1"))
sigma_s = [x * density for x in sigma_s]
sigma_a = [x * density for x in sigma_a]
mm_per_unit = float(args.get("mm_per_unit", "0"))
cam_az, cam_el = float(args.get("cam_az", "15")), float(args.get("cam_el", "35"))
fit, fov = float(args.get("fit", "0.9")), float(args.get("fov", "35"))
cam_distance = float(args.get("cam_distance", "0"))
light_az, light_el = float(args.get("light_az", "170")), float(args.get("light_el", "35"))
light_intensity = float(args.get("light_intensity", "1"))
exposure = float(args.get("exposure", "1"))
samples, bounces = int(args.get("samples", "256")), int(args.get("bounces", "1024"))
seed = int(args.get("seed", "0"))
boundary = args.get("boundary", "matched")
if boundary not in ("matched", "walk"):
    sys.exit("cycles_scene: boundary=%s: matched or walk" % boundary)
out = args["out"]
background = [0.05, 0.055, 0.065]  # jd_scene_defaults: after the shoulder, before the sqrt

bpy.ops.wm.read_factory_settings(use_empty=True)
low = mesh_path.lower()
if low.endswith(".obj"):
    bpy.ops.wm.obj_import(filepath=mesh_path, forward_axis="Y", up_axis="Z")
elif low.endswith(".ply"):
    bpy.ops.import_mesh.ply(filepath=mesh_path)
elif low.endswith(".stl"):
    bpy.ops.import_mesh.stl(filepath=mesh_path, axis_forward="Y", axis_up="Z")
else:
    sys.exit("cycles_scene: %s: only OBJ, PLY and STL (Blender's importers, no axis change)" % mesh_path)
objs = [o for o in bpy.context.scene.objects if o.type == "MESH"]
if not objs:
    sys.exit("cycles_scene: %s: no mesh imported" % mesh_path)
for o in objs:
    o.rotation_euler = (0, 0, 0)
    o.matrix_world = mathutils.Matrix.Identity(4)
# jade reads every group of an OBJ as one mesh: so does the medium (an
# importer makes an object per `o` line, and only one would be placed).
obj = objs[0]
bpy.context.view_layer.objects.active = obj
for o in objs:
    o.select_set(True)
if len(objs) > 1:
    bpy.ops.object.join()

# A closed surface: Cycles tells inside from outside by the faces a ray
# crosses, and a hole would leave a path "inside" the medium for ever (the
# Stanford bunny has five under its base). Filled here; jade sees the holes.
bpy.context.view_layer.objects.active = obj
bpy.ops.object.mode_set(mode="EDIT")
bpy.ops.mesh.select_all(action="SELECT")
bpy.ops.mesh.remove_doubles(threshold=1e-7)
bpy.ops.mesh.select_all(action="DESELECT")
bpy.ops.mesh.select_non_manifold(extend=False, use_wire=False, use_boundary=True, use_multi_face=False,
                                 use_non_contiguous=False, use_verts=False)
bpy.ops.mesh.fill_holes(sides=0)
bpy.ops.mesh.select_all(action="SELECT")
bpy.ops.mesh.normals_make_consistent(inside=False)
bpy.ops.object.mode_set(mode="OBJECT")

# jade's placement (core/mesh.c jd_mesh_placement): the box's centre and half
# diagonal, from the positions as loaded (before the holes were filled: the
# fill adds no vertex).
vs = [v.co for v in obj.data.vertices]
bmin = [min(v[k] for v in vs) for k in range(3)]
bmax = [max(v[k] for v in vs) for k in range(3)]
centre = [(bmin[k] + bmax[k]) / 2 for k in range(3)]
radius = 0.5 * math.sqrt(sum((bmax[k] - bmin[k]) ** 2 for k in range(3))) or 1.0
if mm_per_unit <= 0:
    mm_per_unit = 100.0 / (2.0 * radius)
s = mm_per_unit
obj.data.transform(mathutils.Matrix.Translation([-c for c in centre]))
obj.data.transform(mathutils.Matrix.Scale(s, 4))
obj.data.update()


def from_angles(az, el):
    az, el = math.radians(az), math.radians(el)
    return mathutils.Vector((math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az)))


def fit_distance(half, d, fit, fov_deg, aspect):
    """core/scene.c fit_distance, in world units (half box diagonals)."""
    ty = math.tan(math.radians(fov_deg) / 2) * fit
    tx = ty * aspect
    up = mathutils.Vector((1, 0, 0)) if abs(d.y) > 0.999 else mathutils.Vector((0, 1, 0))
    right = up.cross(d).normalized()
    u = d.cross(right)
    dist = 0.0
    for k in range(8):
        p = mathutils.Vector((half[0] if k & 1 else -half[0], half[1] if k & 2 else -half[1],
                              half[2] if k & 4 else -half[2]))
        x, y, z = abs(p.dot(right)), abs(p.dot(u)), p.dot(d)
        dist = max(dist, z + x / tx, z + y / ty)
    return max(dist, 1.3)


d = from_angles(cam_az, cam_el)
half = [(bmax[k] - bmin[k]) * 0.5 / radius for k in range(3)]
dist = cam_distance if cam_distance > 0 else fit_distance(half, d, fit, fov, width / height)
mm_per_world = s * radius
eye = d * dist * mm_per_world
fwd = (-eye).normalized()
# jd_m4_look_at's up: +Y, or +X where the view is within 2.6 degrees of it
world_up = mathutils.Vector((1, 0, 0)) if abs(fwd.y) > 0.999 else mathutils.Vector((0, 1, 0))
right = fwd.cross(world_up).normalized()
up = right.cross(fwd)
cam_data = bpy.data.cameras.new("jade")
cam_data.sensor_fit = "VERTICAL"
cam_data.angle_y = math.radians(fov)
cam_data.clip_start = 0.01 * mm_per_world
cam_data.clip_end = 1000.0 * mm_per_world
cam = bpy.data.objects.new("jade", cam_data)
m = mathutils.Matrix.Identity(4)
for k in range(3):
    m[k][0], m[k][1], m[k][2], m[k][3] = right[k], up[k], -fwd[k], eye[k]
cam.matrix_world = m
bpy.context.scene.collection.objects.link(cam)
bpy.context.scene.camera = cam

sun_data = bpy.data.lights.new("sun", type="SUN")
sun_data.energy = math.pi * light_intensity
sun_data.angle = 0.0
sun = bpy.data.objects.new("sun", sun_data)
ld = from_angles(light_az, light_el)
sun.rotation_mode = "QUATERNION"
sun.rotation_quaternion = mathutils.Vector((0, 0, 1)).rotation_difference(ld)
bpy.context.scene.collection.objects.link(sun)

world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
bpy.context.scene.world = world

WALK_IOR = 1.01  # the least Cycles takes; the radius below undoes what it does


def bisect(f, target, steps):
    """x in [0, 1] where the increasing f reaches target: the last midpoint of
    `steps` halvings, as Cycles' own solver returns it."""
    lo, hi = 0.0, 1.0
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        if f(mid) < target:
            lo = mid
        else:
            hi = mid
    return mid


def walk_alpha(albedo):
    """Cycles 3.4's subsurface_random_walk_remap at anisotropy 0: the surface
    colour to the single-scattering albedo (Chiang et al. 2016's fit)."""
    a0, b, c = 1.8260523782, 4.98511194385 + 0.127355959438, 1.09686102424
    d, e, f = 0.496310210422, 4.23190299701 + 0.00310603949088, 2.40602999408
    blend = albedo ** 0.25
    alpha = (1 - blend) * a0 * math.atan(b * albedo) ** c + blend * d * math.atan(e * albedo) ** f
    return min(max(alpha, 0.0), 0.999999)


def walk_radius_factor(albedo, eta):
    """Cycles 3.4's bssrdf_setup_radius for the random walk: the radius it is
    given is multiplied by sqrt(3 (1 - alpha')), alpha' from inverting the
    dipole's total reflectance by its own 12-step bisection."""
    inv = 1.0 / eta
    f_dr = inv * (-1.440 * inv + 0.710) + 0.668 + 0.0636 * eta
    fta = (4.0 / 3.0) * (1 + f_dr) / (1 - f_dr)

    def rd(ap):
        t = math.sqrt(3 * (1 - ap))
        return 0.5 * ap * (1 + math.exp(-fta * t)) * math.exp(-t)

    if albedo < 1e-4:
        ap = 0.0
    elif albedo >= 0.995:
        ap = 0.999999
    else:
        ap = bisect(rd, albedo, 12)
    return math.sqrt(3 * (1 - ap))


def walk_inputs(ss, sa):
    """The node's colour and radius (mm) for one channel whose medium is jade's
    sigma_s' (isotropic) and sigma_a: Cycles takes sigma_t = 1 / (radius x
    factor) and the albedo from walk_alpha(colour); both are inverted here.
    Below a single-scattering albedo of 0.2 Cycles raises it to 0.2 and lowers
    the path's weight instead (ketchup's green and blue): not the same medium
    there, and said so."""
    st = ss + sa
    alpha = ss / st
    colour = bisect(walk_alpha, alpha, 60)
    return colour, (1.0 / st) / walk_radius_factor(colour, WALK_IOR), alpha


mat = bpy.data.materials.new("medium")
mat.use_nodes = True
nt = mat.node_tree
for n in list(nt.nodes):
    nt.nodes.remove(n)
outn = nt.nodes.new("ShaderNodeOutputMaterial")
if boundary == "walk":
    ch = [walk_inputs(sigma_s[k], sigma_a[k]) for k in range(3)]
    for k, (_, _, alpha) in enumerate(ch):
        if alpha < 0.2:
            print("cycles_scene: channel %d: single-scattering albedo %.3f, below the 0.2 Cycles' random walk "
                  "keeps; that channel is not jade's medium" % (k, alpha))
    ss_node = nt.nodes.new("ShaderNodeSubsurfaceScattering")
    ss_node.falloff = "RANDOM_WALK"
    ss_node.inputs["Color"].default_value = (ch[0][0], ch[1][0], ch[2][0], 1)
    ss_node.inputs["Scale"].default_value = 1.0
    ss_node.inputs["Radius"].default_value = (ch[0][1], ch[1][1], ch[2][1])
    ss_node.inputs["IOR"].default_value = WALK_IOR
    ss_node.inputs["Anisotropy"].default_value = 0.0
    nt.links.new(ss_node.outputs[0], outn.inputs["Surface"])
    print("cycles_scene: random walk: colour %s radius %s mm" % ([round(c[0], 6) for c in ch], [round(c[1], 6) for c in ch]))
# The medium: Volume Scatter (colour x density = sigma_s per channel) plus
# Volume Absorption (density x (1 - colour) = sigma_a), no surface shader.
sc = nt.nodes.new("ShaderNodeVolumeScatter")
ab = nt.nodes.new("ShaderNodeVolumeAbsorption")
add = nt.nodes.new("ShaderNodeAddShader")
ds = max(sigma_s) or 1.0
sc.inputs["Color"].default_value = (sigma_s[0] / ds, sigma_s[1] / ds, sigma_s[2] / ds, 1)
sc.inputs["Density"].default_value = ds
sc.inputs["Anisotropy"].default_value = 0.0
da = max(sigma_a) or 1.0
ab.inputs["Color"].default_value = (1 - sigma_a[0] / da, 1 - sigma_a[1] / da, 1 - sigma_a[2] / da, 1)
ab.inputs["Density"].default_value = da
nt.links.new(sc.outputs[0], add.inputs[0])
nt.links.new(ab.outputs[0], add.inputs[1])
if boundary == "matched":
    nt.links.new(add.outputs[0], outn.inputs["Volume"])
mat.cycles.homogeneous_volume = True
obj.data.materials.clear()
obj.data.materials.append(mat)

sc_ = bpy.context.scene
sc_.render.engine = "CYCLES"
sc_.cycles.device = "CPU"
sc_.cycles.samples = samples
sc_.cycles.use_adaptive_sampling = False
sc_.cycles.use_denoising = False
sc_.cycles.seed = seed
sc_.cycles.max_bounces = bounces
sc_.cycles.volume_bounces = bounces
# Blender clamps both to 1024 without a word: a picture asked for at 4096
# came out bit for bit the 1024 one, which once read as "no path reaches the
# limit" (docs/quality.md, "Converged"). Refuse what it will not do.
if sc_.cycles.max_bounces != bounces or sc_.cycles.volume_bounces != bounces:
    sys.exit("cycles_scene: bounces=%d: Blender %s takes at most %d (it clamps, it does not refuse)"
             % (bounces, bpy.app.version_string, sc_.cycles.max_bounces))
# The walk's exit is a diffuse surface: light it sends on re-enters elsewhere
# (the matched medium's paths do that as volume bounces).
sc_.cycles.diffuse_bounces = bounces if boundary == "walk" else 0
sc_.cycles.glossy_bounces = 0
sc_.cycles.transmission_bounces = 0
sc_.cycles.transparent_max_bounces = 64
sc_.cycles.sample_clamp_direct = 0
sc_.cycles.sample_clamp_indirect = 0
sc_.cycles.caustics_reflective = True
sc_.cycles.caustics_refractive = True
sc_.cycles.blur_glossy = 0.0
sc_.cycles.filter_width = 1.0  # a pixel's own box, as jade's --pixel-samples averages
sc_.cycles.pixel_filter_type = "BOX"
sc_.render.film_transparent = True
sc_.render.resolution_x, sc_.render.resolution_y = width, height
sc_.render.resolution_percentage = 100
sc_.view_settings.view_transform = "Standard"
sc_.view_settings.look = "None"
sc_.view_settings.exposure = 0.0
sc_.view_settings.gamma = 1.0
sc_.render.image_settings.file_format = "OPEN_EXR"
sc_.render.image_settings.color_depth = "32"
sc_.render.image_settings.color_mode = "RGBA"
sc_.render.filepath = out + ".exr"
bpy.ops.render.render(write_still=True)

img = bpy.data.images.load(out + ".exr")
px = list(img.pixels)  # bottom row first, RGBA, linear
bg = [b / (1.0 - 0.15 * b) for b in background]  # jd_shoulder_inverse
lin = []
for i in range(width * height):
    r, g, b, a = px[4 * i:4 * i + 4]
    lin.append(((r * exposure + (1 - a) * bg[0]), (g * exposure + (1 - a) * bg[1]), (b * exposure + (1 - a) * bg[2]), a))
with open(out + ".pfm", "wb") as f:  # PFM rows run bottom to top, as Blender's
    f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
    f.write(b"".join(struct.pack("<3f", *p[:3]) for p in lin))


def tone(x):
    x = max(x, 0.0)
    y = x / (1.0 + 0.15 * x)
    return int(round(255 * math.sqrt(min(max(y, 0.0), 1.0))))


png = bpy.data.images.new("tone", width, height, alpha=False)
png.colorspace_settings.name = "Non-Color"
png.pixels = [v for p in lin for v in (tone(p[0]) / 255, tone(p[1]) / 255, tone(p[2]) / 255, 1.0)]
png.filepath_raw = out + ".png"
png.file_format = "PNG"
png.save()
mask = bpy.data.images.new("mask", width, height, alpha=False)
mask.colorspace_settings.name = "Non-Color"
mask.pixels = [v for p in lin for v in ((1.0,) * 3 if p[3] > 0.5 else (0.0,) * 3) + (1.0,)]
mask.filepath_raw = out + ".mask.png"
mask.file_format = "PNG"
mask.save()
print("cycles_scene: wrote %s.png, .pfm, .mask.png (%dx%d, %d samples, %d bounces, %.4g mm per unit, "
      "sigma_s %s sigma_a %s per mm)" % (out, width, height, samples, bounces, s, sigma_s, sigma_a))
