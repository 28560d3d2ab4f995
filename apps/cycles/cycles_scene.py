"""Render an rtweekend text scene file with Blender Cycles (CPU) and write a linear PFM.

Run inside Blender (tested with Debian 12's Blender 3.4.1, Cycles with Embree, no denoiser):

    blender -b --factory-startup --python apps/cycles/cycles_scene.py -- SCENE.txt \
        --spp 64 --threads 2 -o out.pfm [--width W] [--seed N] [--depth N]
        [--spheres auto|points|ico] [--ico-subdivisions 7] [--glass exact|schlick]
        [--background-only] [--exr out.exr]

The scene is rebuilt in Cycles with the closest mapping Cycles allows (apps/cycles/README.md lists
what differs):

  sphere            an exact sphere: a one-point point cloud, which Cycles intersects
                    analytically; but glass spheres are smooth-shaded icospheres
                    (81,920 faces), one mesh per material shared by all (instanced), because
                    Cycles 3.4 intersects point spheres from outside only, so a ray that entered
                    one never leaves through it (--spheres auto, the default; points or ico:
                    all spheres one way)
  quad, triangle    a one-face mesh with the scene's winding (face normal u x v)
  box               a cube mesh between the corners, then the transforms
  lambertian        Diffuse BSDF (roughness 0 = Lambert), colour = albedo
  metal r g b fuzz  Glossy BSDF (GGX), colour = albedo, roughness from the fuzz (fuzz_to_roughness)
  dielectric ior    Glass BSDF (sharp), white, IOR = ior (Cycles: exact Fresnel; the book: Schlick;
                    --glass schlick builds the book's rule from nodes)
  diffuse_light     Emission (strength 1, colour = radiance) on the front face only (Backfacing
                    mixes in a black, non-scattering shader); two_sided_light: both faces
  background        the book's sky lerp(white, (0.5, 0.7, 1), 0.5 (d.y + 1)) from the world's
                    Generated coordinate (the unit ray direction in a world shader), or a constant
  camera            vertical sensor fit, lens from vfov, DOF: focus distance = focus_dist, aperture
                    radius focus_dist * tan(defocus_angle / 2)

Colours (and a metal's roughness) reach the shared materials through the object's colour (Object
Info), so there is one material per kind, not one per sphere.

Render settings: CPU, fixed thread count, no denoiser, no adaptive sampling, opaque film, box
pixel filter 1 px wide (uniform jitter over the pixel, as rtweekend), every bounce limit
max_depth - 1 (max_depth counts rays, Cycles counts bounces), no clamping, no glossy filter,
reflective and refractive caustics on, light sampling and MIS at Cycles' defaults, colour
management 'Standard' view, exposure 0, gamma 1. The image is saved as 32-bit float OpenEXR and
converted here to PFM (rows bottom to top, little-endian), which rtweekend's `compare` reads.

Printed on stdout, one line each (machine-readable, key=value):
  CYCLES_BUILD seconds=<scene construction in Python> objects=... spheres=...
  CYCLES_ICO subdivisions=... faces=... max_radial_error_over_radius=...   (when there are icospheres)
  CYCLES_RESULT scene=... width=... height=... spp=... threads=... seconds=<the render call: scene
                sync, BVH, light preprocessing and rendering> out=...
"""

import argparse
import array
import math
import os
import sys
import time

import bmesh
import bpy
from mathutils import Matrix, Vector


# ---------------------------------------------------------------------------------------------
# Scene file (the subset of rtweekend's format used by the books' scenes)


class SceneError(Exception):
    pass


MATERIALS = ("lambertian", "metal", "dielectric", "diffuse_light", "two_sided_light")


class Shape:
    def __init__(self, kind, params, material, transform):
        self.kind = kind          # sphere | quad | triangle | box
        self.params = params      # list of floats
        self.material = material  # (name, r, g, b, fuzz, ior)
        self.transform = transform  # mathutils Matrix 4x4 (applied to the shape's points)


class Scene:
    def __init__(self):
        self.cam = dict(lookfrom=(0.0, 0.0, 0.0), lookat=(0.0, 0.0, -1.0), vup=(0.0, 1.0, 0.0), vfov=90.0,
                        defocus_angle=0.0, focus_dist=10.0, aspect_ratio=1.0, image_width=100, image_height=0,
                        samples_per_pixel=10, max_depth=10, seed=None)
        self.background = None    # None: the book's sky; else (r, g, b)
        self.shapes = []

    def height(self):
        if self.cam["image_height"] > 0:
            return self.cam["image_height"]
        return max(1, int(self.cam["image_width"] / self.cam["aspect_ratio"]))


def read_scene(path):
    sc = Scene()
    with open(path) as f:
        for lineno, raw in enumerate(f, 1):
            line = raw.split("#", 1)[0].split()
            if not line:
                continue
            where = "%s:%d: " % (path, lineno)
            try:
                parse_line(sc, line)
            except (ValueError, IndexError) as e:
                raise SceneError(where + "cannot read '%s' (%s)" % (" ".join(line), e))
            except SceneError as e:
                raise SceneError(where + str(e))
    return sc


def parse_line(sc, t):
    word = t[0]
    if word == "camera":
        key, vals = t[1], t[2:]
        three = lambda: tuple(float(v) for v in vals[:3])
        if key in ("lookfrom", "lookat", "vup"):
            sc.cam[key] = three()
        elif key in ("vfov", "vfov_deg"):
            sc.cam["vfov"] = float(vals[0])
        elif key in ("defocus_angle", "defocus_angle_deg"):
            sc.cam["defocus_angle"] = float(vals[0])
        elif key in ("focus_dist", "aspect_ratio"):
            sc.cam[key] = float(vals[0])
        elif key in ("image_width", "image_height", "samples_per_pixel", "max_depth", "seed"):
            sc.cam[key] = int(vals[0])
        elif key == "background":
            sc.background = three()
        elif key in ("adaptive_error", "adaptive_min_samples"):
            pass  # rtweekend's adaptive sampling: not mapped (Cycles runs without adaptive sampling)
        else:
            raise SceneError("unknown camera key '%s'" % key)
    elif word == "background":
        sc.background = tuple(float(v) for v in t[1:4])
    elif word in ("sphere", "quad", "triangle", "box"):
        nparams = {"sphere": 4, "quad": 9, "triangle": 9, "box": 6}[word]
        params = [float(v) for v in t[1:1 + nparams]]
        i = 1 + nparams
        name = t[i]
        if name not in MATERIALS:
            raise SceneError("material '%s' is not mapped to Cycles (mapped: %s)" % (name, ", ".join(MATERIALS)))
        if any(v.startswith("@") for v in t[i + 1:i + 6]):
            raise SceneError("textures are not mapped to Cycles")
        r, g, b, fuzz, ior = (float(v) for v in t[i + 1:i + 6])
        material = (name, r, g, b, min(fuzz, 1.0), ior)
        sc.shapes.append(Shape(word, params, material, parse_transforms(t[i + 6:])))
    else:
        raise SceneError("directive '%s' is not mapped to Cycles (mapped: camera, background, sphere, quad, "
                         "triangle, box)" % word)


def parse_transforms(t):
    """rotate_y DEG | translate X Y Z | rotate AX AY AZ DEG | scale SX SY SZ, applied in the order written."""
    m = Matrix.Identity(4)
    i = 0
    while i < len(t):
        w = t[i]
        if w == "rotate_y":
            step = Matrix.Rotation(math.radians(float(t[i + 1])), 4, "Y")  # right-handed, as rtweekend
            i += 2
        elif w == "translate":
            step = Matrix.Translation(Vector([float(v) for v in t[i + 1:i + 4]]))
            i += 4
        elif w == "rotate":
            axis = Vector([float(v) for v in t[i + 1:i + 4]]).normalized()
            step = Matrix.Rotation(math.radians(float(t[i + 4])), 4, axis)
            i += 5
        elif w == "scale":
            s = [float(v) for v in t[i + 1:i + 4]]
            step = Matrix.Diagonal(Vector(s + [1.0]))
            i += 4
        else:
            raise SceneError("unexpected '%s' (expected rotate_y, translate, rotate or scale)" % w)
        m = step @ m
    return m


# ---------------------------------------------------------------------------------------------
# Material mapping


def fuzz_to_roughness(fuzz):
    """Blender roughness (GGX alpha = roughness^2) for the book's fuzz.

    The book's lobe is w = normalize(m + fuzz * B), B uniform in the unit ball, m the mirror
    direction. At normal incidence its median angle from m is theta_b(fuzz) (computed below; about
    0.608 fuzz for small fuzz: the median radius of the ball's projection onto a plane is
    sqrt(1 - 0.5^(2/3))). GGX's half-vector density (D cos) has tan(theta_h) median equal to alpha,
    and the reflected direction turns by twice theta_h, so the medians agree for
    alpha = tan(theta_b / 2). fuzz 0 gives roughness 0 (Cycles' sharp mirror).
    """
    if fuzz <= 0:
        return 0.0
    theta = _book_median_angle(fuzz)
    return math.sqrt(math.tan(theta / 2))


def _book_median_angle(f):
    # Median over B uniform in the unit ball of the angle between m + f B and m (m = +z), at
    # normal incidence (the book's rejection of directions below the surface needs f > 1 there).
    # The points of the ball of radius f about m within angle theta of the axis fill, at height z,
    # a disc of radius min(sqrt(f^2 - (z - 1)^2), z tan theta): integrate (midpoint rule) and
    # bisect theta for half the ball's volume.
    n = 400
    zs = [1 - f + 2 * f * (k + 0.5) / n for k in range(n)]

    def fraction(theta):
        t2 = math.tan(theta) ** 2
        area = sum(min(f * f - (z - 1) ** 2, z * z * t2) for z in zs)
        return area * (2 * f / n) / (4.0 / 3.0 * f ** 3)

    lo, hi = 0.0, math.pi / 2 - 1e-9
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if fraction(mid) < 0.5 else (lo, mid)
    return 0.5 * (lo + hi)


def make_material(name, nodes_fn):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    out.target = "CYCLES"
    nt.links.new(nodes_fn(nt), out.inputs["Surface"])
    return mat


def schlick_glass(nt, n):
    """The book's dielectric in nodes: reflect with Schlick's probability (1 under total internal
    reflection), else refract; a Mix Shader of two sharp closures is sampled in proportion to
    its weights, as the book chooses. Cycles flips N to the ray's side, so cos = N . I >= 0."""
    def math(op, a, b, c=None):
        m = nt.nodes.new("ShaderNodeMath")
        m.operation = op
        for k, v in enumerate((a, b, c)):
            if v is None:
                continue
            if isinstance(v, (int, float)):
                m.inputs[k].default_value = v
            else:
                nt.links.new(v, m.inputs[k])
        return m.outputs["Value"]
    geo = nt.nodes.new("ShaderNodeNewGeometry")
    dot = nt.nodes.new("ShaderNodeVectorMath")
    dot.operation = "DOT_PRODUCT"
    nt.links.new(geo.outputs["Normal"], dot.inputs[0])
    nt.links.new(geo.outputs["Incoming"], dot.inputs[1])
    cos = math("MINIMUM", dot.outputs["Value"], 1.0)
    ri = math("MULTIPLY_ADD", geo.outputs["Backfacing"], n - 1.0 / n, 1.0 / n)  # front: 1/n, back: n
    sin = math("SQRT", math("SUBTRACT", 1.0, math("MULTIPLY", cos, cos)), 0.0)
    tir = math("GREATER_THAN", math("MULTIPLY", ri, sin), 1.0)
    r0 = ((1 - n) / (1 + n)) ** 2
    schlick = math("MULTIPLY_ADD", math("POWER", math("SUBTRACT", 1.0, cos), 5.0), 1 - r0, r0)
    fac = math("MAXIMUM", tir, schlick)
    refr = nt.nodes.new("ShaderNodeBsdfRefraction")
    refr.distribution = "SHARP"
    refr.inputs["Color"].default_value = (1, 1, 1, 1)
    refr.inputs["IOR"].default_value = n
    refl = nt.nodes.new("ShaderNodeBsdfGlossy")
    refl.distribution = "SHARP"
    refl.inputs["Color"].default_value = (1, 1, 1, 1)
    mix = nt.nodes.new("ShaderNodeMixShader")
    nt.links.new(fac, mix.inputs["Fac"])
    nt.links.new(refr.outputs["BSDF"], mix.inputs[1])
    nt.links.new(refl.outputs["BSDF"], mix.inputs[2])
    return mix.outputs["Shader"]


class Materials:
    """Materials shared by shape kind: the colour (and a metal's roughness) comes from the
    object's colour through Object Info, so every sphere can share one mesh and Cycles instances it."""

    def __init__(self, glass="exact"):
        self.cache = {}
        self.glass = glass

    def _object_color(self, nt):
        return nt.nodes.new("ShaderNodeObjectInfo")

    def get(self, material):
        name, r, g, b, fuzz, ior = material
        if name == "lambertian":
            key = ("lambertian",)
            color = (r, g, b, 1.0)
        elif name == "metal":
            key = ("metal",)
            color = (r, g, b, fuzz_to_roughness(fuzz))
        elif name == "dielectric":
            key = ("dielectric", ior)
            color = (1.0, 1.0, 1.0, 1.0)
        else:  # emitters: constant colours, so Cycles sees (and samples) a light
            key = (name, r, g, b)
            color = (1.0, 1.0, 1.0, 1.0)
        if key not in self.cache:
            self.cache[key] = self._build(key)
        return self.cache[key], color

    def _build(self, key):
        kind = key[0]
        if kind == "lambertian":
            def f(nt):
                info = self._object_color(nt)
                d = nt.nodes.new("ShaderNodeBsdfDiffuse")
                d.inputs["Roughness"].default_value = 0.0
                nt.links.new(info.outputs["Color"], d.inputs["Color"])
                return d.outputs["BSDF"]
            return make_material("lambertian", f)
        if kind == "metal":
            def f(nt):
                info = self._object_color(nt)
                g = nt.nodes.new("ShaderNodeBsdfGlossy")
                g.distribution = "GGX"
                nt.links.new(info.outputs["Color"], g.inputs["Color"])
                nt.links.new(info.outputs["Alpha"], g.inputs["Roughness"])
                return g.outputs["BSDF"]
            return make_material("metal", f)
        if kind == "dielectric" and self.glass == "schlick":
            return make_material("dielectric_schlick_%g" % key[1], lambda nt: schlick_glass(nt, key[1]))
        if kind == "dielectric":
            def f(nt):
                g = nt.nodes.new("ShaderNodeBsdfGlass")
                g.distribution = "SHARP"
                g.inputs["Color"].default_value = (1, 1, 1, 1)
                g.inputs["IOR"].default_value = key[1]
                return g.outputs["BSDF"]
            return make_material("dielectric_%g" % key[1], f)
        # emitters
        r, g, b = key[1:]

        def f(nt):
            e = nt.nodes.new("ShaderNodeEmission")
            e.inputs["Color"].default_value = (r, g, b, 1.0)
            e.inputs["Strength"].default_value = 1.0
            if kind == "two_sided_light":
                return e.outputs["Emission"]
            # One-sided: the back face neither emits nor scatters (rtweekend's diffuse_light).
            geo = nt.nodes.new("ShaderNodeNewGeometry")
            black = nt.nodes.new("ShaderNodeBsdfDiffuse")
            black.inputs["Color"].default_value = (0, 0, 0, 1)
            mix = nt.nodes.new("ShaderNodeMixShader")
            nt.links.new(geo.outputs["Backfacing"], mix.inputs["Fac"])
            nt.links.new(e.outputs["Emission"], mix.inputs[1])
            nt.links.new(black.outputs["BSDF"], mix.inputs[2])
            return mix.outputs["Shader"]
        return make_material("%s_%g_%g_%g" % (kind, r, g, b), f)


# ---------------------------------------------------------------------------------------------
# Geometry


def mesh_object(name, verts, faces, mat, color, matrix=None):
    me = bpy.data.meshes.new(name)
    me.from_pydata([tuple(v) for v in verts], [], faces)
    me.materials.append(mat)
    ob = bpy.data.objects.new(name, me)
    ob.color = color
    if matrix is not None:
        ob.matrix_world = matrix
    bpy.context.scene.collection.objects.link(ob)
    return ob


class SphereBuilder:
    def __init__(self, mode, subdivisions):
        self.mode = mode
        self.meshes = {}  # material -> shared unit-sphere mesh (ico mode)
        self.subdivisions = subdivisions
        self.node_group = None
        self.ico_error = None

    def _points_group(self):
        if self.node_group is None:
            ng = bpy.data.node_groups.new("true_sphere", "GeometryNodeTree")
            ng.inputs.new("NodeSocketGeometry", "Geometry")
            ng.inputs.new("NodeSocketFloat", "Radius")
            ng.inputs.new("NodeSocketMaterial", "Material")
            ng.outputs.new("NodeSocketGeometry", "Geometry")
            gi = ng.nodes.new("NodeGroupInput")
            go = ng.nodes.new("NodeGroupOutput")
            m2p = ng.nodes.new("GeometryNodeMeshToPoints")
            sm = ng.nodes.new("GeometryNodeSetMaterial")
            ng.links.new(gi.outputs["Geometry"], m2p.inputs["Mesh"])
            ng.links.new(gi.outputs["Radius"], m2p.inputs["Radius"])
            ng.links.new(m2p.outputs["Points"], sm.inputs["Geometry"])
            ng.links.new(gi.outputs["Material"], sm.inputs["Material"])
            ng.links.new(sm.outputs["Geometry"], go.inputs["Geometry"])
            self.node_group = ng
            self.point_mesh = bpy.data.meshes.new("one_point")
            self.point_mesh.from_pydata([(0.0, 0.0, 0.0)], [], [])
            self.radius_key = ng.inputs["Radius"].identifier
            self.material_key = ng.inputs["Material"].identifier
        return self.node_group

    def _unit_ico(self, mat):
        if mat.name not in self.meshes:
            bm_mesh = bpy.data.meshes.new("ico_" + mat.name)
            bm = bmesh.new()
            bmesh.ops.create_icosphere(bm, subdivisions=self.subdivisions, radius=1.0)
            bm.to_mesh(bm_mesh)
            bm.free()
            for p in bm_mesh.polygons:
                p.use_smooth = True
            bm_mesh.materials.append(mat)
            self.meshes[mat.name] = bm_mesh
            if self.ico_error is None:
                # Deepest point of a flat face below the unit sphere: 1 - distance of its plane.
                worst = 1.0
                for p in bm_mesh.polygons:
                    a = bm_mesh.vertices[p.vertices[0]].co
                    worst = min(worst, abs(p.normal.dot(a)))
                self.ico_error = (1.0 - worst, len(bm_mesh.polygons))
        return self.meshes[mat.name]

    def add(self, name, center, radius, mat, color, refracts):
        # Cycles' point spheres are exact, but Cycles 3.4 keeps only a ray's front hit with one
        # ("always back-face culling for now", kernel/geom/point_intersect.h): a ray inside never
        # leaves through it, so a glass point sphere refracts once only. Glass spheres are
        # icospheres in the default mode ("auto").
        if self.mode == "points" or (self.mode == "auto" and not refracts):
            ng = self._points_group()
            ob = bpy.data.objects.new(name, self.point_mesh)
            ob.location = center
            ob.color = color
            md = ob.modifiers.new("true_sphere", "NODES")
            md.node_group = ng
            md[self.radius_key] = float(radius)
            md[self.material_key] = mat
        else:
            ob = bpy.data.objects.new(name, self._unit_ico(mat))
            ob.location = center
            ob.scale = (radius, radius, radius)
            ob.color = color
        bpy.context.scene.collection.objects.link(ob)
        return ob


def build_shapes(sc, mats, spheres):
    count = 0
    for i, s in enumerate(sc.shapes):
        mat, color = mats.get(s.material)
        name = "%s_%d" % (s.kind, i)
        p = s.params
        if s.kind == "sphere":
            c = s.transform @ Vector(p[:3])
            # A sphere moved by a similarity stays a sphere; its radius follows the scale.
            scale = s.transform.to_3x3().determinant() ** (1.0 / 3.0)
            spheres.add(name, c, p[3] * scale, mat, color, s.material[0] == "dielectric")
            count += 1
        elif s.kind in ("quad", "triangle"):
            q, u, v = Vector(p[0:3]), Vector(p[3:6]), Vector(p[6:9])
            pts = [q, q + u, q + u + v, q + v] if s.kind == "quad" else [q, q + u, q + v]
            if s.kind == "triangle":  # triangle: three corners a b c
                pts = [Vector(p[0:3]), Vector(p[3:6]), Vector(p[6:9])]
            pts = [s.transform @ x for x in pts]
            mesh_object(name, pts, [list(range(len(pts)))], mat, color)
        elif s.kind == "box":
            a, b = Vector(p[0:3]), Vector(p[3:6])
            lo = Vector([min(a[k], b[k]) for k in range(3)])
            hi = Vector([max(a[k], b[k]) for k in range(3)])
            verts = [Vector((hi.x if i & 1 else lo.x, hi.y if i & 2 else lo.y, hi.z if i & 4 else lo.z))
                     for i in range(8)]
            # Outward-facing quads (counter-clockwise seen from outside).
            faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
            verts = [s.transform @ x for x in verts]
            mesh_object(name, verts, faces, mat, color)
    return count


# ---------------------------------------------------------------------------------------------
# Camera, world, settings


def setup_camera(sc, width, height):
    c = sc.cam
    cam = bpy.data.cameras.new("camera")
    cam.type = "PERSP"
    cam.sensor_fit = "VERTICAL"
    cam.sensor_height = 24.0
    cam.sensor_width = 24.0 * width / height
    cam.lens = (cam.sensor_height / 2) / math.tan(math.radians(c["vfov"]) / 2)
    cam.clip_start = 1e-4 * c["focus_dist"]
    cam.clip_end = 1e7
    cam.shift_x = cam.shift_y = 0.0
    radius = c["focus_dist"] * math.tan(math.radians(c["defocus_angle"]) / 2)
    if radius > 0:
        cam.dof.use_dof = True
        cam.dof.focus_distance = c["focus_dist"]
        # Cycles: aperture radius = lens[mm] * 1e-3 / (2 fstop) (blender/camera.cpp), in scene units.
        cam.dof.aperture_fstop = cam.lens * 1e-3 / (2 * radius)
        cam.dof.aperture_blades = 0
        cam.dof.aperture_ratio = 1.0
    else:
        cam.dof.use_dof = False
    ob = bpy.data.objects.new("camera", cam)
    # Camera frame as rtweekend: w = unit(lookfrom - lookat), u = unit(vup x w), v = w x u;
    # Blender's camera looks down its -Z with +Y up, so its axes are (u, v, w).
    lf, la, up = Vector(c["lookfrom"]), Vector(c["lookat"]), Vector(c["vup"])
    w = (lf - la).normalized()
    u = up.cross(w).normalized()
    v = w.cross(u)
    m = Matrix.Identity(4)
    for r in range(3):
        m[r][0], m[r][1], m[r][2], m[r][3] = u[r], v[r], w[r], lf[r]
    ob.matrix_world = m
    bpy.context.scene.collection.objects.link(ob)
    bpy.context.scene.camera = ob
    return radius


def setup_world(sc):
    world = bpy.data.worlds.new("world")
    bpy.context.scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputWorld")
    bg = nt.nodes.new("ShaderNodeBackground")
    bg.inputs["Strength"].default_value = 1.0
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    if sc.background is not None:
        bg.inputs["Color"].default_value = tuple(sc.background) + (1.0,)
        if max(sc.background) <= 0:
            bg.inputs["Strength"].default_value = 0.0
        return "constant %g %g %g" % tuple(sc.background)
    # The book's sky: a = 0.5 (d.y + 1); colour = (1 - a) white + a (0.5, 0.7, 1.0)
    #                                            = (1, 1, 1) + a (-0.5, -0.3, 0).
    # In a world shader Cycles' Generated coordinate is the (unit) ray direction. Scene y is kept
    # as the world's y (the scene is not turned to Blender's z-up; nothing in Cycles depends on it).
    tc = nt.nodes.new("ShaderNodeTexCoord")
    sep = nt.nodes.new("ShaderNodeSeparateXYZ")
    nt.links.new(tc.outputs["Generated"], sep.inputs["Vector"])
    a = nt.nodes.new("ShaderNodeMath")
    a.operation = "MULTIPLY_ADD"
    a.use_clamp = False
    nt.links.new(sep.outputs["Y"], a.inputs[0])
    a.inputs[1].default_value = 0.5
    a.inputs[2].default_value = 0.5
    col = nt.nodes.new("ShaderNodeVectorMath")
    col.operation = "MULTIPLY_ADD"
    nt.links.new(a.outputs["Value"], col.inputs[0])  # float -> (a, a, a)
    col.inputs[1].default_value = (-0.5, -0.3, 0.0)
    col.inputs[2].default_value = (1.0, 1.0, 1.0)
    nt.links.new(col.outputs["Vector"], bg.inputs["Color"])
    return "book sky gradient"


def setup_render(args, width, height, depth):
    scene = bpy.context.scene
    r = scene.render
    r.engine = "CYCLES"
    r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    r.threads_mode = "FIXED"
    r.threads = args.threads
    r.film_transparent = False
    r.use_compositing = False
    r.use_sequencer = False
    r.use_stamp = False
    r.use_persistent_data = False
    r.use_motion_blur = False
    cy = scene.cycles
    cy.device = "CPU"
    cy.feature_set = "SUPPORTED"
    cy.samples = args.spp
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.use_preview_denoising = False
    cy.seed = args.seed
    cy.use_animated_seed = False
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    cy.film_exposure = 1.0
    cy.max_bounces = depth
    cy.diffuse_bounces = depth
    cy.glossy_bounces = depth
    cy.transmission_bounces = depth
    cy.volume_bounces = depth
    cy.transparent_max_bounces = depth
    cy.min_light_bounces = 0
    cy.min_transparent_bounces = 0
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.blur_glossy = 0.0
    cy.caustics_reflective = True
    cy.caustics_refractive = True
    cy.use_auto_tile = False
    vs = scene.view_settings
    scene.display_settings.display_device = "sRGB"
    vs.view_transform = "Standard"
    vs.look = "None"
    vs.exposure = 0.0
    vs.gamma = 1.0
    vs.use_curve_mapping = False
    im = r.image_settings
    im.file_format = "OPEN_EXR"
    im.color_depth = "32"
    im.color_mode = "RGBA"
    im.exr_codec = "NONE"


def write_pfm(path, rgba, width, height):
    # Blender's pixel rows run bottom to top, as PFM's do; drop alpha, write little-endian floats.
    rgb = array.array("f", (v for i, v in enumerate(rgba) if i % 4 != 3))
    if sys.byteorder != "little":
        rgb.byteswap()
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        rgb.tofile(f)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="cycles_scene.py", description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("-o", "--out", required=True, help="output PFM")
    ap.add_argument("--spp", type=int, default=None, help="samples per pixel (default: the file's)")
    ap.add_argument("--width", type=int, default=None, help="image width (height follows the aspect ratio)")
    ap.add_argument("--depth", type=int, default=None, help="max_depth, rays per path (default: the file's)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--spheres", choices=("auto", "points", "ico"), default="auto",
                    help="auto: point spheres, but icospheres for glass; points: all point spheres; "
                         "ico: all icospheres")
    ap.add_argument("--ico-subdivisions", type=int, default=7,
                    help="bmesh icosphere subdivisions (7: 81,920 faces)")
    ap.add_argument("--glass", choices=("exact", "schlick"), default="exact",
                    help="exact: Glass BSDF (exact Fresnel); schlick: the book's Schlick rule in nodes")
    ap.add_argument("--background-only", action="store_true", help="no shapes: the camera and background only")
    ap.add_argument("--exr", default=None, help="also keep the 32-bit EXR here")
    args = ap.parse_args(argv)

    t0 = time.perf_counter()
    sc = read_scene(args.scene)
    if args.width:
        sc.cam["image_width"] = args.width
        sc.cam["image_height"] = 0
    if args.spp is None:
        args.spp = sc.cam["samples_per_pixel"]
    depth_rays = args.depth or sc.cam["max_depth"]
    width, height = sc.cam["image_width"], sc.height()

    # Empty the factory scene.
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.materials, bpy.data.cameras, bpy.data.lights, bpy.data.worlds):
        for block in list(coll):
            coll.remove(block)

    radius = setup_camera(sc, width, height)
    sky = setup_world(sc)
    mats = Materials(args.glass)
    spheres = SphereBuilder(args.spheres, args.ico_subdivisions)
    n_spheres = 0 if args.background_only else build_shapes(sc, mats, spheres)
    setup_render(args, width, height, max(0, depth_rays - 1))
    build_s = time.perf_counter() - t0
    print("CYCLES_BUILD seconds=%.3f objects=%d spheres=%d sphere_mode=%s aperture_radius=%.6g background=%s"
          % (build_s, len(bpy.data.objects), n_spheres, args.spheres, radius, sky.replace(" ", "_")))
    if spheres.ico_error is not None:
        err, faces = spheres.ico_error
        print("CYCLES_ICO subdivisions=%d faces=%d max_radial_error_over_radius=%.3g"
              % (args.ico_subdivisions, faces, err))

    t1 = time.perf_counter()
    bpy.ops.render.render(write_still=False)
    render_s = time.perf_counter() - t1

    exr = args.exr or (os.path.splitext(args.out)[0] + ".tmp.exr")
    bpy.data.images["Render Result"].save_render(exr)
    img = bpy.data.images.load(exr)
    px = array.array("f", bytes(4 * width * height * 4))
    img.pixels.foreach_get(px)
    write_pfm(args.out, px, width, height)
    bpy.data.images.remove(img)
    if not args.exr:
        os.remove(exr)
    print("CYCLES_RESULT scene=%s width=%d height=%d spp=%d threads=%d seconds=%.4f out=%s"
          % (os.path.basename(args.scene), width, height, args.spp, args.threads, render_s, args.out))
    sys.stdout.flush()


if __name__ == "__main__":
    try:
        main()
    except SceneError as e:
        print("cycles_scene.py: error: %s" % e, file=sys.stderr)
        sys.stdout.flush()
        os._exit(2)
    except SystemExit as e:
        sys.stdout.flush()
        os._exit(e.code if isinstance(e.code, int) else 1)
    except Exception:
        import traceback
        traceback.print_exc()
        sys.stdout.flush()
        os._exit(1)
