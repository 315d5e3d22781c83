"""Builds and renders, inside Blender (Cycles, CPU), the scene that
docs/tools/cycles_fur.py describes in a JSON file, so that it matches pelage's render of
the same scene setting for setting. Run by cycles_fur.py as

    blender -b --factory-startup -noaudio -P docs/tools/cycles_scene.py -- CONFIG.json

CONFIG holds the mesh (OFF), the camera, the constant environment and the sun, the skin's
constant colour, the strands (root, tip, radius at root and tip, straight along the
interpolated normal) and the hair's absorption and roughnesses, the film and the
integrator settings. pelage's scenes are y-up and Blender's z-up: every point and
direction is turned by (x, y, z) -> (x, -z, y), which changes nothing else.

Cycles' settings that would bias the comparison are off: no indirect or direct clamping,
no Filter Glossy, no light threshold, no adaptive sampling, no denoising.
"""
import json
import math
import sys

import bpy
import numpy as np
from mathutils import Vector


def zup(p):
    return (p[0], -p[2], p[1])


def read_off(path):
    with open(path, encoding="utf-8") as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    assert words[0] == "OFF", path
    nv, nf = int(words[1]), int(words[2])
    at = 4
    verts = [zup([float(words[at + 3 * i + k]) for k in range(3)]) for i in range(nv)]
    at += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(words[at])
        faces.append([int(w) for w in words[at + 1:at + 1 + n]])
        at += 1 + n
    return verts, faces


def material(name):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    for n in list(nodes):
        nodes.remove(n)
    out = nodes.new("ShaderNodeOutputMaterial")
    return m, nodes, out


def skin_material(colour):
    m, nodes, out = material("skin")
    d = nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs["Color"].default_value = (*colour, 1)
    d.inputs["Roughness"].default_value = 0
    m.node_tree.links.new(d.outputs["BSDF"], out.inputs["Surface"])
    return m


def hair_material(h):
    m, nodes, out = material("hair")
    b = nodes.new("ShaderNodeBsdfHairPrincipled")
    b.parametrization = "ABSORPTION"
    b.inputs["Absorption Coefficient"].default_value = h["sigma_a"]
    b.inputs["Roughness"].default_value = h["beta_m"]
    b.inputs["Radial Roughness"].default_value = h["beta_n"]
    b.inputs["Coat"].default_value = 0
    b.inputs["IOR"].default_value = h["eta"]
    b.inputs["Offset"].default_value = math.radians(h["alpha_deg"])
    b.inputs["Random Roughness"].default_value = 0
    b.inputs["Random Color"].default_value = 0
    m.node_tree.links.new(b.outputs["BSDF"], out.inputs["Surface"])
    return m


def strands(c, verts, faces):
    """Straight strands at area-uniform random roots (no jitter, no stratification), along
    the area-weighted vertex normals interpolated at the root, as pelage grows them with
    "comb": "normal"."""
    V = np.array(verts, dtype=np.float64)
    F = np.array([f for f in faces if len(f) == 3], dtype=np.int64)
    a, b, d = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    fn = np.cross(b - a, d - a)  # |fn| = 2 area
    vn = np.zeros_like(V)
    for k in range(3):
        np.add.at(vn, F[:, k], fn)
    vn /= np.maximum(np.linalg.norm(vn, axis=1, keepdims=True), 1e-30)
    area = 0.5 * np.linalg.norm(fn, axis=1)
    n = int(round(c["density"] * area.sum()))
    rng = np.random.default_rng(c["seed"])
    tri = rng.choice(len(F), size=n, p=area / area.sum())
    u, v = rng.random(n), rng.random(n)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    w = 1 - u - v
    root = a[tri] * w[:, None] + b[tri] * u[:, None] + d[tri] * v[:, None]
    nrm = (vn[F[tri, 0]] * w[:, None] + vn[F[tri, 1]] * u[:, None] +
           vn[F[tri, 2]] * v[:, None])
    nrm /= np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-30)
    k = c["segments"] + 1
    t = np.linspace(0, 1, k)
    pts = root[:, None, :] + nrm[:, None, :] * (c["length"] * t)[None, :, None]
    rad = c["root_radius"] + (c["tip_radius"] - c["root_radius"]) * t
    return pts.reshape(-1, 3), np.tile(rad, n), n, k


def fur_object(c, verts, faces, mat, scene):
    """The strands as a mesh of edge chains, turned into a hair Curves object by geometry
    nodes (Object Info of the edges, Mesh to Curve, Set Curve Radius from a point
    attribute): Cycles renders a Curves object as its 3D curves, with the hair
    material."""
    pts, rad, n, k = strands(c, verts, faces)
    me = bpy.data.meshes.new("fur_edges")
    me.vertices.add(len(pts))
    me.vertices.foreach_set("co", pts.astype(np.float32).ravel())
    idx = np.arange(n * k).reshape(n, k)
    e = np.stack([idx[:, :-1], idx[:, 1:]], axis=-1).reshape(-1, 2)
    me.edges.add(len(e))
    me.edges.foreach_set("vertices", e.astype(np.int32).ravel())
    attr = me.attributes.new("strand_radius", "FLOAT", "POINT")
    attr.data.foreach_set("value", rad.astype(np.float32))
    me.update()
    edges = bpy.data.objects.new("fur_edges", me)
    scene.collection.objects.link(edges)
    edges.hide_render = True
    obj = bpy.data.objects.new("fur", bpy.data.hair_curves.new("fur"))
    obj.data.materials.append(mat)
    g = bpy.data.node_groups.new("to_hair", "GeometryNodeTree")
    g.inputs.new("NodeSocketGeometry", "Geometry")
    g.outputs.new("NodeSocketGeometry", "Geometry")
    go = g.nodes.new("NodeGroupOutput")
    info = g.nodes.new("GeometryNodeObjectInfo")
    info.inputs["Object"].default_value = edges
    to_curve = g.nodes.new("GeometryNodeMeshToCurve")
    radius = g.nodes.new("GeometryNodeSetCurveRadius")
    named = g.nodes.new("GeometryNodeInputNamedAttribute")
    named.data_type = "FLOAT"
    named.inputs["Name"].default_value = "strand_radius"
    set_mat = g.nodes.new("GeometryNodeSetMaterial")
    set_mat.inputs["Material"].default_value = mat
    L = g.links
    L.new(info.outputs["Geometry"], to_curve.inputs["Mesh"])
    L.new(to_curve.outputs["Curve"], radius.inputs["Curve"])
    # Named Attribute has one "Attribute" output per data type; the float one.
    value = next(o for o in named.outputs if o.type == "VALUE" and o.enabled)
    L.new(value, radius.inputs["Radius"])
    L.new(radius.outputs["Curve"], set_mat.inputs["Geometry"])
    L.new(set_mat.outputs["Geometry"], go.inputs["Geometry"])
    mod = obj.modifiers.new("to_hair", "NODES")
    mod.node_group = g
    return obj, n


def main():
    cfg = json.load(open(sys.argv[sys.argv.index("--") + 1], encoding="utf-8"))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    cy = scene.cycles
    cy.device = "CPU"
    cy.samples = cfg["spp"]
    cy.seed = cfg["seed"]
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.sample_clamp_direct = 0
    cy.sample_clamp_indirect = 0
    cy.blur_glossy = 0
    cy.caustics_reflective = True
    cy.caustics_refractive = True
    cy.light_sampling_threshold = 0
    # pelage's max_depth counts scattering events (1: direct light only), Cycles'
    # bounces count the events after the first (0: direct light only).
    depth = cfg["max_depth"] - 1
    cy.max_bounces = depth
    cy.diffuse_bounces = depth
    cy.glossy_bounces = depth
    cy.transmission_bounces = depth
    cy.transparent_max_bounces = depth
    cy.volume_bounces = 0
    cy.pixel_filter_type = "BLACKMAN_HARRIS"
    cy.filter_width = cfg["filter_radius"]  # Cycles' BH reaches ±width (film.cpp)
    scene.cycles_curves.shape = "THICK"
    scene.render.threads_mode = "FIXED"
    scene.render.threads = cfg["threads"]
    scene.render.resolution_x, scene.render.resolution_y = cfg["width"], cfg["height"]
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_mode = "RGBA"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"

    verts, faces = read_off(cfg["mesh"])
    me = bpy.data.meshes.new("skin")
    me.from_pydata(verts, [], faces)
    for p in me.polygons:
        p.use_smooth = True
    me.update()
    skin = bpy.data.objects.new("skin", me)
    skin.data.materials.append(skin_material(cfg["skin_colour"]))
    scene.collection.objects.link(skin)
    if cfg.get("fur"):
        fur, count = fur_object(cfg["fur"], verts, faces, hair_material(cfg["fur"]), scene)
        scene.collection.objects.link(fur)
        print(f"cycles_scene: {count} strands")

    world = bpy.data.worlds.new("world")
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (*cfg["environment"]["colour"], 1)
    bg.inputs["Strength"].default_value = cfg["environment"]["intensity"]
    scene.world = world

    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = cfg["sun"]["intensity"]  # irradiance, as pelage's distant light
    sun.color = cfg["sun"]["colour"]
    sun.angle = math.radians(cfg["sun"]["angle"])
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_euler = Vector(zup(cfg["sun"]["direction"])).to_track_quat(
        "-Z", "Y").to_euler()
    scene.collection.objects.link(sun_obj)

    cam = bpy.data.cameras.new("camera")
    cam.sensor_fit = "VERTICAL"
    cam.lens_unit = "FOV"
    cam.angle = math.radians(cfg["camera"]["fov"])
    cam_obj = bpy.data.objects.new("camera", cam)
    eye, at = Vector(zup(cfg["camera"]["position"])), Vector(zup(cfg["camera"]["look_at"]))
    cam_obj.location = eye
    cam_obj.rotation_euler = (at - eye).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(cam_obj)
    scene.camera = cam_obj

    scene.render.filepath = cfg["output"]
    bpy.ops.render.render(write_still=True)


main()
